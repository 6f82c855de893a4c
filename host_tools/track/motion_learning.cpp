// SPDX-License-Identifier: MIT
#include "motion_learning.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

extern "C" {
#include "sbr/channel.h"
#include "sbr/track.h"
#include "sbr/models.h"
}

namespace sbr_track_host {
namespace {

// The active channels (at most 3 with overlap 3) of one encoding, scaled.
struct Active {
    uint32_t n = 0;
    size_t idx[3] = {0, 0, 0};
    double w[3] = {0, 0, 0};
};

Active encode_active(const sbr_channel_config_t &cfg, float x, double scale)
{
    float enc[SBR_TRACK_MAX_VEL];
    Active a;
    if (sbr_channel_encode(&cfg, x, 1.0f, enc, SBR_TRACK_MAX_VEL) != SBR_OK) return a;
    for (uint32_t k = 0; k < cfg.count && a.n < 3; ++k) {
        if (enc[k] > 0.0f) {
            a.idx[a.n] = k;
            a.w[a.n] = enc[k] * scale;
            a.n++;
        }
    }
    return a;
}

// A Gaussian row over V channels around `centre` (channels), summing to 1.
std::vector<double> gauss_row(size_t V, double centre, double sigma)
{
    std::vector<double> g(V);
    double gs = 0;
    for (size_t k = 0; k < V; ++k) {
        const double z = (static_cast<double>(k) - centre) / sigma;
        g[k] = std::exp(-0.5 * z * z);
        gs += g[k];
    }
    for (double &v : g) v /= gs;
    return g;
}

// One triple (a, b, c) on one axis: b's region, the velocity channels a->b and b->c, and
// the axis's offset in the transition table.
struct Coded {
    Active r, v1, v2;
    size_t base;
};

// One pass of counting over every sequence, and the rows made of the counts.
class Learner {
public:
    Learner(const std::vector<Seq> &seqs, const LearnParams &p, sbr_host::TrackModel &d);
    // Counts H and B from scratch; the triples weighted by d's current transition table
    // unless `uniform`.
    void count(const std::vector<std::vector<std::vector<Det>>> &dets, bool uniform, LearnStats &stats);
    // d's transition and birth rows from the counts.
    void make_rows();

private:
    Active regions(int axis, double pos) const;
    Active velocity(double v) const { return encode_active(vc_, static_cast<float>(v), 1.0); }
    bool fits(double v) const { return v >= vlo_ && v < vhi_; }
    Coded code(int axis, const Det &a, const Det &b, const Det &c) const;
    double score(const Det &a, const Det &b, const Det &c) const;
    void add_pair(const Det &a, const Det &b, double share);
    void add_triple(const Det &a, const Det &b, const Det &c, double w);
    void count_detection(const std::vector<Det> *prev, const Det &b, const std::vector<Det> *next, bool uniform,
                         LearnStats &stats);

    const LearnParams &p_;
    sbr_host::TrackModel &d_;
    size_t V_;
    sbr_channel_config_t vc_{};
    sbr_channel_config_t rc_[2]{};
    float vlo_ = 0, vhi_ = 0;
    std::vector<double> H_, B_, birth_tail_;
};

Learner::Learner(const std::vector<Seq> &seqs, const LearnParams &p, sbr_host::TrackModel &d)
    : p_(p), d_(d), V_(p.vel_count)
{
    d.m.order = SBR_TRACK_ORDER;
    d.m.period = kPeriod;
    d.m.extent[0] = static_cast<float>(seqs.front().width);
    d.m.extent[1] = static_cast<float>(seqs.front().height);
    d.m.regions[0] = p.regions[0];
    d.m.regions[1] = p.regions[1];
    d.m.vel_count = p.vel_count;
    d.m.vel_spacing = p.vel_spacing;
    H_.assign(SBR_TRACK_MODEL_TRANSITION_LEN(p.regions[0], p.regions[1], p.vel_count), 0.0);
    B_.assign(SBR_TRACK_MODEL_BIRTH_LEN(p.regions[0], p.regions[1], p.vel_count), 0.0);
    d.trans.resize(H_.size());
    d.birth.resize(B_.size());
    vc_.first_centre = -0.5f * static_cast<float>(p.vel_count - 1) * p.vel_spacing;
    vc_.spacing = p.vel_spacing;
    vc_.count = p.vel_count;
    vc_.overlap = 3;
    sbr_channel_range(&vc_, &vlo_, &vhi_);
    // the region layout is the tracker's own (sbr_track_region_config)
    sbr_track_region_config(&d.m, 0, &rc_[0]);
    sbr_track_region_config(&d.m, 1, &rc_[1]);
    birth_tail_ = gauss_row(V_, 0.5 * static_cast<double>(V_ - 1), 6.0);
}

Active Learner::regions(int axis, double pos) const
{
    const double ext = d_.m.extent[axis];
    const float q = static_cast<float>(std::min(std::max(pos, 0.0), ext - 1e-3));
    return encode_active(rc_[axis], q, 1.0 / 1.5);  // one encoding sums to 1.5
}

Coded Learner::code(int axis, const Det &a, const Det &b, const Det &c) const
{
    Coded e;
    e.r = regions(axis, axis ? b.y : b.x);
    e.v1 = velocity(axis ? b.y - a.y : b.x - a.x);
    e.v2 = velocity(axis ? c.y - b.y : c.x - b.x);
    e.base = axis ? p_.regions[0] * V_ * V_ : 0;
    return e;
}

// The current model's probability of the triple, both axes.
double Learner::score(const Det &a, const Det &b, const Det &c) const
{
    double sc = 1.0;
    for (int axis = 0; axis < 2; ++axis) {
        const Coded e = code(axis, a, b, c);
        double t = 0;
        for (uint32_t r = 0; r < e.r.n; ++r)
            for (uint32_t j = 0; j < e.v1.n; ++j)
                for (uint32_t k = 0; k < e.v2.n; ++k)
                    t += e.r.w[r] * e.v1.w[j] * e.v2.w[k] *
                         d_.trans[e.base + (e.r.idx[r] * V_ + e.v1.idx[j]) * V_ + e.v2.idx[k]];
        sc *= t;
    }
    return sc;
}

// The velocity prior on arrival at b from a, a share of b's unit.
void Learner::add_pair(const Det &a, const Det &b, double share)
{
    for (int axis = 0; axis < 2; ++axis) {
        const Active r = regions(axis, axis ? b.y : b.x);
        const Active v = velocity(axis ? b.y - a.y : b.x - a.x);
        const size_t base = axis ? p_.regions[0] * V_ : 0;
        for (uint32_t i = 0; i < r.n; ++i)
            for (uint32_t k = 0; k < v.n; ++k) B_[base + r.idx[i] * V_ + v.idx[k]] += r.w[i] * v.w[k] / share;
    }
}

void Learner::add_triple(const Det &a, const Det &b, const Det &c, double w)
{
    for (int axis = 0; axis < 2; ++axis) {
        const Coded e = code(axis, a, b, c);
        for (uint32_t r = 0; r < e.r.n; ++r)
            for (uint32_t j = 0; j < e.v1.n; ++j)
                for (uint32_t k = 0; k < e.v2.n; ++k)
                    H_[e.base + (e.r.idx[r] * V_ + e.v1.idx[j]) * V_ + e.v2.idx[k]] +=
                        w * e.r.w[r] * e.v1.w[j] * e.v2.w[k];
    }
}

// Detection b of a frame: its pairs with the previous frame, its triples with the
// previous and the next (`next` null on the last frame).
void Learner::count_detection(const std::vector<Det> *prev, const Det &b, const std::vector<Det> *next,
                              bool uniform, LearnStats &stats)
{
    std::vector<const Det *> A;
    for (const Det &a : *prev)
        if (fits(b.x - a.x) && fits(b.y - a.y)) A.push_back(&a);
    for (const Det *a : A) {
        add_pair(*a, b, static_cast<double>(A.size()));
        stats.pairs++;
    }
    if (next == nullptr || A.empty()) return;
    std::vector<const Det *> C;
    for (const Det &c : *next)
        if (fits(c.x - b.x) && fits(c.y - b.y)) C.push_back(&c);
    if (C.empty()) return;
    std::vector<double> tw;
    double tws = 0;
    for (const Det *a : A)
        for (const Det *c : C) {
            tw.push_back(uniform ? 1.0 : score(*a, b, *c));
            tws += tw.back();
        }
    if (tws <= 0) return;
    size_t ti = 0;
    for (const Det *a : A)
        for (const Det *c : C) {
            add_triple(*a, b, *c, tw[ti++] / tws);
            stats.triples++;
        }
}

void Learner::count(const std::vector<std::vector<std::vector<Det>>> &dets, bool uniform, LearnStats &stats)
{
    std::fill(H_.begin(), H_.end(), 0.0);
    std::fill(B_.begin(), B_.end(), 0.0);
    stats = LearnStats{};
    for (const auto &D : dets) {
        for (size_t f = 1; f < D.size(); ++f) {
            const std::vector<Det> *next = f + 1 < D.size() ? &D[f + 1] : nullptr;
            for (const Det &b : D[f]) count_detection(&D[f - 1], b, next, uniform, stats);
        }
    }
}

// Transition rows: the soft counts plus the constant-velocity tail; entries below 1e-5
// are dropped (the prediction skips zeros) and the row renormalised. Birth rows: the soft
// counts plus one count of a wide prior around 0.
void Learner::make_rows()
{
    const size_t V = V_;
    for (size_t row = 0; row < H_.size() / V; ++row) {
        const std::vector<double> g = gauss_row(V, static_cast<double>(row % V), p_.tail_sigma);
        double hs = 0;
        for (size_t k = 0; k < V; ++k) hs += H_[row * V + k];
        const double a = std::max(1.0, p_.tail * hs);
        double kept = 0;
        for (size_t k = 0; k < V; ++k) {
            double v = (H_[row * V + k] + a * g[k]) / (hs + a);
            if (v < 1e-5) v = 0;
            d_.trans[row * V + k] = static_cast<float>(v);
            kept += v;
        }
        for (size_t k = 0; k < V; ++k) d_.trans[row * V + k] = static_cast<float>(d_.trans[row * V + k] / kept);
    }
    for (size_t row = 0; row < B_.size() / V; ++row) {
        double bs = 0;
        for (size_t k = 0; k < V; ++k) bs += B_[row * V + k];
        for (size_t k = 0; k < V; ++k)
            d_.birth[row * V + k] = static_cast<float>((B_[row * V + k] + birth_tail_[k]) / (bs + 1.0));
    }
}

}  // namespace

sbr_host::TrackModel learn_motion_model(const std::vector<Seq> &seqs,
                                        const std::vector<std::vector<std::vector<Det>>> &dets,
                                        const LearnParams &p, LearnStats &stats)
{
    sbr_host::TrackModel d;
    Learner l(seqs, p, d);
    for (int iter = 0; iter < p.em_iters; ++iter) {
        l.count(dets, iter == 0, stats);
        l.make_rows();
    }
    d.bind();
    return d;
}

std::string write_model_c(const sbr_host::TrackModel &d, const std::string &path, const std::string &header)
{
    std::ofstream out(path);
    if (!out) return "cannot write " + path;
    out << "/* SPDX-License-Identifier: MIT */\n/*\n * Motion model of sbr's channel tracker. GENERATED by sbr_train_track - do not edit.\n"
        << header << " */\n#include \"sbr/models.h\"\n\n";
    out << "sbr_status_t sbr_track_model_kitti(sbr_track_model_t *out)\n{\n";
    auto table = [&](const char *name, const std::vector<float> &t) {
        out << "    static const float " << name << "[" << t.size() << "] = {\n";
        char buf[32];
        for (size_t i = 0; i < t.size(); ++i) {
            if (t[i] == 0.0f) std::snprintf(buf, sizeof buf, "0.0f");
            else std::snprintf(buf, sizeof buf, "%.9ef", static_cast<double>(t[i]));
            out << (i % d.m.vel_count == 0 ? "        " : " ") << buf << ",";
            if ((i + 1) % d.m.vel_count == 0) out << "\n";
        }
        out << "    };\n";
    };
    table("track_transition", d.trans);
    table("track_birth", d.birth);
    char buf[64];
    out << "    sbr_status_t st = SBR_OK;\n    if (out == NULL) {\n        st = SBR_ERR_NULL;\n"
        << "    } else {\n        out->order = " << d.m.order << "u;\n";
    std::snprintf(buf, sizeof buf, "%.9ef", static_cast<double>(d.m.period));
    out << "        out->period = " << buf << ";\n";
    std::snprintf(buf, sizeof buf, "%.9ef", static_cast<double>(d.m.extent[0]));
    out << "        out->extent[0] = " << buf << ";\n";
    std::snprintf(buf, sizeof buf, "%.9ef", static_cast<double>(d.m.extent[1]));
    out << "        out->extent[1] = " << buf << ";\n";
    out << "        out->regions[0] = " << d.m.regions[0] << "u;\n        out->regions[1] = " << d.m.regions[1]
        << "u;\n        out->vel_count = " << d.m.vel_count << "u;\n";
    std::snprintf(buf, sizeof buf, "%.9ef", static_cast<double>(d.m.vel_spacing));
    out << "        out->vel_spacing = " << buf << ";\n"
        << "        out->transition = track_transition;\n        out->birth = track_birth;\n"
        << "    }\n    return st;\n}\n";
    return out ? "" : "write failed: " + path;
}

}  // namespace sbr_track_host
