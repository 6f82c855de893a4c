// SPDX-License-Identifier: MIT
#include "gtsrb_tracks.hpp"

#include <algorithm>
#include <array>
#include <set>
#include <sstream>

#include "classes.hpp"

namespace sbr_host {

namespace {

// One track's crops (positions into idx) through a fresh sign tracking.
bool fuse_one(const std::vector<std::vector<float>> &probs, const std::vector<size_t> &pos, int k,
              const sbr_signs_config_t &cfg, std::vector<uint64_t> &ws, GtsrbTrack &t) {
    sbr_signs_t s;
    if (sbr_signs_init(&s, &cfg, ws.data(), ws.size() * sizeof(uint64_t)) != SBR_OK) return false;
    std::set<uint32_t> ids;
    std::vector<sbr_sign_t> out(cfg.max_tracks);
    for (size_t j = 0; j < pos.size(); ++j) {
        const std::vector<float> &p = probs[pos[j]];
        sbr_detection_t d{};
        uint32_t n = 0;
        if (!p.empty()) {
            const int best = int(std::max_element(p.begin(), p.end()) - p.begin());
            t.crops_right += best == t.cls;
            if (best < k) {
                d.box = {static_cast<uint32_t>(cfg.width / 2.0f) - 20u, static_cast<uint32_t>(cfg.height / 2.0f) - 20u,
                         40u, 40u};
                d.class_id = static_cast<uint16_t>(best);
                d.score = std::min(1.0f, std::max(0.0f, p[size_t(best)]));
                n = 1;
            }
        }
        uint32_t count = 0;
        const sbr_status_t st = sbr_signs_update(&s, uint64_t(j + 1) * cfg.period_us, n ? &d : nullptr, n, nullptr,
                                                 out.data(), uint32_t(out.size()), &count);
        if (st != SBR_OK) return false;
        for (uint32_t i = 0; i < count; ++i) {
            const sbr_sign_t &g = out[i];
            ids.insert(g.id);
            if (g.flags & SBR_SIGN_NEW) {
                if (t.confirmed_at == 0) {
                    t.confirmed_at = int(j) + 1;
                    t.confirmed_class = g.class_id;
                }
            }
            if (g.flags & SBR_SIGN_RENAMED) ++t.renamed;
            t.final_class = g.class_id;
        }
    }
    t.signs = int(ids.size());
    return true;
}

struct Tally {
    int tracks = 0, right = 0, confirmed_wrong = 0, unconfirmed = 0, crops = 0, crops_right = 0;
    int long_tracks = 0, long_right = 0;  // tracks with at least confirm_hits crops
    std::vector<int> until;
    void add(const GtsrbTrack &t, int hits) {
        ++tracks;
        if (t.crops >= hits) {
            ++long_tracks;
            long_right += t.final_class == t.cls;
        }
        right += t.final_class == t.cls;
        confirmed_wrong += t.confirmed_at > 0 && t.confirmed_class != t.cls;
        unconfirmed += t.confirmed_at == 0;
        crops += t.crops;
        crops_right += t.crops_right;
        if (t.confirmed_at > 0) until.push_back(t.confirmed_at);
    }
    double pct(int a, int b) const { return b ? 100.0 * a / b : 0.0; }
    // mean, median, 90th percentile of crops until confirmation
    std::array<double, 3> delays() const {
        if (until.empty()) return {0, 0, 0};
        std::vector<int> u(until);
        std::sort(u.begin(), u.end());
        double m = 0;
        for (int v : u) m += v;
        return {m / double(u.size()), double(u[u.size() / 2]), double(u[(u.size() * 9) / 10])};
    }
};

std::array<Tally, 5> tally(const std::vector<GtsrbTrack> &ts, int hits) {
    std::array<Tally, 5> g{};  // superclasses 0..3, then all
    for (const GtsrbTrack &t : ts) {
        g[size_t(superclass_of(t.cls))].add(t, hits);
        g[4].add(t, hits);
    }
    return g;
}

}  // namespace

std::vector<GtsrbTrack> fuse_gtsrb_tracks(const std::vector<GtsrbCrop> &crops, const std::vector<size_t> &idx,
                                          const std::vector<std::vector<float>> &probs, int k,
                                          const sbr_signs_config_t &cfg, std::string &err) {
    std::vector<GtsrbTrack> out;
    const size_t bytes = sbr_signs_workspace_size(&cfg);
    if (bytes == 0) {
        err = "the sign tracking's configuration is refused (sbr_signs_config_check)";
        return out;
    }
    std::vector<uint64_t> ws(bytes / sizeof(uint64_t) + 1);
    for (size_t j = 0; j < idx.size();) {
        const GtsrbCrop &c = crops[idx[j]];
        std::vector<size_t> pos;
        for (; j < idx.size() && crops[idx[j]].cls == c.cls && crops[idx[j]].track == c.track; ++j) pos.push_back(j);
        GtsrbTrack t;
        t.cls = c.cls;
        t.track = c.track;
        t.crops = int(pos.size());
        if (!fuse_one(probs, pos, k, cfg, ws, t)) {
            err = "the sign tracking refused a frame of track " + std::to_string(c.track);
            return {};
        }
        out.push_back(t);
    }
    return out;
}

void print_gtsrb_tracks(std::FILE *out, const std::vector<GtsrbTrack> &ts, int hits, const std::string &title) {
    const std::array<Tally, 5> g = tally(ts, hits);
    std::fprintf(out, "%s\n", title.c_str());
    std::fprintf(out, "%-12s %6s %7s %9s %8s %10s %10s %11s %22s\n", "", "tracks", "crops", "per-crop", "track",
                 "track acc.", "confirmed", "never", "crops until confirmed");
    std::fprintf(out, "%-12s %6s %7s %9s %8s %10s %10s %11s %22s\n", "", "", "", "accuracy", "accuracy",
                 (">=" + std::to_string(hits) + " crops").c_str(), "wrong", "confirmed", "mean / median / p90");
    for (size_t i = 0; i < 5; ++i) {
        const Tally &t = g[i];
        if (t.tracks == 0) continue;
        const std::array<double, 3> d = t.delays();
        std::fprintf(out, "%-12s %6d %7d %8.2f%% %7.2f%% %9.2f%% %10d %11d %10.1f / %.0f / %.0f\n",
                     i < 4 ? kSuperclassNames[i] : "all", t.tracks, t.crops, t.pct(t.crops_right, t.crops),
                     t.pct(t.right, t.tracks), t.pct(t.long_right, t.long_tracks), t.confirmed_wrong, t.unconfirmed,
                     d[0], d[1], d[2]);
    }
    // the target: >= 99.5 % of the tracks named right (those long enough to be
    // confirmed), no danger-sign track confirmed as another class
    const bool met = g[4].long_tracks > 0 && 1000.0 * g[4].long_right >= 995.0 * g[4].long_tracks &&
                     g[2].confirmed_wrong == 0;
    std::fprintf(out, "tracks_target=%s (track-level accuracy >= 99.5 %% over the tracks of >= %d crops: %.2f %%; "
                      "danger tracks confirmed wrong: %d)\n",
                 met ? "met" : "missed", hits, g[4].pct(g[4].long_right, g[4].long_tracks), g[2].confirmed_wrong);
    for (const GtsrbTrack &t : ts)
        if (t.final_class != t.cls || (t.confirmed_at > 0 && t.confirmed_class != t.cls))
            std::fprintf(out,
                         "  track %05d class %d: %d/%d crops right, confirmed as %d after %d crops, ends as %d "
                         "(%d renamings, %d sign ids)\n",
                         t.track, t.cls, t.crops_right, t.crops, t.confirmed_class, t.confirmed_at, t.final_class,
                         t.renamed, t.signs);
}

std::string gtsrb_tracks_json(const std::vector<GtsrbTrack> &ts, int hits) {
    const std::array<Tally, 5> g = tally(ts, hits);
    std::ostringstream o;
    o << "{";
    for (size_t i = 0; i < 5; ++i) {
        const Tally &t = g[i];
        const std::array<double, 3> d = t.delays();
        o << (i ? ", " : "") << "\"" << (i < 4 ? kSuperclassNames[i] : "all") << "\": {\"tracks\": " << t.tracks
          << ", \"crops\": " << t.crops << ", \"crops_right\": " << t.crops_right << ", \"tracks_right\": " << t.right << ", \"long_tracks\": " << t.long_tracks
          << ", \"long_tracks_right\": " << t.long_right
          << ", \"confirmed_wrong\": " << t.confirmed_wrong << ", \"unconfirmed\": " << t.unconfirmed
          << ", \"crops_until_confirmed\": {\"mean\": " << d[0] << ", \"median\": " << d[1] << ", \"p90\": " << d[2]
          << "}}";
    }
    o << "}";
    return o.str();
}

}  // namespace sbr_host
