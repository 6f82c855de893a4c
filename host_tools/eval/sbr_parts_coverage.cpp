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


}  // namespace

int main(int argc, char **argv) {
    std::string data;
    int range_a = 400, range_b = 599;
    bool list = false;
    sbr_recog_config_t rc;
    sbr_recog_config_default(&rc);
    sbr_parts_config_t cfg = rc.parts;
    sbr_host::ImageRanges range;
    sbr_host::FrontEnd fe;
    CLI::App app{"sbr_parts_coverage: GTSDB signs whose outline some part traced (front-end diagnostic)"};
    app.add_option("--data", data, "GTSDB folder")->required();
    sbr_host::add_range_option(app, range, "one span of image numbers (default 400-599)");
    app.add_option("--delta", cfg.mser.delta, "MSER delta")->check(CLI::Range(1u, SBR_MSER_MAX_DELTA))->capture_default_str();
    app.add_option("--variation", cfg.mser.max_variation, "MSER max_variation")
        ->check(sbr_host::finite_range(0.0, 100.0))
        ->capture_default_str();
    app.add_option("--diversity", cfg.mser.min_diversity, "MSER min_diversity")
        ->check(sbr_host::finite_range(0.0, 1.0))
        ->capture_default_str();
    app.add_option("--min-area", cfg.mser.min_area, "MSER min_area")->capture_default_str();
    app.add_option("--min-fill", cfg.min_fill, "parts.min_fill")->check(sbr_host::finite_range(0.0, 1.0))->capture_default_str();
    app.add_option("--maps", cfg.maps, "parts.maps (bit k = map kind k)")
        ->check(CLI::Range(1u, (1u << SBR_MAP_KINDS) - 1u))
        ->capture_default_str();
    sbr_host::add_front_end_options(app, fe);
    app.add_flag("--list", list, "list every sign with its best part");
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    if (range.spans.size() > 1) {
        std::fprintf(stderr, "sbr_parts_coverage: --range takes one span A-B\n");
        return 2;
    }
    if (!range.empty()) {
        range_a = range.spans[0].first;
        range_b = range.spans[0].second;
    }
    sbr_host::apply_front_end(fe, cfg);
    if (sbr_parts_config_check(&cfg) != SBR_OK) {
        std::fprintf(stderr, "sbr_parts_coverage: invalid part configuration\n");
        return 2;
    }
    const std::string dir = gtsdb_image_dir(data);
    const auto gt = read_gt(dir + "/gt.txt");
    if (gt.empty()) {
        std::fprintf(stderr, "sbr_parts_coverage: no ground truth in %s\n", dir.c_str());
        return 2;
    }
    sbr_fft_t fft;
    if (sbr_fft_init(&fft, cfg.fd_n) != SBR_OK) return 2;
    std::vector<sbr_part_t> parts(rc.max_parts);
    std::vector<uint8_t> ws;
    int signs = 0, at5 = 0, at7 = 0, at8 = 0, frames = 0;
    int sc_n[4] = {0, 0, 0, 0}, sc_hit[4] = {0, 0, 0, 0}, best_map[4] = {0, 0, 0, 0};
    double parts_total = 0.0;
    for (const auto &entry : list_images(dir)) {
        const int id = image_number(entry);
        if (id < range_a || id > range_b) continue;
        const auto it = gt.find(id);
        const cv::Mat img = cv::imread(entry, cv::IMREAD_COLOR);
        if (img.empty()) {
            std::fprintf(stderr, "sbr_parts_coverage: cannot read %s\n", entry.c_str());
            return 1;
        }
        const sbr_image_t view = bgr_view(img);
        ws.resize(sbr_parts_workspace_size(&cfg, view.width, view.height));
        uint32_t count = 0;
        const sbr_status_t st = sbr_parts_extract(&view, &cfg, &fft, ws.data(), ws.size(), parts.data(),
                                                  static_cast<uint32_t>(parts.size()), &count, nullptr);
        if (st != SBR_OK && st != SBR_ERR_CAPACITY) {
            std::fprintf(stderr, "sbr_parts_coverage: %s: %s\n", entry.c_str(), sbr_status_str(st));
            return 1;
        }
        ++frames;
        parts_total += count;
        if (it == gt.end()) continue;
        for (const GtBox &g : it->second) {
            double best = 0.0;
            int map = -1;
            for (uint32_t k = 0; k < count; ++k) {
                const double o = box_iou(rect_pixbox(parts[k].bbox), gt_pixbox(g));
                if (o > best) { best = o; map = parts[k].map; }
            }
            const int sc = superclass_of(g.class_id);
            ++signs;
            ++sc_n[sc];
            at5 += best >= 0.5;
            at7 += best >= 0.7;
            at8 += best >= 0.8;
            if (best >= 0.5) {
                ++sc_hit[sc];
                ++best_map[map];
            } else if (list) {
                std::printf("below 0.5: %05d class %d (%s) %dx%d px, best IoU %.2f\n", id, g.class_id,
                            class_name(g.class_id), g.right - g.left + 1, g.bottom - g.top + 1, best);
            }
        }
    }
    if (signs == 0) {
        std::fprintf(stderr, "sbr_parts_coverage: no annotated signs in range\n");
        return 2;
    }
    std::printf("front end: maps 0x%X, MSER delta %u, variation %.2f, diversity %.2f, min area %u, "
                "min fill %.2f\n", cfg.maps, cfg.mser.delta, static_cast<double>(cfg.mser.max_variation),
                static_cast<double>(cfg.mser.min_diversity), cfg.mser.min_area,
                static_cast<double>(cfg.min_fill));
    std::printf("images %d, parts per frame %.0f, signs %d\n", frames, parts_total / frames, signs);
    std::printf("signs with a part box at IoU >= 0.5: %d (%.1f%%), >= 0.7: %d (%.1f%%), >= 0.8: %d (%.1f%%)\n",
                at5, 100.0 * at5 / signs, at7, 100.0 * at7 / signs, at8, 100.0 * at8 / signs);
    for (int s = 0; s < 4; ++s)
        std::printf("  %-12s %d of %d at IoU >= 0.5\n", kSuperclassNames[s], sc_hit[s], sc_n[s]);
    std::printf("  best part's map (IoU >= 0.5): intensity %d, red %d, blue %d, yellow %d\n", best_map[0],
                best_map[1], best_map[2], best_map[3]);
    std::printf("coverage_percent=%.1f\n", 100.0 * at5 / signs);
    return 0;
}
