// SPDX-License-Identifier: MIT
// sbr_train_track: learns the channel tracker's motion model (paper E) from KITTI
// tracking box centres without track ids (motion_learning.hpp), writes it as a model file
// (sbr_track --model) and/or as the generated C table of the built-in model
// (lib/models/sbr_track_model_kitti.c; ./sbr.sh learn-tracker).
#include "cli_core.hpp"
#include <cstdio>
#include <iostream>
#include <set>
#include <string>
#include <vector>

extern "C" {
#include "sbr/track.h"
#include "sbr/models.h"
}

#include "kitti.hpp"
#include "kitti_cli.hpp"
#include "motion_learning.hpp"
#include "track_model_io.hpp"

using namespace sbr_track_host;

namespace {

struct Options {
    KittiInput in = kitti_input("0000-0005");
    std::string model_out, c_out;
    LearnParams learn;
};

// -1: go on; otherwise the exit status.
int parse_options(int argc, char **argv, Options &o)
{
    CLI::App app{"sbr_train_track: learn the channel tracker's motion model from KITTI tracking labels without "
                 "track ids (docs/usage/track.md)"};
    add_kitti_options(app, o.in);
    app.add_option("--model-out", o.model_out, "write the learned model file here (sbr_track --model)");
    app.add_option("--c-out", o.c_out, "write the learned model as a generated C table here");
    app.add_option("--vel-count", o.learn.vel_count, "velocity channels (odd)")
        ->check(CLI::Range(5u, SBR_TRACK_MAX_VEL))
        ->capture_default_str();
    app.add_option("--vel-spacing", o.learn.vel_spacing, "pixels per period between velocity channels")
        ->check(sbr_host::finite_range(0.01, 1000.0))
        ->capture_default_str();
    app.add_option("--em", o.learn.em_iters, "passes of the soft association EM")
        ->check(CLI::Range(0, 100))
        ->capture_default_str();
    app.add_option("--tail", o.learn.tail, "share of a row given to the wide constant-velocity tail")
        ->check(sbr_host::finite_range(0.0, 1.0))
        ->capture_default_str();
    app.add_option("--tail-sigma", o.learn.tail_sigma, "the tail's standard deviation, velocity channels")
        ->check(sbr_host::finite_range(0.01, 1000.0))
        ->capture_default_str();
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    parse_kitti(o.in);
    return -1;
}

// The generated table's opening comment: how to regenerate it, from what, under which terms.
std::string c_header(const Options &o, const sbr_host::TrackModel &d, const LearnStats &st)
{
    char hdr[1024];
    std::snprintf(hdr, sizeof hdr,
                  " * Regenerate: ./sbr.sh learn-tracker   (runs sbr_train_track --seqs %s --noise %g\n"
                  " *             --miss %g --clutter %g --seed %u --c-out lib/models/sbr_track_model_kitti.c\n"
                  " *             on KITTI tracking label_02, classes Car and Cyclist)\n"
                  " * Learned from %ld detection triples and %ld pairs, without track ids (%d passes of\n"
                  " * soft-association EM). %u x %u regions, %u velocity channels of %.2f px.\n"
                  " * Data: KITTI (Geiger, Lenz, Urtasun, CVPR 2012), CC BY-NC-SA 3.0: research use.\n",
                  o.in.seqs.c_str(), o.in.noise, o.in.miss, o.in.clutter, o.in.seed, st.triples, st.pairs, o.learn.em_iters,
                  d.m.regions[0], d.m.regions[1], d.m.vel_count, static_cast<double>(d.m.vel_spacing));
    return hdr;
}

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    const int parsed = parse_options(argc, argv, o);
    if (parsed >= 0) return parsed;
    std::vector<Seq> seqs;
    const int ls = load_kitti(o.in, "sbr_train_track", seqs);
    if (ls >= 0) return ls;
    std::vector<std::vector<std::vector<Det>>> dets;
    for (const Seq &s : seqs) dets.push_back(corrupt(s, o.in.noise, o.in.miss, o.in.clutter, o.in.seed));
    LearnStats stats;
    sbr_host::TrackModel d = learn_motion_model(seqs, dets, o.learn, stats);
    const sbr_status_t st = sbr_track_model_check(&d.m);
    std::printf("learned from %zu sequences (%s), %ld detection triples, %ld pairs, no track ids: %s\n", seqs.size(),
                o.in.seqs.c_str(), stats.triples, stats.pairs, sbr_status_str(st));
    if (st != SBR_OK) return 1;
    std::string e;
    if (!o.model_out.empty()) e = sbr_host::save_track_model(d, o.model_out);
    if (e.empty() && !o.c_out.empty()) e = write_model_c(d, o.c_out, c_header(o, d, stats));
    if (!e.empty()) {
        std::cerr << "sbr_train_track: " << e << "\n";
        return 1;
    }
    return 0;
}
