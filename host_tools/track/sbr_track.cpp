// sbr_track: paper E's channel tracker on KITTI tracking ground truth, against a
// constant-velocity Kalman filter with Hungarian association and a bootstrap particle
// filter, all three on the very same corrupted detections; and the learning of the
// tracker's motion model from detections without track ids.
//
// Detections (documented corruption, seeded): every labelled object of the chosen classes
// (default Car and Cyclist) in every frame is dropped with probability --miss, else its
// box centre gets Gaussian noise of --noise px per axis (clamped into the image); then a
// Poisson number (mean --clutter) of clutter detections uniform over the image is added.
// The detections of a frame are shuffled, so their order says nothing about identity.
//
// Track management is the same for the three methods: every unassigned detection starts
// a tentative track, confirmed by its second hit; a tentative track dies at its first
// miss, a confirmed one after more than 5 consecutive misses or when its estimate leaves
// the image. A confirmed track is reported in a frame if it has missed at most 2 frames
// in a row. Gate: normalised distance <= 4 standard deviations (sum over both axes).
//
// Scoring (CLEAR-MOT): in every frame, ground-truth objects of the chosen classes and
// reported tracks are matched if their centres are at most 20 px apart; correspondences
// of the previous frame are kept while valid, the rest by the Hungarian method on the
// distance. MOTA = 1 - (misses + false positives + id switches) / ground-truth objects;
// RMSE is the root mean square centre distance over matched pairs.
#include "cli_core.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

extern "C" {
#include "sbr/channel.h"
#include "sbr/tracker.h"
}

#include "track_model_io.hpp"

namespace {

constexpr double kMatchPx = 20.0;
constexpr unsigned kConfirmHits = 2;
constexpr unsigned kMaxMisses = 5;
constexpr unsigned kReportMisses = 2;
constexpr double kGate = 4.0;
constexpr float kPeriod = 0.1f;  // KITTI: 10 frames per second
constexpr uint32_t kPeriodUs = 100000u;  // the same in microseconds (sbr_track_step())
double g_tail = 0.01;       // share of a learned row given to the wide constant-velocity tail
double g_tail_sigma = 2.0;  // its standard deviation, velocity channels
size_t g_workspace_bytes = 0;
int g_em_iters = 3;         // passes of the soft association EM in learning

struct Obj {
    int id;
    std::string type;
    double cx, cy, w, h;
};

struct Seq {
    std::string name;
    int frames = 0;
    double width = 1242.0, height = 375.0;
    std::vector<std::vector<Obj>> gt;  // per frame
};

struct Det {
    double x, y, w, h;
    std::string type;
};

struct Hyp {
    unsigned id;
    double x, y, w, h;
    std::string type;
};

std::vector<std::string> split(const std::string &s, char c)
{
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, c)) {
        if (!item.empty()) out.push_back(item);
    }
    return out;
}

std::vector<std::string> parse_seqs(const std::string &s)
{
    std::vector<std::string> out;
    for (const auto &part : split(s, ',')) {
        const auto dash = part.find('-');
        if (dash == std::string::npos) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "%04d", std::atoi(part.c_str()));
            out.emplace_back(buf);
        } else {
            const int a = std::atoi(part.substr(0, dash).c_str());
            const int b = std::atoi(part.substr(dash + 1).c_str());
            for (int i = a; i <= b; ++i) {
                char buf[8];
                std::snprintf(buf, sizeof buf, "%04d", i);
                out.emplace_back(buf);
            }
        }
    }
    return out;
}

bool load_seq(const std::string &dir, const std::string &name, const std::set<std::string> &classes,
              Seq &seq)
{
    std::ifstream in(dir + "/" + name + ".txt");
    if (!in) return false;
    seq.name = name;
    std::string line;
    std::vector<std::pair<int, Obj>> all;
    int maxf = -1;
    while (std::getline(in, line)) {
        std::istringstream ls(line);
        int frame, id, trunc, occ;
        std::string type;
        double alpha, l, t, r, b;
        if (!(ls >> frame >> id >> type >> trunc >> occ >> alpha >> l >> t >> r >> b)) continue;
        maxf = std::max(maxf, frame);
        if (!classes.count(type)) continue;
        all.push_back({frame, Obj{id, type, 0.5 * (l + r), 0.5 * (t + b), r - l, b - t}});
    }
    // frame count: the official sequence map when it is beside the labels, else the labels
    int frames = maxf + 1;
    std::ifstream map(dir + "/../evaluate_tracking.seqmap.training");
    std::string ms, dummy, f0, f1;
    while (map >> ms >> dummy >> f0 >> f1) {
        if (ms == name) frames = std::atoi(f1.c_str());
    }
    seq.frames = frames;
    seq.gt.assign(static_cast<size_t>(frames), {});
    for (auto &p : all) {
        if (p.first < frames) seq.gt[static_cast<size_t>(p.first)].push_back(p.second);
    }
    return true;
}

// The documented corruption. One generator per (seed, sequence).
std::vector<std::vector<Det>> corrupt(const Seq &seq, double noise, double miss, double clutter,
                                      unsigned seed)
{
    std::mt19937 rng(seed * 7919u + static_cast<unsigned>(std::atoi(seq.name.c_str())));
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    std::poisson_distribution<int> pois(clutter > 0.0 ? clutter : 1.0);
    std::vector<std::vector<Det>> out(seq.gt.size());
    for (size_t f = 0; f < seq.gt.size(); ++f) {
        for (const auto &o : seq.gt[f]) {
            if (uni(rng) < miss) continue;
            Det d{o.cx + noise * gauss(rng), o.cy + noise * gauss(rng), o.w, o.h, o.type};
            d.x = std::min(std::max(d.x, 0.0), seq.width - 0.01);
            d.y = std::min(std::max(d.y, 0.0), seq.height - 0.01);
            out[f].push_back(d);
        }
        const int nc = clutter > 0.0 ? pois(rng) : 0;
        for (int i = 0; i < nc; ++i) {
            Det d{uni(rng) * (seq.width - 0.01), uni(rng) * (seq.height - 0.01), 60.0, 45.0, "Car"};
            out[f].push_back(d);
        }
        std::shuffle(out[f].begin(), out[f].end(), rng);
    }
    return out;
}

// ---- Hungarian method (square, minimisation) ------------------------------------------

std::vector<int> hungarian(const std::vector<std::vector<double>> &cost_in, size_t rows, size_t cols)
{
    const size_t n = std::max(rows, cols);
    const double big = 1e9;
    std::vector<std::vector<double>> a(n + 1, std::vector<double>(n + 1, big));
    for (size_t i = 0; i < rows; ++i)
        for (size_t j = 0; j < cols; ++j) a[i + 1][j + 1] = cost_in[i][j];
    for (size_t i = rows; i < n; ++i)
        for (size_t j = 0; j < n; ++j) a[i + 1][j + 1] = 0.0;
    for (size_t i = 0; i < rows; ++i)
        for (size_t j = cols; j < n; ++j) a[i + 1][j + 1] = big;
    std::vector<double> u(n + 1, 0.0), v(n + 1, 0.0);
    std::vector<size_t> p(n + 1, 0), way(n + 1, 0);
    for (size_t i = 1; i <= n; ++i) {
        p[0] = i;
        size_t j0 = 0;
        std::vector<double> minv(n + 1, std::numeric_limits<double>::infinity());
        std::vector<char> used(n + 1, 0);
        do {
            used[j0] = 1;
            const size_t i0 = p[j0];
            double delta = std::numeric_limits<double>::infinity();
            size_t j1 = 0;
            for (size_t j = 1; j <= n; ++j) {
                if (!used[j]) {
                    const double cur = a[i0][j] - u[i0] - v[j];
                    if (cur < minv[j]) {
                        minv[j] = cur;
                        way[j] = j0;
                    }
                    if (minv[j] < delta) {
                        delta = minv[j];
                        j1 = j;
                    }
                }
            }
            for (size_t j = 0; j <= n; ++j) {
                if (used[j]) {
                    u[p[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
        } while (p[j0] != 0);
        do {
            const size_t j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
        } while (j0);
    }
    std::vector<int> assign(rows, -1);
    for (size_t j = 1; j <= n; ++j) {
        if (p[j] >= 1 && p[j] <= rows && j <= cols) assign[p[j] - 1] = static_cast<int>(j - 1);
    }
    return assign;
}

// ---- baselines: common track management around a per-track filter ----------------------

struct Gauss2 {
    double mx, my, sxx, sxy, syy;  // predicted measurement mean and covariance (with R)
};

struct KfTrack {
    double x[4];
    double P[4][4];
};

struct PfTrack {
    std::vector<double> p;  // particles: x y vx vy, interleaved
    std::vector<double> w;
};

template <class F>
struct Baseline {
    struct T {
        unsigned id;
        unsigned hits = 1, misses = 0;
        bool confirmed = false;
        double w = 0, h = 0;
        std::string type;
        F f;
    };
    std::vector<T> tracks;
    unsigned next_id = 1;
};

struct KfOps {
    double accel, r, vel0;
    void birth(KfTrack &t, const Det &d, std::mt19937 &) const
    {
        std::memset(&t, 0, sizeof t);
        t.x[0] = d.x;
        t.x[1] = d.y;
        t.P[0][0] = t.P[1][1] = r * r;
        t.P[2][2] = t.P[3][3] = vel0 * vel0;
    }
    void predict(KfTrack &t, double ratio, std::mt19937 &) const
    {
        // x' = F x, P' = F P F^T + Q (white-noise acceleration, per period)
        double F[4][4] = {{1, 0, ratio, 0}, {0, 1, 0, ratio}, {0, 0, 1, 0}, {0, 0, 0, 1}};
        double nx[4] = {0, 0, 0, 0};
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) nx[i] += F[i][j] * t.x[j];
        std::memcpy(t.x, nx, sizeof nx);
        double FP[4][4] = {}, P2[4][4] = {};
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                for (int k = 0; k < 4; ++k) FP[i][j] += F[i][k] * t.P[k][j];
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                for (int k = 0; k < 4; ++k) P2[i][j] += FP[i][k] * F[j][k];
        const double q = accel * accel;
        const double dt = ratio;
        for (int a = 0; a < 2; ++a) {
            P2[a][a] += q * dt * dt * dt * dt / 4.0;
            P2[a][a + 2] += q * dt * dt * dt / 2.0;
            P2[a + 2][a] += q * dt * dt * dt / 2.0;
            P2[a + 2][a + 2] += q * dt * dt;
        }
        std::memcpy(t.P, P2, sizeof P2);
    }
    Gauss2 predicted(const KfTrack &t) const
    {
        return Gauss2{t.x[0], t.x[1], t.P[0][0] + r * r, t.P[0][1], t.P[1][1] + r * r};
    }
    void update(KfTrack &t, const Det &d, std::mt19937 &) const
    {
        const double S[2][2] = {{t.P[0][0] + r * r, t.P[0][1]}, {t.P[1][0], t.P[1][1] + r * r}};
        const double det = S[0][0] * S[1][1] - S[0][1] * S[1][0];
        const double Si[2][2] = {{S[1][1] / det, -S[0][1] / det}, {-S[1][0] / det, S[0][0] / det}};
        double K[4][2];
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 2; ++j) K[i][j] = t.P[i][0] * Si[0][j] + t.P[i][1] * Si[1][j];
        const double y0 = d.x - t.x[0], y1 = d.y - t.x[1];
        for (int i = 0; i < 4; ++i) t.x[i] += K[i][0] * y0 + K[i][1] * y1;
        double P2[4][4];
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) P2[i][j] = t.P[i][j] - (K[i][0] * t.P[0][j] + K[i][1] * t.P[1][j]);
        std::memcpy(t.P, P2, sizeof P2);
    }
    void estimate(const KfTrack &t, double &x, double &y) const
    {
        x = t.x[0];
        y = t.x[1];
    }
};

struct PfOps {
    double accel, r, vel0;
    unsigned n;
    void birth(PfTrack &t, const Det &d, std::mt19937 &rng) const
    {
        std::normal_distribution<double> g(0.0, 1.0);
        t.p.resize(4u * n);
        t.w.assign(n, 1.0 / n);
        for (unsigned i = 0; i < n; ++i) {
            t.p[4 * i + 0] = d.x + r * g(rng);
            t.p[4 * i + 1] = d.y + r * g(rng);
            t.p[4 * i + 2] = vel0 * g(rng);
            t.p[4 * i + 3] = vel0 * g(rng);
        }
    }
    void predict(PfTrack &t, double ratio, std::mt19937 &rng) const
    {
        std::normal_distribution<double> g(0.0, 1.0);
        for (unsigned i = 0; i < n; ++i) {
            double *s = &t.p[4 * i];
            const double ax = accel * g(rng), ay = accel * g(rng);
            s[0] += s[2] * ratio + 0.5 * ax * ratio * ratio;
            s[1] += s[3] * ratio + 0.5 * ay * ratio * ratio;
            s[2] += ax * ratio;
            s[3] += ay * ratio;
        }
    }
    Gauss2 predicted(const PfTrack &t) const
    {
        double mx, my, sw = 0;
        estimate(t, mx, my);
        for (unsigned i = 0; i < n; ++i) sw += t.w[i];
        double sxx = 0, sxy = 0, syy = 0;
        for (unsigned i = 0; i < n; ++i) {
            const double dx = t.p[4 * i] - mx, dy = t.p[4 * i + 1] - my;
            sxx += t.w[i] * dx * dx;
            sxy += t.w[i] * dx * dy;
            syy += t.w[i] * dy * dy;
        }
        return Gauss2{mx, my, sxx / sw + r * r, sxy / sw, syy / sw + r * r};
    }
    void update(PfTrack &t, const Det &d, std::mt19937 &rng) const
    {
        double sw = 0;
        for (unsigned i = 0; i < n; ++i) {
            const double dx = t.p[4 * i] - d.x, dy = t.p[4 * i + 1] - d.y;
            t.w[i] = std::exp(-0.5 * (dx * dx + dy * dy) / (r * r));
            sw += t.w[i];
        }
        if (sw <= 1e-300) {
            t.w.assign(n, 1.0 / n);
            return;
        }
        for (auto &w : t.w) w /= sw;
        // estimate before resampling is the weighted mean; systematic resampling
        std::uniform_real_distribution<double> u(0.0, 1.0 / n);
        std::vector<double> np(t.p.size());
        double c = t.w[0], pos = u(rng);
        unsigned j = 0;
        for (unsigned i = 0; i < n; ++i) {
            while (pos > c && j + 1 < n) c += t.w[++j];
            std::memcpy(&np[4 * i], &t.p[4 * j], 4 * sizeof(double));
            pos += 1.0 / n;
        }
        t.p.swap(np);
        t.w.assign(n, 1.0 / n);
    }
    void estimate(const PfTrack &t, double &x, double &y) const
    {
        double sw = 0;
        x = y = 0;
        for (unsigned i = 0; i < n; ++i) {
            x += t.w[i] * t.p[4 * i];
            y += t.w[i] * t.p[4 * i + 1];
            sw += t.w[i];
        }
        x /= sw;
        y /= sw;
    }
};

template <class F, class Ops>
std::vector<Hyp> baseline_step(Baseline<F> &b, const Ops &ops, const std::vector<Det> &dets,
                               double ratio, double width, double height, std::mt19937 &rng)
{
    for (auto &t : b.tracks) ops.predict(t.f, ratio, rng);
    // association: confirmed tracks first, then tentative ones, Hungarian on the
    // normalised squared distance, gated
    std::vector<int> det_of(b.tracks.size(), -1);
    std::vector<char> used(dets.size(), 0);
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<size_t> rows;
        for (size_t i = 0; i < b.tracks.size(); ++i)
            if (b.tracks[i].confirmed == (pass == 0)) rows.push_back(i);
        std::vector<size_t> cols;
        for (size_t j = 0; j < dets.size(); ++j)
            if (!used[j]) cols.push_back(j);
        if (rows.empty() || cols.empty()) continue;
        std::vector<std::vector<double>> cost(rows.size(), std::vector<double>(cols.size(), 1e6));
        for (size_t a = 0; a < rows.size(); ++a) {
            const Gauss2 g = ops.predicted(b.tracks[rows[a]].f);
            const double det = g.sxx * g.syy - g.sxy * g.sxy;
            for (size_t c = 0; c < cols.size(); ++c) {
                const double dx = dets[cols[c]].x - g.mx, dy = dets[cols[c]].y - g.my;
                const double d2 = (g.syy * dx * dx - 2 * g.sxy * dx * dy + g.sxx * dy * dy) / det;
                if (d2 <= kGate * kGate) cost[a][c] = d2 + std::log(det);
            }
        }
        const auto asg = hungarian(cost, rows.size(), cols.size());
        for (size_t a = 0; a < rows.size(); ++a) {
            if (asg[a] >= 0 && cost[a][static_cast<size_t>(asg[a])] < 1e5) {
                det_of[rows[a]] = static_cast<int>(cols[static_cast<size_t>(asg[a])]);
                used[cols[static_cast<size_t>(asg[a])]] = 1;
            }
        }
    }
    std::vector<typename Baseline<F>::T> keep;
    for (size_t i = 0; i < b.tracks.size(); ++i) {
        auto &t = b.tracks[i];
        bool dead = false;
        if (det_of[i] >= 0) {
            const Det &d = dets[static_cast<size_t>(det_of[i])];
            ops.update(t.f, d, rng);
            t.hits++;
            t.misses = 0;
            t.w = d.w;
            t.h = d.h;
            t.type = d.type;
            if (t.hits >= kConfirmHits) t.confirmed = true;
        } else {
            t.misses++;
            dead = !t.confirmed || t.misses > kMaxMisses;
        }
        double x, y;
        ops.estimate(t.f, x, y);
        if (x < 0 || y < 0 || x >= width || y >= height) dead = true;
        if (!dead) keep.push_back(std::move(t));
    }
    b.tracks.swap(keep);
    for (size_t j = 0; j < dets.size(); ++j) {
        if (used[j]) continue;
        typename Baseline<F>::T t;
        t.id = b.next_id++;
        t.w = dets[j].w;
        t.h = dets[j].h;
        t.type = dets[j].type;
        ops.birth(t.f, dets[j], rng);
        b.tracks.push_back(std::move(t));
    }
    std::vector<Hyp> out;
    for (const auto &t : b.tracks) {
        if (!t.confirmed || t.misses > kReportMisses) continue;
        double x, y;
        ops.estimate(t.f, x, y);
        out.push_back(Hyp{t.id, x, y, t.w, t.h, t.type});
    }
    return out;
}


// ---- CLEAR-MOT ------------------------------------------------------------------------

struct Mot {
    long gt = 0, fn = 0, fp = 0, idsw = 0, matches = 0;
    double sq = 0.0;
    double mota() const { return gt ? 1.0 - static_cast<double>(fn + fp + idsw) / static_cast<double>(gt) : 0.0; }
    double rmse() const { return matches ? std::sqrt(sq / static_cast<double>(matches)) : 0.0; }
    void add(const Mot &o)
    {
        gt += o.gt;
        fn += o.fn;
        fp += o.fp;
        idsw += o.idsw;
        matches += o.matches;
        sq += o.sq;
    }
};

struct MotScorer {
    std::map<int, unsigned> last_hyp;   // gt id -> hypothesis id of its last match
    std::map<int, unsigned> prev_match; // gt id -> hypothesis matched in the previous frame
    Mot m;
    void frame(const std::vector<Obj> &gt, const std::vector<Hyp> &hyp)
    {
        m.gt += static_cast<long>(gt.size());
        std::vector<int> g2h(gt.size(), -1);
        std::vector<char> hused(hyp.size(), 0);
        auto dist = [&](size_t g, size_t h) {
            return std::hypot(gt[g].cx - hyp[h].x, gt[g].cy - hyp[h].y);
        };
        // keep last frame's correspondences while they are valid
        for (size_t g = 0; g < gt.size(); ++g) {
            auto it = prev_match.find(gt[g].id);
            if (it == prev_match.end()) continue;
            for (size_t h = 0; h < hyp.size(); ++h) {
                if (!hused[h] && hyp[h].id == it->second && dist(g, h) <= kMatchPx) {
                    g2h[g] = static_cast<int>(h);
                    hused[h] = 1;
                }
            }
        }
        std::vector<size_t> rows, cols;
        for (size_t g = 0; g < gt.size(); ++g)
            if (g2h[g] < 0) rows.push_back(g);
        for (size_t h = 0; h < hyp.size(); ++h)
            if (!hused[h]) cols.push_back(h);
        if (!rows.empty() && !cols.empty()) {
            std::vector<std::vector<double>> cost(rows.size(), std::vector<double>(cols.size(), 1e6));
            for (size_t a = 0; a < rows.size(); ++a)
                for (size_t c = 0; c < cols.size(); ++c) {
                    const double d = dist(rows[a], cols[c]);
                    if (d <= kMatchPx) cost[a][c] = d;
                }
            const auto asg = hungarian(cost, rows.size(), cols.size());
            for (size_t a = 0; a < rows.size(); ++a) {
                if (asg[a] >= 0 && cost[a][static_cast<size_t>(asg[a])] <= kMatchPx) {
                    g2h[rows[a]] = static_cast<int>(cols[static_cast<size_t>(asg[a])]);
                    hused[cols[static_cast<size_t>(asg[a])]] = 1;
                }
            }
        }
        prev_match.clear();
        for (size_t g = 0; g < gt.size(); ++g) {
            if (g2h[g] < 0) {
                m.fn++;
                continue;
            }
            const Hyp &h = hyp[static_cast<size_t>(g2h[g])];
            auto it = last_hyp.find(gt[g].id);
            if (it != last_hyp.end() && it->second != h.id) m.idsw++;
            last_hyp[gt[g].id] = h.id;
            prev_match[gt[g].id] = h.id;
            const double d = dist(g, static_cast<size_t>(g2h[g]));
            m.sq += d * d;
            m.matches++;
        }
        for (size_t h = 0; h < hyp.size(); ++h)
            if (!hused[h]) m.fp++;
    }
};

// ---- the learned model: file form and generated C ---------------------------------------

std::string write_model_c(const sbr_host::TrackModel &d, const std::string &path, const std::string &header)
{
    std::ofstream out(path);
    if (!out) return "cannot write " + path;
    out << "/*\n * Motion model of sbr's channel tracker. GENERATED by sbr_track --learn - do not edit.\n"
        << header << " */\n#include \"sbr/tracker.h\"\n\n";
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

// Learning without track ids: soft counts of every detection triple (pair for the birth
// prior) whose displacements fit the velocity range, channel-coded, per region; each
// middle detection spreads one unit over its candidate triples. A pseudo-count of one
// constant-velocity row (acceleration 2 channels) regularises rows with little data.
// The active channels (at most 3 with overlap 3) of one encoding.
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

sbr_host::TrackModel learn(const std::vector<Seq> &seqs, const std::vector<std::vector<std::vector<Det>>> &dets,
                uint32_t vel, float spacing, uint32_t rx, uint32_t ry, long &triples, long &pairs)
{
    sbr_host::TrackModel d;
    d.m.order = SBR_TRACK_ORDER;
    d.m.period = kPeriod;
    d.m.extent[0] = static_cast<float>(seqs.front().width);
    d.m.extent[1] = static_cast<float>(seqs.front().height);
    d.m.regions[0] = rx;
    d.m.regions[1] = ry;
    d.m.vel_count = vel;
    d.m.vel_spacing = spacing;
    const size_t V = vel;
    std::vector<double> H(SBR_TRACK_MODEL_TRANSITION_LEN(rx, ry, vel), 0.0);
    std::vector<double> B(SBR_TRACK_MODEL_BIRTH_LEN(rx, ry, vel), 0.0);
    d.trans.resize(H.size());
    d.birth.resize(B.size());
    sbr_channel_config_t vc{};
    vc.first_centre = -0.5f * static_cast<float>(vel - 1) * spacing;
    vc.spacing = spacing;
    vc.count = vel;
    vc.overlap = 3;
    float vlo = 0, vhi = 0;
    sbr_channel_range(&vc, &vlo, &vhi);
    // the region layout is the tracker's own (sbr_track_region_config)
    sbr_channel_config_t rc[2]{};
    sbr_track_region_config(&d.m, 0, &rc[0]);
    sbr_track_region_config(&d.m, 1, &rc[1]);
    auto regions = [&](int axis, double pos) {
        const double ext = d.m.extent[axis];
        const float p = static_cast<float>(std::min(std::max(pos, 0.0), ext - 1e-3));
        return encode_active(rc[axis], p, 1.0 / 1.5);  // one encoding sums to 1.5
    };
    auto velocity = [&](double v) { return encode_active(vc, static_cast<float>(v), 1.0); };
    auto fits = [&](double v) { return v >= vlo && v < vhi; };
    // One triple (a, b, c) on one axis: its region, previous and next velocity channels.
    struct Coded {
        Active r, v1, v2;
        size_t base;
    };
    auto code = [&](int axis, const Det &a, const Det &b, const Det &c) {
        Coded e;
        e.r = regions(axis, axis ? b.y : b.x);
        e.v1 = velocity(axis ? b.y - a.y : b.x - a.x);
        e.v2 = velocity(axis ? c.y - b.y : c.x - b.x);
        e.base = axis ? rx * V * V : 0;
        return e;
    };
    // Soft EM over the unknown associations: the first pass spreads each middle
    // detection's unit evenly over its candidate triples; later passes weight them by the
    // previous pass's transition probability (normalised per middle detection).
    auto score = [&](const Det &a, const Det &b, const Det &c) {
        double sc = 1.0;
        for (int axis = 0; axis < 2; ++axis) {
            const Coded e = code(axis, a, b, c);
            double t = 0;
            for (uint32_t r = 0; r < e.r.n; ++r)
                for (uint32_t j = 0; j < e.v1.n; ++j)
                    for (uint32_t k = 0; k < e.v2.n; ++k)
                        t += e.r.w[r] * e.v1.w[j] * e.v2.w[k] *
                             d.trans[e.base + (e.r.idx[r] * V + e.v1.idx[j]) * V + e.v2.idx[k]];
            sc *= t;
        }
        return sc;
    };
    const std::vector<double> birth_tail = gauss_row(V, 0.5 * static_cast<double>(V - 1), 6.0);
    for (int iter = 0; iter < g_em_iters; ++iter) {
        std::fill(H.begin(), H.end(), 0.0);
        std::fill(B.begin(), B.end(), 0.0);
        triples = pairs = 0;
        for (size_t si = 0; si < seqs.size(); ++si) {
            const auto &D = dets[si];
            for (size_t f = 1; f < D.size(); ++f) {
                for (const Det &b : D[f]) {
                    // pairs: the velocity prior on arrival at b
                    std::vector<const Det *> A;
                    for (const Det &a : D[f - 1])
                        if (fits(b.x - a.x) && fits(b.y - a.y)) A.push_back(&a);
                    for (const Det *a : A) {
                        for (int axis = 0; axis < 2; ++axis) {
                            const Active r = regions(axis, axis ? b.y : b.x);
                            const Active v = velocity(axis ? b.y - a->y : b.x - a->x);
                            const size_t base = axis ? rx * V : 0;
                            for (uint32_t i = 0; i < r.n; ++i)
                                for (uint32_t k = 0; k < v.n; ++k)
                                    B[base + r.idx[i] * V + v.idx[k]] +=
                                        r.w[i] * v.w[k] / static_cast<double>(A.size());
                        }
                        pairs++;
                    }
                    if (f + 1 >= D.size() || A.empty()) continue;
                    std::vector<const Det *> C;
                    for (const Det &c : D[f + 1])
                        if (fits(c.x - b.x) && fits(c.y - b.y)) C.push_back(&c);
                    if (C.empty()) continue;
                    std::vector<double> tw;
                    double tws = 0;
                    for (const Det *a : A)
                        for (const Det *c : C) {
                            tw.push_back(iter == 0 ? 1.0 : score(*a, b, *c));
                            tws += tw.back();
                        }
                    if (tws <= 0) continue;
                    size_t ti = 0;
                    for (const Det *a : A)
                        for (const Det *c : C) {
                            const double w = tw[ti++] / tws;
                            for (int axis = 0; axis < 2; ++axis) {
                                const Coded e = code(axis, *a, b, *c);
                                for (uint32_t r = 0; r < e.r.n; ++r)
                                    for (uint32_t j = 0; j < e.v1.n; ++j)
                                        for (uint32_t k = 0; k < e.v2.n; ++k)
                                            H[e.base + (e.r.idx[r] * V + e.v1.idx[j]) * V + e.v2.idx[k]] +=
                                                w * e.r.w[r] * e.v1.w[j] * e.v2.w[k];
                            }
                            triples++;
                        }
                }
            }
        }
        // rows: the soft counts plus a constant-velocity tail (a share g_tail of the row,
        // at least one count); entries below 1e-5 are dropped (the prediction skips
        // zeros) and the row renormalised
        for (size_t row = 0; row < H.size() / V; ++row) {
            const std::vector<double> g = gauss_row(V, static_cast<double>(row % V), g_tail_sigma);
            double hs = 0;
            for (size_t k = 0; k < V; ++k) hs += H[row * V + k];
            const double a = std::max(1.0, g_tail * hs);
            double kept = 0;
            for (size_t k = 0; k < V; ++k) {
                double v = (H[row * V + k] + a * g[k]) / (hs + a);
                if (v < 1e-5) v = 0;
                d.trans[row * V + k] = static_cast<float>(v);
                kept += v;
            }
            for (size_t k = 0; k < V; ++k) d.trans[row * V + k] = static_cast<float>(d.trans[row * V + k] / kept);
        }
        // birth rows: the soft counts plus one count of a wide prior around 0
        for (size_t row = 0; row < B.size() / V; ++row) {
            double bs = 0;
            for (size_t k = 0; k < V; ++k) bs += B[row * V + k];
            for (size_t k = 0; k < V; ++k)
                d.birth[row * V + k] = static_cast<float>((B[row * V + k] + birth_tail[k]) / (bs + 1.0));
        }
    }
    d.bind();
    return d;
}

// A synthetic sequence for the time per frame with `n` targets at once: targets on an
// 8-column grid over a KITTI-sized image, each moving at a constant velocity of up to
// 3 px per frame and turning back at its cell's edge (so they never meet).
Seq synthetic_seq(unsigned n, int frames, unsigned seed)
{
    Seq s;
    s.name = "synthetic";
    s.frames = frames;
    s.gt.assign(static_cast<size_t>(frames), {});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    const unsigned cols = 8, rows = (n + cols - 1) / cols;
    const double cw = s.width / cols, ch = s.height / rows;
    for (unsigned i = 0; i < n; ++i) {
        const double x0 = (i % cols + 0.5) * cw, y0 = (i / cols + 0.5) * ch;
        const double vx = u(rng), vy = u(rng) * ch / cw;
        for (int f = 0; f < frames; ++f) {
            // a triangle wave within +-0.3 of the cell around its centre
            auto tri = [](double t, double a) { const double p = std::fmod(std::fabs(t), 4 * a); return p < 2 * a ? p - a : 3 * a - p; };
            s.gt[static_cast<size_t>(f)].push_back(
                Obj{static_cast<int>(i), "Car", x0 + tri(vx * f + 0.3 * cw, 0.3 * cw), y0 + tri(vy * f + 0.3 * ch, 0.3 * ch), 40, 30});
        }
    }
    return s;
}

// ---- runs ---------------------------------------------------------------------------------

struct Options {
    std::string labels, seqs = "0006-0010", out, model_file, model_out, c_out;
    double noise = 3.0, miss = 0.1, clutter = 1.0;
    unsigned seed = 1, particles = 500;
    bool csv = false, learn = false, table = false;
    double kf_accel = 3.0, vel0 = 8.0;
    unsigned bench = 0;  // > 0: time per frame with this many targets (synthetic)
    double cv_model = 0.0;  // > 0: the channel tracker uses a constant-velocity model (ablation)
    uint32_t window = 25;
    uint32_t vel_count = 41;
    float vel_spacing = 3.5f;
    std::set<std::string> classes{"Car", "Cyclist"};
};

struct Result {
    std::string method;
    Mot mot;
    double ms = 0;
    long frames = 0;
};

void write_kitti(const std::string &dir, const std::string &seq, const std::vector<std::vector<Hyp>> &per_frame)
{
    std::ofstream out(dir + "/" + seq + ".txt");
    for (size_t f = 0; f < per_frame.size(); ++f) {
        for (const Hyp &h : per_frame[f]) {
            char buf[256];
            std::snprintf(buf, sizeof buf,
                          "%zu %u %s -1 -1 -10 %.2f %.2f %.2f %.2f -1 -1 -1 -1000 -1000 -1000 -10 1\n", f, h.id,
                          h.type.c_str(), h.x - 0.5 * h.w, h.y - 0.5 * h.h, h.x + 0.5 * h.w, h.y + 0.5 * h.h);
            out << buf;
        }
    }
}

std::vector<Result> run_all(const Options &o, const std::vector<Seq> &seqs, const sbr_track_model_t &model,
                            double noise, double miss, double clutter, bool write_out)
{
    std::vector<Result> res(3);
    g_workspace_bytes = 0;
    res[0].method = "channel";
    res[1].method = "kalman";
    res[2].method = "particle";
    const double r = std::max(noise, 1.0);
    for (const Seq &seq : seqs) {
        const auto dets = corrupt(seq, noise, miss, clutter, o.seed);
        std::vector<std::vector<Hyp>> outs[3];
        for (auto &v : outs) v.resize(seq.gt.size());
        // (a) channel tracker (the core)
        {
            sbr_track_config_t cfg;
            sbr_track_config_default(&cfg);
            cfg.model = &model;
            cfg.max_targets = 32;
            cfg.window = o.window;
            cfg.meas_sigma = static_cast<float>(r);
            cfg.gate = static_cast<float>(kGate);
            cfg.confirm_hits = kConfirmHits;
            cfg.max_misses = kMaxMisses;
            g_workspace_bytes = sbr_track_workspace_size(&cfg);
            std::vector<uint32_t> ws(g_workspace_bytes / 4 + 1);
            sbr_track_t trk;
            if (sbr_track_init(&trk, &cfg, ws.data(), ws.size() * 4) != SBR_OK) {
                std::cerr << "sbr_track: tracker init failed\n";
                std::exit(2);
            }
            std::vector<sbr_track_target_t> tg(SBR_TRACK_MAX_TARGETS);
            std::map<uint32_t, std::pair<double, double>> size;
            std::map<uint32_t, std::string> type;
            for (size_t f = 0; f < dets.size(); ++f) {
                std::vector<sbr_track_detection_t> in;
                for (const Det &d : dets[f])
                    in.push_back({static_cast<float>(d.x), static_cast<float>(d.y), 1.0f});
                uint32_t n = 0;
                const auto t0 = std::chrono::steady_clock::now();
                const sbr_status_t st = sbr_track_step(&trk, kPeriodUs, in.data(), static_cast<uint32_t>(in.size()),
                                                       tg.data(), static_cast<uint32_t>(tg.size()), &n);
                res[0].ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                if (st != SBR_OK && st != SBR_ERR_CAPACITY) {
                    std::cerr << "sbr_track: step failed: " << sbr_status_str(st) << "\n";
                    std::exit(2);
                }
                for (uint32_t i = 0; i < n; ++i) {
                    const auto &t = tg[i];
                    if (t.detection >= 0) {
                        const Det &d = dets[f][static_cast<size_t>(t.detection)];
                        size[t.id] = {d.w, d.h};
                        type[t.id] = d.type;
                    }
                    if (!(t.flags & SBR_TRACK_CONFIRMED) || t.misses > kReportMisses) continue;
                    outs[0][f].push_back(Hyp{t.id, t.x, t.y, size[t.id].first, size[t.id].second, type[t.id]});
                }
            }
        }
        // (b) Kalman + Hungarian, (c) particle filter
        {
            KfOps kf{o.kf_accel, r, o.vel0};
            Baseline<KfTrack> b;
            std::mt19937 rng(o.seed);
            for (size_t f = 0; f < dets.size(); ++f) {
                const auto t0 = std::chrono::steady_clock::now();
                outs[1][f] = baseline_step(b, kf, dets[f], 1.0, seq.width, seq.height, rng);
                res[1].ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            }
        }
        {
            PfOps pf{o.kf_accel, r, o.vel0, o.particles};
            Baseline<PfTrack> b;
            std::mt19937 rng(o.seed);
            for (size_t f = 0; f < dets.size(); ++f) {
                const auto t0 = std::chrono::steady_clock::now();
                outs[2][f] = baseline_step(b, pf, dets[f], 1.0, seq.width, seq.height, rng);
                res[2].ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            }
        }
        for (int m = 0; m < 3; ++m) {
            MotScorer sc;
            for (size_t f = 0; f < seq.gt.size(); ++f) sc.frame(seq.gt[f], outs[m][f]);
            res[static_cast<size_t>(m)].mot.add(sc.m);
            res[static_cast<size_t>(m)].frames += static_cast<long>(seq.gt.size());
            if (write_out) {
                const std::string dir = o.out + "/" + res[static_cast<size_t>(m)].method;
                std::error_code ec;
                std::filesystem::create_directories(dir, ec);
                if (ec) std::cerr << "sbr_track: cannot create " << dir << ": " << ec.message() << "\n";
                write_kitti(dir, seq.name, outs[m]);
            }
        }
    }
    return res;
}

// -1: go on; otherwise the exit status. seqs_given: --seqs was on the command line.
int parse_options(int argc, char **argv, Options &o, bool &seqs_given)
{
    CLI::App app{"sbr_track: the channel tracker (paper E) against a Kalman filter with Hungarian association "
                 "and a particle filter on KITTI tracking ground truth, corrupted by noise, misses and clutter "
                 "(docs/usage/track.md); --learn: learn the tracker's motion model"};
    app.add_option("--labels", o.labels, "KITTI tracking label_02 folder")->required();
    auto *seqs = app.add_option("--seqs", o.seqs, "sequences: numbers or ranges, e.g. 0006-0010 or 1,3,5")
                     ->capture_default_str();
    app.add_option("--noise", o.noise, "detection noise, pixels (Gaussian sigma)")
        ->check(sbr_host::finite_range(0.0, 99.999))
        ->capture_default_str();
    app.add_option("--miss", o.miss, "probability that a detection is missed")
        ->check(sbr_host::finite_range(0.0, 0.999))
        ->capture_default_str();
    app.add_option("--clutter", o.clutter, "false detections per frame (Poisson mean)")
        ->check(sbr_host::finite_range(0.0, 50.0))
        ->capture_default_str();
    app.add_option("--seed", o.seed, "random seed")->capture_default_str();
    app.add_flag("--csv", o.csv, "print method,rmse_px,mota,id_switches,ms_per_frame");
    app.add_option("--out", o.out, "write each method's tracks in KITTI's format to this folder");
    app.add_option("--model", o.model_file, "motion model file (default: the built-in one)");
    app.add_option("--model-out", o.model_out, "(with --learn) write the learned model here");
    app.add_option("--c-out", o.c_out, "(with --learn) write the learned model as a C table");
    app.add_flag("--learn", o.learn, "learn the motion model (default sequences 0000-0005)");
    app.add_option("--vel-count", o.vel_count, "(with --learn) velocity channels (odd)")
        ->check(CLI::Range(5u, SBR_TRACK_MAX_VEL))
        ->capture_default_str();
    app.add_option("--vel-spacing", o.vel_spacing, "(with --learn) pixels per period between velocity channels")
        ->check(sbr_host::finite_range(0.01, 1000.0))
        ->capture_default_str();
    app.add_option("--em", g_em_iters, "(with --learn) passes of the soft association EM")
        ->check(CLI::Range(0, 100))
        ->capture_default_str();
    app.add_option("--tail", g_tail, "(with --learn) share of a row given to the wide constant-velocity tail")
        ->check(sbr_host::finite_range(0.0, 1.0))
        ->capture_default_str();
    app.add_option("--tail-sigma", g_tail_sigma, "(with --learn) the tail's standard deviation, velocity channels")
        ->check(sbr_host::finite_range(0.01, 1000.0))
        ->capture_default_str();
    app.add_flag("--table", o.table, "print the result as a Markdown table");
    app.add_option("--particles", o.particles, "particle filter size")
        ->check(CLI::Range(16u, 100000u))
        ->capture_default_str();
    app.add_option("--accel", o.kf_accel, "Kalman filter's acceleration noise, pixels per frame squared")
        ->check(sbr_host::finite_range(0.0, 1000.0))
        ->capture_default_str();
    app.add_option("--bench-targets", o.bench, "time per frame with this many synthetic targets (0: KITTI)")
        ->check(CLI::Range(0u, 32u));
    app.add_option("--cv-model", o.cv_model, "> 0: the channel tracker uses a constant-velocity model (ablation)")
        ->check(sbr_host::finite_range(0.0, 1000.0));
    app.add_option("--window", o.window, "the channel tracker's window, channels")->capture_default_str();
    std::string classes;
    app.add_option("--classes", classes, "KITTI classes tracked, comma-separated (default Car,Cyclist)");
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    seqs_given = seqs->count() > 0;
    if (!classes.empty()) {
        o.classes.clear();
        for (auto &c : split(classes, ',')) o.classes.insert(c);
    }
    return -1;
}

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    bool seqs_given = false;
    const int parsed = parse_options(argc, argv, o, seqs_given);
    if (parsed >= 0) return parsed;
    if (o.learn && !seqs_given) o.seqs = "0000-0005";
    std::vector<Seq> seqs;
    if (o.bench > 0) {
        seqs.push_back(synthetic_seq(o.bench, 300, o.seed));
        o.seqs = "synthetic";
    }
    for (const auto &name : o.bench > 0 ? std::vector<std::string>{} : parse_seqs(o.seqs)) {
        Seq s;
        if (!load_seq(o.labels, name, o.classes, s)) {
            std::cerr << "sbr_track: cannot read " << o.labels << "/" << name << ".txt\n";
            return 77;
        }
        seqs.push_back(std::move(s));
    }
    if (seqs.empty()) {
        std::cerr << "sbr_track: --seqs names no sequence\n";
        return 2;
    }
    if (o.learn) {
        std::vector<std::vector<std::vector<Det>>> dets;
        for (const Seq &s : seqs) dets.push_back(corrupt(s, o.noise, o.miss, o.clutter, o.seed));
        long triples = 0, pairs = 0;
        sbr_host::TrackModel d = learn(seqs, dets, o.vel_count, o.vel_spacing, 10, 5, triples, pairs);
        const sbr_status_t st = sbr_track_model_check(&d.m);
        std::printf("learned from %zu sequences (%s), %ld detection triples, %ld pairs, no track ids: %s\n",
                    seqs.size(), o.seqs.c_str(), triples, pairs, sbr_status_str(st));
        if (st != SBR_OK) return 1;
        if (!o.model_out.empty()) {
            const std::string e = sbr_host::save_track_model(d, o.model_out);
            if (!e.empty()) { std::cerr << e << "\n"; return 1; }
        }
        if (!o.c_out.empty()) {
            char hdr[1024];
            std::snprintf(hdr, sizeof hdr,
                          " * Regenerate: ./sbr.sh learn-tracker   (runs sbr_track --learn --seqs %s --noise %g\n"
                          " *             --miss %g --clutter %g --seed %u --c-out lib/models/sbr_track_model_kitti.c\n"
                          " *             on KITTI tracking label_02, classes Car and Cyclist)\n"
                          " * Learned from %ld detection triples and %ld pairs, without track ids (%d passes of\n"
                          " * soft-association EM). %u x %u regions, %u velocity channels of %.2f px.\n"
                          " * Data: KITTI (Geiger, Lenz, Urtasun, CVPR 2012), CC BY-NC-SA 3.0: research use.\n",
                          o.seqs.c_str(), o.noise, o.miss, o.clutter, o.seed, triples, pairs, g_em_iters,
                          d.m.regions[0], d.m.regions[1], d.m.vel_count, static_cast<double>(d.m.vel_spacing));
            const std::string e = write_model_c(d, o.c_out, hdr);
            if (!e.empty()) { std::cerr << e << "\n"; return 1; }
        }
        return 0;
    }
    sbr_track_model_t model{};
    sbr_host::TrackModel loaded;
    if (!o.model_file.empty()) {
        const std::string e = sbr_host::load_track_model(o.model_file, loaded);
        if (!e.empty()) { std::cerr << "sbr_track: " << e << "\n"; return 2; }
        model = loaded.m;
    } else if (o.cv_model > 0.0) {
        loaded.trans.resize(SBR_TRACK_MODEL_TRANSITION_LEN(3, 3, o.vel_count));
        loaded.birth.resize(SBR_TRACK_MODEL_BIRTH_LEN(3, 3, o.vel_count));
        if (sbr_track_model_cv(&model, static_cast<float>(seqs.front().width), static_cast<float>(seqs.front().height),
                               kPeriod, o.vel_count, o.vel_spacing, static_cast<float>(o.cv_model), static_cast<float>(o.vel0),
                               loaded.trans.data(), loaded.trans.size(), loaded.birth.data(),
                               loaded.birth.size()) != SBR_OK)
            return 2;
    } else if (sbr_track_model_kitti(&model) != SBR_OK) {
        return 2;
    }
    if (sbr_track_model_check(&model) != SBR_OK) {
        std::cerr << "sbr_track: the model is invalid\n";
        return 2;
    }
    auto print = [&](const std::vector<Result> &res) {
        std::printf("method,rmse_px,mota,id_switches,ms_per_frame\n");
        for (const auto &r : res)
            std::printf("%s,%.3f,%.4f,%ld,%.4f\n", r.method.c_str(), r.mot.rmse(), r.mot.mota(), r.mot.idsw,
                        r.ms / static_cast<double>(r.frames));
    };
    const auto res = run_all(o, seqs, model, o.noise, o.miss, o.clutter, !o.out.empty());
    if (o.csv) {
        print(res);
    } else {
        std::printf("sbr_track: sequences %s, noise %.1f px, miss %.2f, clutter %.1f per frame, seed %u\n",
                    o.seqs.c_str(), o.noise, o.miss, o.clutter, o.seed);
        std::printf("channel tracker: 32 targets, window %u, %u velocity channels of %.2f px, %u x %u regions, "
                    "workspace %zu bytes, model tables %zu bytes\n",
                    o.window, model.vel_count, static_cast<double>(model.vel_spacing), model.regions[0],
                    model.regions[1], g_workspace_bytes,
                    (SBR_TRACK_MODEL_TRANSITION_LEN(model.regions[0], model.regions[1], model.vel_count) +
                     SBR_TRACK_MODEL_BIRTH_LEN(model.regions[0], model.regions[1], model.vel_count)) *
                        sizeof(float));
        std::printf("| method | RMSE px | MOTA | ID switches | misses | false positives | GT objects | ms/frame |\n");
        std::printf("|---|---|---|---|---|---|---|---|\n");
        for (const auto &r : res)
            std::printf("| %s | %.3f | %.4f | %ld | %ld | %ld | %ld | %.4f |\n", r.method.c_str(), r.mot.rmse(),
                        r.mot.mota(), r.mot.idsw, r.mot.fn, r.mot.fp, r.mot.gt, r.ms / static_cast<double>(r.frames));
    }
    const bool met = res[0].mot.rmse() <= res[1].mot.rmse() && res[0].mot.mota() >= res[1].mot.mota();
    if (o.table) {
        std::printf("\n| noise px | miss | channel RMSE | Kalman RMSE | particle RMSE | channel MOTA | Kalman MOTA | particle MOTA |\n");
        std::printf("|---|---|---|---|---|---|---|---|\n");
        for (double nz : {1.0, 3.0, 6.0})
            for (double ms : {0.0, 0.1, 0.3}) {
                const auto t = run_all(o, seqs, model, nz, ms, o.clutter, false);
                std::printf("| %.0f | %.1f | %.3f | %.3f | %.3f | %.4f | %.4f | %.4f |\n", nz, ms, t[0].mot.rmse(),
                            t[1].mot.rmse(), t[2].mot.rmse(), t[0].mot.mota(), t[1].mot.mota(), t[2].mot.mota());
            }
    }
    if (!o.csv) std::printf("channel_vs_kalman_target=%s\n", met ? "met" : "not_met");
    return 0;
}
