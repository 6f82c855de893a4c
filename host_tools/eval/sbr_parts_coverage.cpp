// SPDX-License-Identifier: MIT
// sbr_parts_coverage: how many annotated signs the recogniser's front end can see whole.
//   sbr_parts_coverage --data DIR [--range A-B] [--delta D] [--variation V] [--diversity X]
//                      [--min-area A] [--min-fill F] [--maps MASK] [--map-subsample I,R,B,Y]
//                      [--map-min-area I,R,B,Y] [--list]
// For every ground-truth box of the images in range it extracts the parts exactly as the
// recogniser does (sbr_recog_config_default()'s part configuration, or the options given)
// and reports the best intersection-over-union between the sign's box and any part's
// bounding box, i.e. whether some region traced the sign's outline. Prints the share of
// signs with a part at IoU >= 0.5 / 0.7 / 0.8, per superclass at 0.5, the map the best
// parts came from and the parts per frame; --list adds one line per sign below 0.5.
// The star model can still find a sign without such a part (inner parts vote for the
// centre and size), so this is a diagnostic of the front end, not a recall bound.
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cli.hpp"
#include "gtsdb.hpp"
#include "model_io.hpp"

extern "C" {
#include "sbr/sbr.h"
}

using namespace sbr_host;

namespace {

struct Options {
    std::string data;
    ImageRanges range{{{400, 599}}};
    bool list = false;
    sbr_parts_config_t cfg;
    uint32_t max_parts = 0;
};

// -1: go on; otherwise the exit status.
int parse_options(int argc, char **argv, Options &o) {
    sbr_recog_config_t rc;
    sbr_recog_config_default(&rc);
    o.cfg = rc.parts;
    o.max_parts = rc.max_parts;
    sbr_parts_config_t &cfg = o.cfg;
    FrontEnd fe;
    CLI::App app{"sbr_parts_coverage: GTSDB signs whose outline some part traced (front-end diagnostic)"};
    app.add_option("--data", o.data, "GTSDB folder")->required();
    add_range_option(app, o.range, "images (default 400-599)");
    app.add_option("--delta", cfg.mser.delta, "MSER delta")->check(CLI::Range(1u, SBR_MSER_MAX_DELTA))->capture_default_str();
    app.add_option("--variation", cfg.mser.max_variation, "MSER max_variation")
        ->check(finite_range(0.0, 100.0))
        ->capture_default_str();
    app.add_option("--diversity", cfg.mser.min_diversity, "MSER min_diversity")
        ->check(finite_range(0.0, 1.0))
        ->capture_default_str();
    app.add_option("--min-area", cfg.mser.min_area, "MSER min_area")->capture_default_str();
    app.add_option("--min-fill", cfg.min_fill, "parts.min_fill")->check(finite_range(0.0, 1.0))->capture_default_str();
    app.add_option("--maps", cfg.maps, "parts.maps (bit k = map kind k)")
        ->check(CLI::Range(1u, (1u << SBR_MAP_KINDS) - 1u))
        ->capture_default_str();
    add_front_end_options(app, fe);
    app.add_flag("--list", o.list, "list every sign with its best part");
    const int parsed = parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    apply_front_end(fe, cfg);
    if (sbr_parts_config_check(&cfg) != SBR_OK) {
        std::fprintf(stderr, "sbr_parts_coverage: invalid part configuration\n");
        return 2;
    }
    return -1;
}

// The counts: signs, those with a part box at IoU >= 0.5 / 0.7 / 0.8, per superclass,
// the map of the best part; frames and parts.
struct Coverage {
    int signs = 0, at5 = 0, at7 = 0, at8 = 0, frames = 0;
    int sc_n[4] = {0, 0, 0, 0}, sc_hit[4] = {0, 0, 0, 0}, best_map[4] = {0, 0, 0, 0};
    double parts_total = 0.0;
};

// One image's signs against its parts (--list: the signs below 0.5).
void add_signs(const std::vector<GtBox> &boxes, const std::vector<sbr_part_t> &parts, uint32_t count, int id,
               bool list, Coverage &c) {
    for (const GtBox &g : boxes) {
        double best = 0.0;
        int map = -1;
        for (uint32_t k = 0; k < count; ++k) {
            const double ov = box_iou(rect_pixbox(parts[k].bbox), gt_pixbox(g));
            if (ov > best) { best = ov; map = parts[k].map; }
        }
        const int sc = superclass_of(g.class_id);
        ++c.signs;
        ++c.sc_n[sc];
        c.at5 += best >= 0.5;
        c.at7 += best >= 0.7;
        c.at8 += best >= 0.8;
        if (best >= 0.5) {
            ++c.sc_hit[sc];
            ++c.best_map[map];
        } else if (list) {
            std::printf("below 0.5: %05d class %d (%s) %dx%d px, best IoU %.2f\n", id, g.class_id,
                        class_name(g.class_id), g.right - g.left + 1, g.bottom - g.top + 1, best);
        }
    }
}

// Every image in range: its parts as the recogniser extracts them. 0, or the exit status.
int measure(const Options &o, const std::string &dir, const std::map<int, std::vector<GtBox>> &gt, Coverage &c) {
    sbr_fft_t fft;
    if (sbr_fft_init(&fft, o.cfg.fd_n) != SBR_OK) return 2;
    std::vector<sbr_part_t> parts(o.max_parts);
    std::vector<uint8_t> ws;
    for (const auto &entry : list_images(dir, o.range)) {
        const int id = image_number(entry);
        const cv::Mat img = cv::imread(entry, cv::IMREAD_COLOR);
        if (img.empty()) {
            std::fprintf(stderr, "sbr_parts_coverage: cannot read %s\n", entry.c_str());
            return 1;
        }
        const sbr_image_t view = bgr_view(img);
        ws.resize(sbr_parts_workspace_size(&o.cfg, view.width, view.height));
        uint32_t count = 0;
        const sbr_status_t st = sbr_parts_extract(&view, &o.cfg, &fft, ws.data(), ws.size(), parts.data(),
                                                  static_cast<uint32_t>(parts.size()), &count, nullptr);
        if (st != SBR_OK && st != SBR_ERR_CAPACITY) {
            std::fprintf(stderr, "sbr_parts_coverage: %s: %s\n", entry.c_str(), sbr_status_str(st));
            return 1;
        }
        ++c.frames;
        c.parts_total += count;
        const auto it = gt.find(id);
        if (it != gt.end()) add_signs(it->second, parts, count, id, o.list, c);
    }
    return 0;
}

void report(const sbr_parts_config_t &cfg, const Coverage &c) {
    std::printf("front end: maps 0x%X, MSER delta %u, variation %.2f, diversity %.2f, min area %u, "
                "min fill %.2f\n", cfg.maps, cfg.mser.delta, static_cast<double>(cfg.mser.max_variation),
                static_cast<double>(cfg.mser.min_diversity), cfg.mser.min_area,
                static_cast<double>(cfg.min_fill));
    std::printf("images %d, parts per frame %.0f, signs %d\n", c.frames, c.parts_total / c.frames, c.signs);
    std::printf("signs with a part box at IoU >= 0.5: %d (%.1f%%), >= 0.7: %d (%.1f%%), >= 0.8: %d (%.1f%%)\n",
                c.at5, 100.0 * c.at5 / c.signs, c.at7, 100.0 * c.at7 / c.signs, c.at8, 100.0 * c.at8 / c.signs);
    for (int s = 0; s < 4; ++s)
        std::printf("  %-12s %d of %d at IoU >= 0.5\n", kSuperclassNames[s], c.sc_hit[s], c.sc_n[s]);
    std::printf("  best part's map (IoU >= 0.5): intensity %d, red %d, blue %d, yellow %d\n", c.best_map[0],
                c.best_map[1], c.best_map[2], c.best_map[3]);
    std::printf("coverage_percent=%.1f\n", 100.0 * c.at5 / c.signs);
}

}  // namespace

int main(int argc, char **argv) {
    Options o;
    const int parsed = parse_options(argc, argv, o);
    if (parsed >= 0) return parsed;
    const std::string dir = gtsdb_image_dir(o.data);
    const auto gt = read_gt(dir + "/gt.txt");
    if (gt.empty()) {
        std::fprintf(stderr, "sbr_parts_coverage: no ground truth in %s\n", dir.c_str());
        return 2;
    }
    Coverage c;
    const int st = measure(o, dir, gt, c);
    if (st != 0) return st;
    if (c.signs == 0) {
        std::fprintf(stderr, "sbr_parts_coverage: no annotated signs in range\n");
        return 2;
    }
    report(o.cfg, c);
    return 0;
}
