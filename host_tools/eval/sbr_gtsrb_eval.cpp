// SPDX-License-Identifier: MIT
// sbr_gtsrb_eval: the class stage on GTSRB crops at their annotated boxes (the fixed
// validation tracks by default): accuracy per superclass, how often "no sign" wins, the
// danger classes' confusions. docs/usage/gtsrb.md.
#include <cstdio>
#include <fstream>
#include <string>

#include "cli.hpp"
#include "gtsrb.hpp"
#include "model_io.hpp"

using namespace sbr_host;

int main(int argc, char **argv) {
    std::string gtsrb = std::string(SBR_DATA_ROOT) + "/gtsrb", picto_path, split = "validation";
    unsigned threads = 2;
    std::string json;
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
