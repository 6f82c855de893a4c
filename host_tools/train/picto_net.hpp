// SPDX-License-Identifier: MIT
// sbr_train_picto's network trainer: one layer of rectified units, a softmax over the 43
// classes and "no sign", and the box outputs, trained by minibatch SGD (deterministic).
#pragma once
#include <string>
#include <vector>

#include "picto_train.hpp"

namespace sbr_host::picto_train {

// The network in training form.
struct Net {
    int h = 0;
    std::vector<float> w1, w2, w3;  // h x (F+1), K x (nin+1), 4 x (nin+1)
    int nin() const { return h > 0 ? h : kF; }
};

// Minibatch SGD with momentum and cosine decay. Each epoch sees every sign sample and a
// fresh `bg_fraction` of the background ones (weighted up to match). Two threads share
// each minibatch and their gradients are added in a fixed order: deterministic.
void train(Net &n, const std::vector<Sample> &s, const std::vector<float> &sw, int epochs, unsigned seed, float lr0,
           float bg_fraction, float rate, float decay);

// The library trainer (--trainer sklearn): the samples and their weights go to a file, the
// Python script (picto_fit.py: scikit-learn's MLPClassifier for the classifier, a ridge
// regression on its hidden units for the box outputs) fits them and writes the weights in
// Net's layout. False, with the reason printed, when it cannot run or its file is wrong.
struct LibraryFit {
    std::string python, script, args;  // interpreter, picto_fit.py, --trainer-args
    int hidden = 128, epochs = 20;
    unsigned seed = 1;
    float bg_fraction = 0.3f;
};
bool train_library(Net &n, const std::vector<Sample> &s, const std::vector<float> &sw, const LibraryFit &lf);

}  // namespace sbr_host::picto_train
