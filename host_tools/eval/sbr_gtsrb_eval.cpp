// SPDX-License-Identifier: MIT
// sbr_gtsrb_eval: the class stage on GTSRB crops at their annotated boxes (the fixed
// validation tracks by default): accuracy per superclass, how often "no sign" wins, the
// danger classes' confusions; with --tracks, each track's crops in order through the core's
// sign tracking (its class by summed evidence). docs/usage/gtsrb.md.
#include <cstdio>
#include <fstream>
#include <string>

#include "cli.hpp"
#include "gtsrb.hpp"
#include "gtsrb_tracks.hpp"
#include "model_io.hpp"

using namespace sbr_host;

// --tracks: each track's crops through the core's sign tracking; the table (and JSON).
int run_tracks(const sbr_picto_model_t &pm, const std::vector<GtsrbCrop> &crops, const std::string &split,
               const std::string &picto_path, const sbr_signs_config_t &scfg, const std::string &json,
               unsigned threads) {
    std::string err;
    const std::vector<size_t> idx = gtsrb_selection(crops, split == "validation", split == "all");
    const auto probs = classify_gtsrb(pm, crops, idx, threads);
    const std::vector<GtsrbTrack> t = fuse_gtsrb_tracks(crops, idx, probs, int(pm.classes), scfg, err);
    if (t.empty()) {
        std::fprintf(stderr, "sbr_gtsrb_eval: %s\n", err.empty() ? "no tracks" : err.c_str());
        return 1;
    }
    char cfgtxt[96];
    std::snprintf(cfgtxt, sizeof cfgtxt, " (confirm_hits %u, confirm_share %.2f)", scfg.confirm_hits,
                  double(scfg.confirm_share));
    print_gtsrb_tracks(stdout, t, int(scfg.confirm_hits),
                       "GTSRB " + split + " tracks through the sign tracking" + cfgtxt + ", class stage " +
                           (picto_path.empty() ? std::string("built-in") : picto_path) + ":");
    if (!json.empty()) {
        std::ofstream f(json);
        f << gtsrb_tracks_json(t, int(scfg.confirm_hits));
        if (!f) {
            std::fprintf(stderr, "sbr_gtsrb_eval: --json %s: cannot write it\n", json.c_str());
            return 1;
        }
    }
    return 0;
}

int main(int argc, char **argv) {
    std::string gtsrb = std::string(SBR_DATA_ROOT) + "/gtsrb", picto_path, split = "validation";
    unsigned threads = 2;
    std::string json;
    bool tracks = false;
    sbr_signs_config_t scfg;
    sbr_signs_config_default(&scfg);
    CLI::App app{"sbr_gtsrb_eval: the class stage (pictogram classifier) on GTSRB crops at their annotated boxes "
                 "(docs/usage/gtsrb.md)"};
    app.add_option("--gtsrb", gtsrb, "GTSRB folder (holds Final_Training/Images)")->capture_default_str();
    app.add_option("--picto", picto_path, "class stage file (.sbrp; default: the built-in one)");
    app.add_option("--split", split,
                   "validation: the held-out tracks (every fifth track of each class, from its third); "
                   "training: the others; all")
        ->check(CLI::IsMember({"validation", "training", "all"}))
        ->capture_default_str();
    app.add_option("--json", json, "also write the figures as JSON to this file");
    app.add_flag("--tracks", tracks,
                 "each track's crops in order through the core's sign tracking (signs.h): track-level accuracy, "
                 "tracks confirmed wrong, crops until confirmation");
    app.add_option("--confirm-hits", scfg.confirm_hits, "with --tracks: sbr_signs_config_t::confirm_hits")
        ->check(CLI::Range(1, 16))
        ->capture_default_str();
    app.add_option("--confirm-share", scfg.confirm_share, "with --tracks: sbr_signs_config_t::confirm_share")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    app.add_option("--threads", threads, "worker threads")->check(CLI::Range(1, 64))->capture_default_str();
    const int parsed = parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;

    std::string err;
    const std::vector<GtsrbCrop> crops = read_gtsrb(gtsrb, err);
    if (crops.empty()) {
        std::fprintf(stderr, "sbr_gtsrb_eval: --gtsrb %s\n", err.c_str());
        return 2;
    }
    Picto own;
    sbr_picto_model_t builtin{};
    const sbr_picto_model_t *pm = &builtin;
    if (!picto_path.empty()) {
        const std::string e = load_picto(picto_path, own);
        if (!e.empty()) {
            std::fprintf(stderr, "sbr_gtsrb_eval: --picto %s\n", e.c_str());
            return 2;
        }
        pm = &own.view;
    } else {
        sbr_picto_gtsdb(&builtin);
    }
    if (sbr_picto_check(pm) != SBR_OK) {
        std::fprintf(stderr, "sbr_gtsrb_eval: the class stage fails sbr_picto_check()\n");
        return 1;
    }
    if (tracks) return run_tracks(*pm, crops, split, picto_path, scfg, json, threads);
    const GtsrbScore s = score_gtsrb(*pm, crops, split == "validation", split == "all", threads);
    print_gtsrb_score(stdout,
                      s,
                      "GTSRB " + split + " crops, class stage " +
                          (picto_path.empty() ? std::string("built-in") : picto_path) + ":");
    if (!json.empty()) {
        std::ofstream f(json);
        f << gtsrb_score_json(s);
        if (!f) {
            std::fprintf(stderr, "sbr_gtsrb_eval: --json %s: cannot write it\n", json.c_str());
            return 1;
        }
    }
    return 0;
}
