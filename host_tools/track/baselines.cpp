// SPDX-License-Identifier: MIT
#include "baselines.hpp"

#include <cmath>
#include <cstring>
#include <random>
#include <utility>

#include "geometry.hpp"

namespace sbr_track_host {
namespace {

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
        std::vector<std::vector<double>> cost(rows.size(), std::vector<double>(cols.size(), sbr_host::kAssignForbidden));
        for (size_t a = 0; a < rows.size(); ++a) {
            const Gauss2 g = ops.predicted(b.tracks[rows[a]].f);
            const double det = g.sxx * g.syy - g.sxy * g.sxy;
            for (size_t c = 0; c < cols.size(); ++c) {
                const double dx = dets[cols[c]].x - g.mx, dy = dets[cols[c]].y - g.my;
                const double d2 = (g.syy * dx * dx - 2 * g.sxy * dx * dy + g.sxx * dy * dy) / det;
                if (d2 <= kGate * kGate) cost[a][c] = d2 + std::log(det);
            }
        }
        const auto asg = sbr_host::hungarian(cost, rows.size(), cols.size());
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

template <class F, class Ops>
class BaselineTracker final : public FrameTracker {
public:
    BaselineTracker(const Ops &ops, unsigned seed, double width, double height)
        : ops_(ops), rng_(seed), width_(width), height_(height)
    {
    }
    std::vector<Hyp> step(const std::vector<Det> &dets) override
    {
        return baseline_step(b_, ops_, dets, 1.0, width_, height_, rng_);
    }

private:
    Baseline<F> b_;
    Ops ops_;
    std::mt19937 rng_;
    double width_, height_;
};

}  // namespace

std::unique_ptr<FrameTracker> make_kalman(const FilterParams &p, unsigned seed, double width, double height)
{
    return std::make_unique<BaselineTracker<KfTrack, KfOps>>(KfOps{p.accel, p.r, p.vel0}, seed, width, height);
}

std::unique_ptr<FrameTracker> make_particle(const FilterParams &p, unsigned seed, double width, double height)
{
    return std::make_unique<BaselineTracker<PfTrack, PfOps>>(PfOps{p.accel, p.r, p.vel0, p.particles}, seed, width,
                                                             height);
}

}  // namespace sbr_track_host
