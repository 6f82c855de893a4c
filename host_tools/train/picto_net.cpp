// SPDX-License-Identifier: MIT
// sbr_train_picto's network trainer (picto_net.hpp).
#include "picto_net.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include <unistd.h>

namespace sbr_host::picto_train {

namespace {

// Dropout mask bit of hidden unit j for one sample in one epoch (deterministic, whatever
// thread computes it): splitmix64 of the three.
bool dropped(uint64_t key, int j, float rate) {
    uint64_t z = key + 0x9E3779B97F4A7C15ull * uint64_t(j + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return float(z >> 40) * (1.0f / 16777216.0f) < rate;
}

// The first layer's weights by feature (w1t[k * h + j] = w1[j][k]), so that the forward
// pass adds feature k to every hidden unit at once: each unit still sums its bias and then
// w[k] * x[k] in the order of k, so its value is the same as a unit-by-unit dot product's.
void transpose_w1(const Net &n, std::vector<float> &w1t) {
    w1t.resize(size_t(n.h) * kF);
    for (int j = 0; j < n.h; ++j)
        for (int k = 0; k < kF; ++k) w1t[size_t(k) * n.h + j] = n.w1[size_t(j) * (kF + 1) + k];
}

// Class probabilities p and box outputs r (in target units) of x; a = hidden units (w1t:
// transpose_w1() of n). With rate > 0 (training), hidden units are dropped at that rate
// (mask from key) and the others scaled by 1 / (1 - rate).
void forward(const Net &n, const std::vector<float> &w1t, const float *x, std::vector<float> &a,
             std::vector<float> &p, float r[kR], float rate = 0.0f, uint64_t key = 0) {
    const float *in = x;
    if (n.h > 0) {
        a.resize(n.h);
        float *s = a.data();
        for (int j = 0; j < n.h; ++j) s[j] = n.w1[size_t(j) * (kF + 1) + kF];
        for (int k = 0; k < kF; ++k) {
            const float xk = x[k];
            const float *wk = &w1t[size_t(k) * n.h];
            for (int j = 0; j < n.h; ++j) s[j] += wk[j] * xk;
        }
        for (int j = 0; j < n.h; ++j) {
            a[j] = s[j] > 0 ? s[j] : 0;
            if (rate > 0.0f) a[j] = dropped(key, j, rate) ? 0.0f : a[j] / (1.0f - rate);
        }
        in = a.data();
    }
    const int ni = n.nin();
    auto row = [&](const std::vector<float> &w, int c) {
        const float *wc = &w[size_t(c) * (ni + 1)];
        float s = wc[ni];
        for (int k = 0; k < ni; ++k) s += wc[k] * in[k];
        return s;
    };
    p.resize(kK);
    float mx = -1e30f;
    for (int c = 0; c < kK; ++c) {
        p[c] = row(n.w2, c);
        mx = std::max(mx, p[c]);
    }
    float sum = 0;
    for (int c = 0; c < kK; ++c) { p[c] = std::exp(p[c] - mx); sum += p[c]; }
    for (int c = 0; c < kK; ++c) p[c] /= sum;
    for (int c = 0; c < kR; ++c) r[c] = row(n.w3, c);
}

// Gradients of one slice of a minibatch, summed into g (w1, w2, w3 layout one after the
// other); returns the slice's weighted loss.
struct Grad {
    std::vector<float> g;
    double loss = 0, weight = 0;
};

void backprop(const Net &n, const std::vector<float> &w1t, const std::vector<Sample> &s, const std::vector<float> &sw,
              const size_t *idx, size_t count, float rate, uint64_t epoch, Grad &out) {
    const int ni = n.nin();
    const size_t o2 = n.w1.size(), o3 = o2 + n.w2.size();
    std::fill(out.g.begin(), out.g.end(), 0.0f);
    out.loss = 0;
    out.weight = 0;
    std::vector<float> a, p, da(std::max(1, n.h));
    for (size_t bi = 0; bi < count; ++bi) {
        const Sample &x = s[idx[bi]];
        const float w = sw[idx[bi]];
        float r[kR];
        forward(n, w1t, x.f.data(), a, p, r, rate, (epoch << 32) ^ uint64_t(idx[bi]));
        const float *in = n.h > 0 ? a.data() : x.f.data();
        if (n.h > 0) std::fill(da.begin(), da.end(), 0.0f);
        auto add_row = [&](size_t off, const std::vector<float> &wm, int c, float d) {
            float *g = &out.g[off + size_t(c) * (ni + 1)];
            const float *wc = &wm[size_t(c) * (ni + 1)];
            for (int k = 0; k < ni; ++k) g[k] += d * in[k];
            g[ni] += d;
            if (n.h > 0)
                for (int k = 0; k < ni; ++k) da[k] += d * wc[k];
        };
        if (x.label >= 0) {
            out.loss -= w * std::log(std::max(p[x.label], 1e-12f));
            out.weight += w;
            for (int c = 0; c < kK; ++c) {
                const float d = w * (p[c] - (c == x.label ? 1.0f : 0.0f));
                if (d != 0.0f) add_row(o2, n.w2, c, d);
            }
        }
        if (x.has_box) {
            // smooth L1 (Huber, 1 target unit) on each box output
            for (int c = 0; c < kR; ++c) {
                const float e = r[c] - x.t[c] / kTargetScale;
                const float d = std::max(-1.0f, std::min(1.0f, e));
                out.loss += std::fabs(e) < 1.0f ? 0.5 * e * e : std::fabs(e) - 0.5;
                add_row(o3, n.w3, c, d);
            }
            if (x.label < 0) out.weight += 1.0;
        }
        if (n.h > 0) {
            for (int j = 0; j < n.h; ++j) {
                if (a[j] <= 0.0f || da[j] == 0.0f) continue;
                float *g = &out.g[size_t(j) * (kF + 1)];
                const float d = rate > 0.0f ? da[j] / (1.0f - rate) : da[j];
                for (int k = 0; k < kF; ++k) g[k] += d * x.f[k];
                g[kF] += d;
            }
        }
    }
}

}  // namespace

// Minibatch SGD with momentum and cosine decay. Each epoch sees every sign sample and a
// fresh `bg_fraction` of the background ones (weighted up to match). Two threads share
// each minibatch and their gradients are added in a fixed order: deterministic.
void train(Net &n, const std::vector<Sample> &s, const std::vector<float> &sw, int epochs, unsigned seed, float lr0,
           float bg_fraction, float rate, float decay) {
    std::mt19937 rng(seed);
    const int ni = n.nin();
    std::normal_distribution<float> nd(0.0f, 1.0f);
    if (n.h > 0) {
        n.w1.assign(size_t(n.h) * (kF + 1), 0.0f);
        const float sc = std::sqrt(2.0f / float(kF));
        for (int j = 0; j < n.h; ++j)
            for (int k = 0; k < kF; ++k) n.w1[size_t(j) * (kF + 1) + k] = nd(rng) * sc;
    }
    n.w2.assign(size_t(kK) * (ni + 1), 0.0f);
    n.w3.assign(size_t(kR) * (ni + 1), 0.0f);
    if (n.h > 0) {
        const float sc = std::sqrt(1.0f / float(ni));
        for (int c = 0; c < kK; ++c)
            for (int k = 0; k < ni; ++k) n.w2[size_t(c) * (ni + 1) + k] = nd(rng) * sc;
    }
    const size_t nw = n.w1.size() + n.w2.size() + n.w3.size();
    std::vector<float> vel(nw, 0.0f);
    std::vector<size_t> fg, bg;
    for (size_t i = 0; i < s.size(); ++i)
        (s[i].label == kBackground && !s[i].hard ? bg : fg).push_back(i);
    std::vector<float> w = sw;
    for (size_t i : bg) w[i] /= bg_fraction;  // the hard ones are in fg: every epoch
    const size_t batch = 64;
    const float mom = 0.9f;
    Grad part[2];
    for (auto &g : part) g.g.assign(nw, 0.0f);
    std::vector<size_t> order;
    std::vector<float> w1t;
    for (int e = 0; e < epochs; ++e) {
        const float lr = lr0 * 0.5f * (1.0f + std::cos(3.14159265f * float(e) / float(epochs)));
        std::shuffle(bg.begin(), bg.end(), rng);
        order = fg;
        order.insert(order.end(), bg.begin(), bg.begin() + std::ptrdiff_t(double(bg.size()) * bg_fraction));
        std::shuffle(order.begin(), order.end(), rng);
        double loss = 0, wsum = 0;
        for (size_t b0 = 0; b0 < order.size(); b0 += batch) {
            const size_t cnt = std::min(order.size(), b0 + batch) - b0, half = cnt / 2;
            if (n.h > 0) transpose_w1(n, w1t);
            std::thread t1([&]() { backprop(n, w1t, s, w, &order[b0], half, rate, uint64_t(e), part[0]); });
            backprop(n, w1t, s, w, &order[b0 + half], cnt - half, rate, uint64_t(e), part[1]);
            t1.join();
            const double bw = part[0].weight + part[1].weight;
            loss += part[0].loss + part[1].loss;
            wsum += bw;
            const float inv = 1.0f / float(std::max(bw, 1e-6));
            float *wts[3] = {n.w1.data(), n.w2.data(), n.w3.data()};
            const size_t len[3] = {n.w1.size(), n.w2.size(), n.w3.size()};
            size_t off = 0;
            for (int m = 0; m < 3; ++m) {
                for (size_t i = 0; i < len[m]; ++i) {
                    const float g = (part[0].g[off + i] + part[1].g[off + i]) * inv;
                    vel[off + i] = mom * vel[off + i] - lr * (g + decay * wts[m][i]);
                    wts[m][i] += vel[off + i];
                }
                off += len[m];
            }
        }
        if (e % 5 == 4 || e + 1 == epochs)
            std::fprintf(stderr, "sbr_train_picto: epoch %d loss %.4f\n", e + 1, loss / std::max(wsum, 1e-9));
    }
}

namespace {

template <typename T>
void put(std::ofstream &f, const T *p, size_t n) {
    f.write(reinterpret_cast<const char *>(p), std::streamsize(n * sizeof(T)));
}

// The samples file of picto_fit.py (its docstring has the format).
bool write_samples(const std::string &path, const std::vector<Sample> &s, const std::vector<float> &sw) {
    std::ofstream f(path, std::ios::binary);
    const int32_t head[4] = {int32_t(s.size()), kF, kK, kR};
    f.write("SBRSMP01", 8);
    put(f, head, 4);
    for (const Sample &x : s) put(f, x.f.data(), size_t(kF));
    for (const Sample &x : s) {
        const int32_t l = x.label;
        put(f, &l, 1);
    }
    put(f, sw.data(), sw.size());
    for (const Sample &x : s) {
        const uint8_t b = x.has_box ? 1u : 0u;
        put(f, &b, 1);
    }
    for (const Sample &x : s) {
        const uint8_t b = x.hard ? 1u : 0u;
        put(f, &b, 1);
    }
    for (const Sample &x : s) {
        float t[kR];
        for (int c = 0; c < kR; ++c) t[c] = x.t[c] / kTargetScale;
        put(f, t, size_t(kR));
    }
    return bool(f);
}

// The weights file picto_fit.py writes, into n (hidden units as asked).
bool read_weights(const std::string &path, int hidden, Net &n) {
    std::ifstream f(path, std::ios::binary);
    char magic[8];
    int32_t head[4];
    if (!f.read(magic, 8) || std::string(magic, 8) != "SBRNET01" ||
        !f.read(reinterpret_cast<char *>(head), sizeof head) || head[0] != hidden || head[1] != kF || head[2] != kK ||
        head[3] != kR)
        return false;
    n.h = hidden;
    n.w1.assign(size_t(hidden) * (kF + 1), 0.0f);
    n.w2.assign(size_t(kK) * (hidden + 1), 0.0f);
    n.w3.assign(size_t(kR) * (hidden + 1), 0.0f);
    for (std::vector<float> *w : {&n.w1, &n.w2, &n.w3})
        if (!f.read(reinterpret_cast<char *>(w->data()), std::streamsize(w->size() * sizeof(float)))) return false;
    char extra;
    return !f.read(&extra, 1);
}

}  // namespace

bool train_library(Net &n, const std::vector<Sample> &s, const std::vector<float> &sw, const LibraryFit &lf) {
    namespace fs = std::filesystem;
    if (lf.hidden <= 0) {
        std::fprintf(stderr, "sbr_train_picto: --trainer sklearn needs hidden units (--hidden >= 1)\n");
        return false;
    }
    static int calls = 0;  // host tool, one thread calls this
    const fs::path dir = fs::temp_directory_path() /
                         ("sbr_picto_fit_" + std::to_string(getpid()) + "_" + std::to_string(++calls));
    fs::create_directories(dir);
    const std::string samples = (dir / "samples.bin").string(), weights = (dir / "weights.bin").string();
    bool ok = write_samples(samples, s, sw);
    if (!ok) std::fprintf(stderr, "sbr_train_picto: cannot write %s\n", samples.c_str());
    if (ok) {
        char nums[160];
        std::snprintf(nums, sizeof nums, " --hidden %d --epochs %d --seed %u --bg-fraction %g", lf.hidden, lf.epochs,
                      lf.seed, double(lf.bg_fraction));
        const std::string cmd = "'" + lf.python + "' '" + lf.script + "' --samples '" + samples + "' --out '" +
                                weights + "'" + nums + (lf.args.empty() ? "" : " " + lf.args);
        std::fprintf(stderr, "sbr_train_picto: %s\n", cmd.c_str());
        const int rc = std::system(cmd.c_str());
        ok = rc == 0 && read_weights(weights, lf.hidden, n);
        if (!ok) std::fprintf(stderr, "sbr_train_picto: the library trainer failed (status %d)\n", rc);
    }
    std::error_code ec;
    fs::remove_all(dir, ec);
    return ok;
}

}  // namespace sbr_host::picto_train
