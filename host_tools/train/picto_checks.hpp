// SPDX-License-Identifier: MIT
// What sbr_train_picto learns after the class stage's network: the colour check's floors
// (--rim-check) and the gate, the class stage's cheap first look (--gate).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "picto_train.hpp"

namespace sbr_host::picto_train {

// --rim-check: for each class of `classes`, the floor of its rim contrast (picto.h
// sbr_picto_rim_contrast()), the 3 % quantile of its training signs' contrasts at their
// annotated boxes, into out's tables (a class with fewer than 5 training signs goes
// unchecked; with no class checked the class stage has no tables).
bool learn_rim_floors(const std::vector<std::string> &files, const std::map<int, std::vector<GtBox>> &gt,
                      const std::vector<int> &classes, Picto &out);

// --gate: the class stage's gate (picto.h sbr_picto_model_t::gate) with `hidden`
// rectified units, learned on the candidates of the images `files` and set to pass
// `recall` of the positive ones; into out. False (reason printed) when too few candidates.
bool learn_gate(const std::vector<std::string> &files, const std::map<int, std::vector<GtBox>> &gt,
                const sbr_model_t &model, Picto &out, float recall, int hidden, unsigned seed);

}  // namespace sbr_host::picto_train
