// SPDX-License-Identifier: MIT
// sbr_track: paper E's channel tracker on KITTI tracking ground truth, against a
// constant-velocity Kalman filter with Hungarian association and a bootstrap particle
// filter, all three on the very same corrupted detections (docs/usage/track.md).
//
// Detections: kitti.hpp's corrupt() (documented, seeded: misses, centre noise, Poisson
// clutter, shuffled order). Track management is the same for the three methods
// (baselines.hpp; the channel tracker is configured with the same constants). Scoring:
// CLEAR-MOT (clear_mot.hpp). The motion model is learned by sbr_train_track.
#include "cli_core.hpp"
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

extern "C" {
#include "sbr/track.h"
#include "sbr/models.h"
}

#include "baselines.hpp"
#include "clear_mot.hpp"
#include "kitti.hpp"
#include "kitti_cli.hpp"
#include "track_model_io.hpp"

using namespace sbr_track_host;

namespace {

struct Options {
    KittiInput in = kitti_input("0006-0010");
    std::string out, model_file;
    unsigned particles = 500;
    bool csv = false, table = false;
    double kf_accel = 3.0, vel0 = 8.0;
    unsigned bench = 0;     // > 0: time per frame with this many targets (synthetic)
    double cv_model = 0.0;  // > 0: the channel tracker uses a constant-velocity model (ablation)
    uint32_t window = 25;
    uint32_t vel_count = 41;   // the constant-velocity model's grid (--cv-model)
    float vel_spacing = 3.5f;
};

// The core's channel tracker behind the baselines' interface: the same track management
// constants, each track's box size and class taken from its last detection.
class ChannelTracker final : public FrameTracker {
public:
    ChannelTracker(const Options &o, const sbr_track_model_t &model, double meas_sigma)
    {
        sbr_track_config_default(&cfg_);
        cfg_.model = &model;
        cfg_.max_targets = 32;
        cfg_.window = o.window;
        cfg_.meas_sigma = static_cast<float>(meas_sigma);
        cfg_.gate = static_cast<float>(kGate);
        cfg_.confirm_hits = kConfirmHits;
        cfg_.max_misses = kMaxMisses;
        ws_.resize(workspace_bytes() / 4 + 1);
        tg_.resize(SBR_TRACK_MAX_TARGETS);
        const sbr_status_t st = sbr_track_init(&trk_, &cfg_, ws_.data(), ws_.size() * 4);
        if (st != SBR_OK) throw std::runtime_error(std::string("tracker init failed: ") + sbr_status_str(st));
    }
    size_t workspace_bytes() const { return sbr_track_workspace_size(&cfg_); }
    std::vector<Hyp> step(const std::vector<Det> &dets) override
    {
        std::vector<sbr_track_detection_t> in;
        for (const Det &d : dets) in.push_back({static_cast<float>(d.x), static_cast<float>(d.y), 1.0f});
        uint32_t n = 0;
        const sbr_status_t st = sbr_track_step(&trk_, kPeriodUs, in.data(), static_cast<uint32_t>(in.size()),
                                               tg_.data(), static_cast<uint32_t>(tg_.size()), &n);
        if (st != SBR_OK && st != SBR_ERR_CAPACITY)
            throw std::runtime_error(std::string("step failed: ") + sbr_status_str(st));
        std::vector<Hyp> out;
        for (uint32_t i = 0; i < n; ++i) {
            const auto &t = tg_[i];
            if (t.detection >= 0) last_[t.id] = dets[static_cast<size_t>(t.detection)];
            if (!(t.flags & SBR_TRACK_CONFIRMED) || t.misses > kReportMisses) continue;
            const Det &d = last_[t.id];
            out.push_back(Hyp{t.id, t.x, t.y, d.w, d.h, d.type});
        }
        return out;
    }

private:
    sbr_track_config_t cfg_{};
    sbr_track_t trk_{};
    std::vector<uint32_t> ws_;
    std::vector<sbr_track_target_t> tg_;
    std::map<uint32_t, Det> last_;  // track id -> its last detection
};

struct Result {
    std::string method;
    Mot mot;
    double ms = 0;
    long frames = 0;
    double ms_per_frame() const { return ms / static_cast<double>(frames); }
};

const char *const kMethods[3] = {"channel", "kalman", "particle"};

// The three methods on one sequence's detections: the reported tracks per frame, the
// time of each step added to res.
void run_seq(const Options &o, const Seq &seq, const std::vector<std::vector<Det>> &dets,
             const sbr_track_model_t &model, double r, std::vector<Result> &res, size_t &workspace,
             std::vector<std::vector<Hyp>> (&outs)[3])
{
    FilterParams fp;
    fp.accel = o.kf_accel;
    fp.r = r;
    fp.vel0 = o.vel0;
    fp.particles = o.particles;
    auto channel = std::make_unique<ChannelTracker>(o, model, r);
    workspace = channel->workspace_bytes();
    std::unique_ptr<FrameTracker> trackers[3] = {std::move(channel), make_kalman(fp, o.in.seed, seq.width, seq.height),
                                                 make_particle(fp, o.in.seed, seq.width, seq.height)};
    for (size_t m = 0; m < 3; ++m) {
        outs[m].resize(seq.gt.size());
        for (size_t f = 0; f < dets.size(); ++f) {
            const auto t0 = std::chrono::steady_clock::now();
            outs[m][f] = trackers[m]->step(dets[f]);
            res[m].ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        }
    }
}

// Every sequence through the three methods, scored; with write_out, each method's tracks
// in KITTI's format under o.out/METHOD/.
std::vector<Result> run_all(const Options &o, const std::vector<Seq> &seqs, const sbr_track_model_t &model,
                            double noise, double miss, double clutter, bool write_out, size_t &workspace)
{
    std::vector<Result> res(3);
    for (size_t m = 0; m < 3; ++m) res[m].method = kMethods[m];
    const double r = std::max(noise, 1.0);
    for (const Seq &seq : seqs) {
        const auto dets = corrupt(seq, noise, miss, clutter, o.in.seed);
        std::vector<std::vector<Hyp>> outs[3];
        run_seq(o, seq, dets, model, r, res, workspace, outs);
        for (size_t m = 0; m < 3; ++m) {
            MotScorer sc;
            for (size_t f = 0; f < seq.gt.size(); ++f) sc.frame(seq.gt[f], outs[m][f]);
            res[m].mot.add(sc.m);
            res[m].frames += static_cast<long>(seq.gt.size());
            if (!write_out) continue;
            const std::string dir = o.out + "/" + res[m].method;
            std::error_code ec;
            std::filesystem::create_directories(dir, ec);
            if (ec) std::cerr << "sbr_track: cannot create " << dir << ": " << ec.message() << "\n";
            write_kitti(dir, seq.name, outs[m]);
        }
    }
    return res;
}

// -1: go on; otherwise the exit status.
int parse_options(int argc, char **argv, Options &o)
{
    CLI::App app{"sbr_track: the channel tracker (paper E) against a Kalman filter with Hungarian association "
                 "and a particle filter on KITTI tracking ground truth, corrupted by noise, misses and clutter "
                 "(docs/usage/track.md); the motion model is learned by sbr_train_track"};
    add_kitti_options(app, o.in);
    app.add_flag("--csv", o.csv, "print method,rmse_px,mota,id_switches,ms_per_frame");
    app.add_option("--out", o.out, "write each method's tracks in KITTI's format to this folder");
    app.add_option("--model", o.model_file, "motion model file from sbr_train_track --model-out (default: the built-in one)");
    app.add_flag("--table", o.table, "print the result as a Markdown table");
    app.add_option("--particles", o.particles, "particle filter size")->check(CLI::Range(16u, 100000u))->capture_default_str();
    app.add_option("--accel", o.kf_accel, "Kalman filter's acceleration noise, pixels per frame squared")
        ->check(sbr_host::finite_range(0.0, 1000.0))
        ->capture_default_str();
    app.add_option("--bench-targets", o.bench, "time per frame with this many synthetic targets (0: KITTI)")
        ->check(CLI::Range(0u, 32u));
    app.add_option("--cv-model", o.cv_model, "> 0: the channel tracker uses a constant-velocity model (ablation)")
        ->check(sbr_host::finite_range(0.0, 1000.0));
    app.add_option("--vel-count", o.vel_count, "(with --cv-model) velocity channels (odd)")
        ->check(CLI::Range(5u, SBR_TRACK_MAX_VEL))
        ->capture_default_str();
    app.add_option("--vel-spacing", o.vel_spacing, "(with --cv-model) pixels per period between velocity channels")
        ->check(sbr_host::finite_range(0.01, 1000.0))
        ->capture_default_str();
    app.add_option("--window", o.window, "the channel tracker's window, channels")->capture_default_str();
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    parse_kitti(o.in);
    return -1;
}

// The motion model: --model's file, the constant-velocity ablation, or the built-in one
// (tables in `loaded`). False, with the reason printed, when it cannot be had.
bool load_model(const Options &o, const Seq &first, sbr_track_model_t &model, sbr_host::TrackModel &loaded)
{
    if (!o.model_file.empty()) {
        const std::string e = sbr_host::load_track_model(o.model_file, loaded);
        if (!e.empty()) {
            std::cerr << "sbr_track: " << e << "\n";
            return false;
        }
        model = loaded.m;
    } else if (o.cv_model > 0.0) {
        loaded.trans.resize(SBR_TRACK_MODEL_TRANSITION_LEN(3, 3, o.vel_count));
        loaded.birth.resize(SBR_TRACK_MODEL_BIRTH_LEN(3, 3, o.vel_count));
        if (sbr_track_model_cv(&model, static_cast<float>(first.width), static_cast<float>(first.height), kPeriod,
                               o.vel_count, o.vel_spacing, static_cast<float>(o.cv_model), static_cast<float>(o.vel0),
                               loaded.trans.data(), loaded.trans.size(), loaded.birth.data(),
                               loaded.birth.size()) != SBR_OK)
            return false;
    } else if (sbr_track_model_kitti(&model) != SBR_OK) {
        return false;
    }
    if (sbr_track_model_check(&model) != SBR_OK) {
        std::cerr << "sbr_track: the model is invalid\n";
        return false;
    }
    return true;
}

void print_results(const Options &o, const std::vector<Result> &res, const sbr_track_model_t &model, size_t workspace)
{
    if (o.csv) {
        std::printf("method,rmse_px,mota,id_switches,ms_per_frame\n");
        for (const auto &r : res)
            std::printf("%s,%.3f,%.4f,%ld,%.4f\n", r.method.c_str(), r.mot.rmse(), r.mot.mota(), r.mot.idsw,
                        r.ms_per_frame());
        return;
    }
    std::printf("sbr_track: sequences %s, noise %.1f px, miss %.2f, clutter %.1f per frame, seed %u\n", o.in.seqs.c_str(),
                o.in.noise, o.in.miss, o.in.clutter, o.in.seed);
    std::printf("channel tracker: 32 targets, window %u, %u velocity channels of %.2f px, %u x %u regions, "
                "workspace %zu bytes, model tables %zu bytes\n",
                o.window, model.vel_count, static_cast<double>(model.vel_spacing), model.regions[0], model.regions[1],
                workspace,
                (SBR_TRACK_MODEL_TRANSITION_LEN(model.regions[0], model.regions[1], model.vel_count) +
                 SBR_TRACK_MODEL_BIRTH_LEN(model.regions[0], model.regions[1], model.vel_count)) *
                    sizeof(float));
    std::printf("| method | RMSE px | MOTA | ID switches | misses | false positives | GT objects | ms/frame |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    for (const auto &r : res)
        std::printf("| %s | %.3f | %.4f | %ld | %ld | %ld | %ld | %.4f |\n", r.method.c_str(), r.mot.rmse(),
                    r.mot.mota(), r.mot.idsw, r.mot.fn, r.mot.fp, r.mot.gt, r.ms_per_frame());
}

// --table: noise 1/3/6 px x miss 0/0.1/0.3.
void print_table(const Options &o, const std::vector<Seq> &seqs, const sbr_track_model_t &model)
{
    std::printf("\n| noise px | miss | channel RMSE | Kalman RMSE | particle RMSE | channel MOTA | Kalman MOTA | particle MOTA |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    size_t workspace = 0;
    for (double nz : {1.0, 3.0, 6.0})
        for (double ms : {0.0, 0.1, 0.3}) {
            const auto t = run_all(o, seqs, model, nz, ms, o.in.clutter, false, workspace);
            std::printf("| %.0f | %.1f | %.3f | %.3f | %.3f | %.4f | %.4f | %.4f |\n", nz, ms, t[0].mot.rmse(),
                        t[1].mot.rmse(), t[2].mot.rmse(), t[0].mot.mota(), t[1].mot.mota(), t[2].mot.mota());
        }
}

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    const int parsed = parse_options(argc, argv, o);
    if (parsed >= 0) return parsed;
    std::vector<Seq> seqs;
    if (o.bench > 0) {
        seqs.push_back(synthetic_seq(o.bench, 300, o.in.seed));
        o.in.seqs = "synthetic";
    } else {
        const int st = load_kitti(o.in, "sbr_track", seqs);
        if (st >= 0) return st;
    }
    sbr_track_model_t model{};
    sbr_host::TrackModel loaded;
    if (!load_model(o, seqs.front(), model, loaded)) return 2;
    try {
        size_t workspace = 0;
        const auto res = run_all(o, seqs, model, o.in.noise, o.in.miss, o.in.clutter, !o.out.empty(), workspace);
        print_results(o, res, model, workspace);
        if (o.table) print_table(o, seqs, model);
        const bool met = res[0].mot.rmse() <= res[1].mot.rmse() && res[0].mot.mota() >= res[1].mot.mota();
        if (!o.csv) std::printf("channel_vs_kalman_target=%s\n", met ? "met" : "not_met");
    } catch (const std::exception &e) {
        std::cerr << "sbr_track: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
