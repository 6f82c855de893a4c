// SPDX-License-Identifier: MIT
// The options both tracking tools take (sbr_track, sbr_train_track): the KITTI labels,
// the sequences, the documented corruption and its seed, the classes; and loading the
// sequences they name.
#pragma once

#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "cli_core.hpp"
#include "kitti.hpp"

namespace sbr_track_host {

struct KittiInput {
    std::string labels, seqs;
    double noise = 3.0, miss = 0.1, clutter = 1.0;
    unsigned seed = 1;
    std::set<std::string> classes{"Car", "Cyclist"};
    std::string class_list;  // --classes as given (applied by parse_kitti())
};

// The defaults with `seqs` as the default sequences.
inline KittiInput kitti_input(const std::string &seqs) {
    KittiInput in;
    in.seqs = seqs;
    return in;
}

// --labels, --seqs (default in.seqs), --noise, --miss, --clutter, --seed, --classes.
inline void add_kitti_options(CLI::App &app, KittiInput &in) {
    app.add_option("--labels", in.labels, "KITTI tracking label_02 folder")->required();
    app.add_option("--seqs", in.seqs, "sequences: numbers or ranges, e.g. " + in.seqs + " or 1,3,5")
        ->capture_default_str();
    app.add_option("--noise", in.noise, "detection noise, pixels (Gaussian sigma)")
        ->check(sbr_host::finite_range(0.0, 99.999))
        ->capture_default_str();
    app.add_option("--miss", in.miss, "probability that a detection is missed")
        ->check(sbr_host::finite_range(0.0, 0.999))
        ->capture_default_str();
    app.add_option("--clutter", in.clutter, "false detections per frame (Poisson mean)")
        ->check(sbr_host::finite_range(0.0, 50.0))
        ->capture_default_str();
    app.add_option("--seed", in.seed, "random seed (the corruption; sbr_track: the particle filter too)")->capture_default_str();
    app.add_option("--classes", in.class_list, "KITTI classes, comma-separated (default Car,Cyclist)");
}

// After parsing: --classes into in.classes.
inline void parse_kitti(KittiInput &in) {
    if (in.class_list.empty()) return;
    in.classes.clear();
    for (auto &c : split_list(in.class_list, ',')) in.classes.insert(c);
}

// The sequences of in.seqs into seqs; -1 on success, else the exit status (77: a file is
// not there, so tests skip; 2: no sequence named), the reason printed with `tool`.
inline int load_kitti(const KittiInput &in, const char *tool, std::vector<Seq> &seqs) {
    const std::vector<std::string> names = parse_seqs(in.seqs);
    const std::string e = load_seqs(in.labels, names, in.classes, seqs);
    if (e.empty()) return -1;
    std::fprintf(stderr, "%s: %s\n", tool, e.c_str());
    return names.empty() ? 2 : 77;
}

}  // namespace sbr_track_host
