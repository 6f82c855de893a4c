// SPDX-License-Identifier: MIT
// The colour check's floors and the gate of the class stage (picto_checks.hpp).
#include "picto_checks.hpp"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <random>

#include "parallel.hpp"

namespace sbr_host::picto_train {

// --rim-check: the floor of a class's rim contrast, the kRimQuantile quantile of its
// training signs' contrasts at their annotated boxes (a few of a class's signs are
// faded or backlit: the floor lets them pass). A class with fewer than 5 training signs
// goes unchecked; with no class checked the classifier has no tables.
constexpr double kRimQuantile = 0.03;
bool learn_rim_floors(const std::vector<std::string> &files, const std::map<int, std::vector<GtBox>> &gt,
                      const std::vector<int> &classes, Picto &out) {
    std::map<int, std::vector<float>> seen;
    for (const auto &file : files) {
        const int num = image_number(file);
        if (!gt.count(num)) continue;
        cv::Mat img;
        for (const auto &g : gt.at(num)) {
            if (std::find(classes.begin(), classes.end(), g.class_id) == classes.end()) continue;
            if (img.empty()) img = cv::imread(file, cv::IMREAD_COLOR);
            if (img.empty()) break;
            const sbr_image_t v = bgr_view(img);
            const PixBox b = gt_pixbox(g);
            const float box[4] = {float(b.x0), float(b.y0), float(b.x1), float(b.y1)};
            float c = 0.0f;
            if (sbr_picto_rim_contrast(&v, box, uint32_t(class_outline_of(g.class_id)), &c) == SBR_OK)
                seen[g.class_id].push_back(c);
        }
    }
    out.rim_shape.assign(kGtsdbClasses, uint8_t(SBR_PICTO_RIM_NONE));
    out.rim_floor.assign(kGtsdbClasses, -2.0f);
    for (int c : classes) {
        auto &v = seen[c];
        if (v.size() < 5) {
            // a floor from so few signs would say nothing: that class goes unchecked
            std::fprintf(stderr, "sbr_train_picto: --rim-check %d: %zu training signs, too few for a floor: no colour check for it\n",
                         c, v.size());
            continue;
        }
        std::sort(v.begin(), v.end());
        out.rim_shape[size_t(c)] = class_outline_of(c);
        out.rim_floor[size_t(c)] = v[size_t(kRimQuantile * double(v.size()))];
        std::fprintf(stderr, "sbr_train_picto: colour check of class %d: rim contrast floor %.4f (%zu signs, median %.4f)\n",
                     c, double(out.rim_floor[size_t(c)]), v.size(), double(v[v.size() / 2]));
    }
    if (std::all_of(out.rim_shape.begin(), out.rim_shape.end(), [](uint8_t k) { return k == SBR_PICTO_RIM_NONE; })) {
        out.rim_shape.clear();  // no class checked: no tables
        out.rim_floor.clear();
    }
    out.bind();
    return true;
}

namespace {

// --gate: the class stage's gate (picto.h sbr_picto_model_t::gate), learned on the
// candidates the class stage sees on the training images: the recogniser's default part
// stage (no class stage, every hypothesis, best part score first, the first
// max_candidates). A candidate is a positive when it covers a sign (IoU >= 0.3) or when
// the trained class stage `out` finds it at least kGateMass sign-like at its first look
// (what the recogniser's refinement and extra views start from); the others are
// negatives. (Also counting candidates the box regression moves onto a sign as positives
// lost one sign more on the cross-validation: docs/results/realtime.md.) The gate: one
// layer of `hidden` rectified units (0: logistic regression) on the standardised gate
// features, positives weighted up to the negatives' count, minibatch SGD with a fixed
// seed, the standardisation folded back into the first layer; the threshold passes
// `recall` of the positives.
constexpr float kGateMass = 0.0003f;
constexpr int kGF = int(SBR_PICTO_GATE_FEATURES);


// The gate's samples (f: the gate features, label: 1 positive, 0 negative) of the class
// stage's candidates on the images, in a deterministic order.
std::vector<Sample> gate_samples(const std::vector<std::string> &files, const std::map<int, std::vector<GtBox>> &gt,
                                 const sbr_model_t &model, const Picto &out) {
    std::vector<Sample> samples;
    std::mutex mu;
    sbr_recog_config_t rc;  // the class stage's candidates: every hypothesis, no floor
    sbr_recog_config_default(&rc);
    rc.min_score = 0.0f;
    rc.nms_iou = 1.0f;
    // the blue map's regions from 40 of its pixels, as the committed gate was learned (the
    // recogniser's default took 20 after it; docs/results/crossval.md)
    rc.parts.map_min_area[SBR_MAP_BLUE] = 40u;
    struct Worker {
        std::vector<uint64_t> ws;
        std::vector<float> f, g = std::vector<float>(kGF);
        float prob[kK];
    };
    parallel_for<Worker>(files.size(), 4u, [&](size_t i, Worker &wk) {
        alignas(8) static thread_local float pws[SBR_PICTO_WORKSPACE_SIZE / sizeof(float) + 1];
        std::vector<float> &f = wk.f, &g = wk.g;
        cv::Mat img = cv::imread(files[i], cv::IMREAD_COLOR);
        if (img.empty()) return;
        const sbr_image_t v = bgr_view(img);
        const int num = image_number(files[i]);
        std::vector<Box> boxes = recog_boxes(v, rc, model, nullptr, wk.ws);
        if (boxes.size() > rc.max_candidates) boxes.resize(rc.max_candidates);
        std::vector<Sample> local;
        for (const Box &b : boxes) {
            const float box[4] = {float(b.x0), float(b.y0), float(b.x1), float(b.y1)};
            if (sbr_picto_gate_features(&v, box, g.data(), uint32_t(kGF), pws, sizeof pws) != SBR_OK) continue;
            // positive: it covers a sign, or the class stage finds it sign-like at its
            // first look
            int label = 0;
            if (gt.count(num))
                for (const auto &t : gt.at(num))
                    if (box_iou(b, gt_pixbox(t)) >= 0.3) label = 1;
            if (label == 0 && features(v, b, f) &&
                sbr_picto_classify(&out.view, f.data(), uint32_t(kF), wk.prob, uint32_t(kK), pws, sizeof pws) ==
                    SBR_OK &&
                1.0f - wk.prob[kBackground] >= kGateMass)
                label = 1;
            local.push_back({g, label});
        }
        std::lock_guard<std::mutex> lock(mu);
        for (auto &smp : local) samples.push_back(std::move(smp));
    });
    sort_samples(samples);  // a deterministic order, whatever order the threads collected them in
    return samples;
}

// The gate's training set: features, labels and the features' mean and deviation.
struct GateData {
    std::vector<std::vector<float>> xs;
    std::vector<int> ys;
    std::vector<double> mean, sd;
};

GateData gate_data(std::vector<Sample> &samples) {
    GateData d;
    for (auto &smp : samples) {
        d.xs.push_back(std::move(smp.f));
        d.ys.push_back(smp.label);
    }
    d.mean.assign(kGF, 0.0);
    d.sd.assign(kGF, 0.0);
    for (const auto &x : d.xs)
        for (int j = 0; j < kGF; ++j) d.mean[j] += x[j];
    for (auto &m : d.mean) m /= double(d.xs.size());
    for (const auto &x : d.xs)
        for (int j = 0; j < kGF; ++j) d.sd[j] += (x[j] - d.mean[j]) * (x[j] - d.mean[j]);
    for (auto &v : d.sd) v = std::sqrt(v / double(d.xs.size())) + 1e-6;
    return d;
}

// The gate's weights (SBR_PICTO_GATE_WEIGHTS(H) of them, on the standardised features):
// one layer of H rectified units (0: logistic regression), positives weighted by wpos,
// 30 epochs of minibatch SGD with momentum from a fixed seed.
std::vector<float> fit_gate(const GateData &gd, int H, unsigned seed, float wpos) {
    const std::vector<std::vector<float>> &xs = gd.xs;
    const std::vector<int> &ys = gd.ys;
    const std::vector<double> &mean = gd.mean, &sd = gd.sd;
    std::vector<size_t> order(xs.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    const size_t nw = SBR_PICTO_GATE_WEIGHTS(uint32_t(H));
    std::vector<float> w(nw, 0.0f), vel(nw, 0.0f), grad(nw);
    std::mt19937 rng(seed);
    {
        std::normal_distribution<float> N(0.0f, std::sqrt(2.0f / float(kGF)));
        if (H > 0) {
            for (int r = 0; r < H; ++r)
                for (int j = 0; j < kGF; ++j) w[size_t(r) * (kGF + 1) + size_t(j)] = N(rng);
            std::normal_distribution<float> N2(0.0f, std::sqrt(1.0f / float(H)));
            for (int r = 0; r < H; ++r) w[size_t(H) * (kGF + 1) + size_t(r)] = N2(rng);
        }
    }
    const int epochs = 30;
    const size_t batch = 256;
    std::vector<float> z(kGF), a(size_t(std::max(H, 1)));
    auto score_of = [&](const std::vector<float> &zz) {
        if (H == 0) {
            float v = w[kGF];
            for (int j = 0; j < kGF; ++j) v += w[size_t(j)] * zz[size_t(j)];
            return v;
        }
        const float *w2 = &w[size_t(H) * (kGF + 1)];
        float v = w2[H];
        for (int r = 0; r < H; ++r) {
            const float *row = &w[size_t(r) * (kGF + 1)];
            float t = row[kGF];
            for (int j = 0; j < kGF; ++j) t += row[j] * zz[size_t(j)];
            a[size_t(r)] = t > 0.0f ? t : 0.0f;
            v += w2[r] * a[size_t(r)];
        }
        return v;
    };
    for (int e = 0; e < epochs; ++e) {
        std::shuffle(order.begin(), order.end(), rng);
        const float lr = 0.05f * (1.0f - float(e) / float(epochs)) + 0.002f;
        for (size_t b0 = 0; b0 < order.size(); b0 += batch) {
            std::fill(grad.begin(), grad.end(), 0.0f);
            float wsum = 0.0f;
            for (size_t k = b0; k < std::min(order.size(), b0 + batch); ++k) {
                const auto &x = xs[order[k]];
                for (int j = 0; j < kGF; ++j) z[size_t(j)] = float((x[size_t(j)] - mean[size_t(j)]) / sd[size_t(j)]);
                const float sc = score_of(z);
                const float p = 1.0f / (1.0f + std::exp(-std::max(-30.0f, std::min(30.0f, sc))));
                const float sw = ys[order[k]] ? wpos : 1.0f;
                const float d = sw * (p - float(ys[order[k]]));
                wsum += sw;
                if (H == 0) {
                    for (int j = 0; j < kGF; ++j) grad[size_t(j)] += d * z[size_t(j)];
                    grad[kGF] += d;
                    continue;
                }
                float *g2 = &grad[size_t(H) * (kGF + 1)];
                const float *w2 = &w[size_t(H) * (kGF + 1)];
                for (int r = 0; r < H; ++r) {
                    g2[r] += d * a[size_t(r)];
                    if (a[size_t(r)] <= 0.0f) continue;
                    const float dr = d * w2[r];
                    float *gr = &grad[size_t(r) * (kGF + 1)];
                    for (int j = 0; j < kGF; ++j) gr[j] += dr * z[size_t(j)];
                    gr[kGF] += dr;
                }
                g2[H] += d;
            }
            for (size_t j = 0; j < nw; ++j) {
                const float gj = grad[j] / wsum + 1e-4f * w[j];
                vel[j] = 0.9f * vel[j] - lr * gj;
                w[j] += vel[j];
            }
        }
    }
    return w;
}

// Sets out's gate to the weights w (standardised features, H hidden units), the
// standardisation folded into the first layer, its threshold passing `recall` of the
// positives; prints what it passes and rejects.
void set_gate(const GateData &gd, const std::vector<float> &w, int H, float recall, Picto &out) {
    const std::vector<std::vector<float>> &xs = gd.xs;
    const std::vector<int> &ys = gd.ys;
    const std::vector<double> &mean = gd.mean, &sd = gd.sd;
    const size_t npos = size_t(std::count(ys.begin(), ys.end(), 1)), nneg = ys.size() - npos;
    // fold the standardisation into the first layer
    out.gate = w;
    out.gate_hidden = uint32_t(H);
    const int rows = H == 0 ? 1 : H;
    for (int r = 0; r < rows; ++r) {
        float *row = &out.gate[size_t(r) * (kGF + 1)];
        double bias = row[kGF];
        for (int j = 0; j < kGF; ++j) {
            bias -= double(row[j]) * mean[size_t(j)] / sd[size_t(j)];
            row[j] = float(double(row[j]) / sd[size_t(j)]);
        }
        row[kGF] = float(bias);
    }
    out.gate_threshold = 0.0f;
    out.bind();
    std::vector<float> pos, neg;
    for (size_t i = 0; i < xs.size(); ++i) {
        float sc = 0.0f;
        sbr_picto_gate(&out.view, xs[i].data(), uint32_t(kGF), &sc);
        (ys[i] ? pos : neg).push_back(sc);
    }
    std::sort(pos.begin(), pos.end());
    out.gate_threshold = pos[size_t(double(1.0f - recall) * double(pos.size()))];
    out.bind();
    const size_t rejected = size_t(std::count_if(neg.begin(), neg.end(), [&](float v) { return v < out.gate_threshold; }));
    const size_t kept = size_t(std::count_if(pos.begin(), pos.end(), [&](float v) { return v >= out.gate_threshold; }));
    std::fprintf(stderr,
                 "sbr_train_picto: gate: %zu candidates (%zu positive), threshold %.4f: %zu of %zu positives pass (%.4f), "
                 "%zu of %zu negatives rejected (%.4f)\n",
                 xs.size(), npos, double(out.gate_threshold), kept, npos, double(kept) / double(npos), rejected, nneg,
                 double(rejected) / double(nneg));
}

}  // namespace

bool learn_gate(const std::vector<std::string> &files, const std::map<int, std::vector<GtBox>> &gt,
                const sbr_model_t &model, Picto &out, float recall, int hidden, unsigned seed) {
    std::vector<Sample> samples = gate_samples(files, gt, model, out);
    const GateData d = gate_data(samples);
    const size_t npos = size_t(std::count(d.ys.begin(), d.ys.end(), 1)), nneg = d.ys.size() - npos;
    if (npos < 10 || nneg < 10) {
        std::fprintf(stderr, "sbr_train_picto: --gate: %zu positive and %zu negative candidates, too few\n", npos, nneg);
        return false;
    }
    const float wpos = float(std::min(50.0, double(nneg) / double(npos)));
    set_gate(d, fit_gate(d, hidden, seed, wpos), hidden, recall, out);
    return true;
}

}  // namespace sbr_host::picto_train
