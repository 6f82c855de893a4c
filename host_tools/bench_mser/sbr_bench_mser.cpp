// SPDX-License-Identifier: MIT
// sbr_bench_mser: time of sbr_mser_detect() on the maps of recorded frames, as the
// recogniser runs it (sbr_recog_config_default()'s MSER settings: delta 3, variation 0.5,
// both polarities).
//
//   sbr_bench_mser [--data DIR] [--first N] [--images N] [--map intensity|blue]
//                  [--subsample S] [--rounds R] [--peer]
//
// Defaults: --data DATA/gtsdb (DATA: the build's SBR_DATA_DIR) (its FullIJCNN2013 folder when it has one),
// --first 400, --images 20 (frames 00400-00419), --map intensity, --subsample 1,
// --rounds 3. Per frame the best round counts (the least disturbed by other load).
// Prints: images, pixels per map, mean and median ms per map (both polarities), ns per
// pixel and polarity, regions, workspace bytes and a checksum (FNV-1a over the regions'
// bytes) that tells whether two builds find bit-identical regions. Exit status 1 when an
// image cannot be read or a call fails.
// --peer: OpenCV's MSER (cv::MSER::detectRegions(), one thread) is timed on the same map in
// the same run, its rounds alternating with sbr's, with the same delta, area bounds,
// variation bound and diversity; also prints its mean and median ms, its region count and
// time_ratio = sbr's mean time / OpenCV's. The ratio is the figure to compare across
// machines and days: both run on the same core under the same load. They are not the same
// computation: OpenCV also runs both polarities but returns each region's pixel list, and
// defines variation and diversity its own way, so the region counts differ.
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cli_core.hpp"
#include "gtsdb.hpp"

extern "C" {
#include "sbr/map.h"
#include "sbr/mser.h"
#include "sbr/recog.h"
}

namespace {

struct Options {
    std::string data = std::string(SBR_DATA_ROOT) + "/gtsdb", map = "intensity";
    int first = 400, images = 20, subsample = 1, rounds = 3;
    bool peer = false;
};

// -1: go on; otherwise the exit status.
int parse_options(int argc, char **argv, Options &o) {
    CLI::App app{"sbr_bench_mser: time of sbr_mser_detect() on the recogniser's maps of recorded frames"};
    app.add_option("--data", o.data, "GTSDB folder")->capture_default_str();
    app.add_option("--first", o.first, "first image number")->check(CLI::Range(0, 99999999))->capture_default_str();
    app.add_option("--images", o.images, "images")->check(CLI::Range(1, 100000))->capture_default_str();
    app.add_option("--map", o.map, "map kind")->check(CLI::IsMember({"intensity", "blue"}))->capture_default_str();
    app.add_option("--subsample", o.subsample, "map subsampling")->check(CLI::Range(1, 8))->capture_default_str();
    app.add_option("--rounds", o.rounds, "rounds per frame (the best counts)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    app.add_flag("--peer", o.peer, "also time OpenCV's MSER on the same maps");
    return sbr_host::parse_cli(app, argc, argv);
}

// What the frames gave: per frame the best time of sbr (and of OpenCV with --peer), the
// region counts, a checksum of sbr's regions, the last frame's size and workspace.
struct Figures {
    std::vector<double> ms, peer_ms;
    unsigned long long total = 0, peer_total = 0;
    uint64_t sum = sbr_host::kFnvStart;
    size_t pixels = 0, ws_bytes = 0;
};

// FNV-1a of the regions, field by field (the struct has padding).
uint64_t checksum(uint64_t sum, const std::vector<sbr_mser_region_t> &regions, uint32_t count) {
    for (uint32_t i = 0; i < count; ++i) {
        const sbr_mser_region_t &g = regions[i];
        const uint32_t f[9] = {g.bbox.x, g.bbox.y, g.bbox.width, g.bbox.height, g.area,
                               g.seed_x, g.seed_y, g.level, g.polarity};
        sum = sbr_host::fnv1a(sum, f, sizeof f);
        sum = sbr_host::fnv1a(sum, &g.variation, sizeof g.variation);
    }
    return sum;
}

// One frame: its map, then rounds of OpenCV (with --peer) and sbr on it. 0, or the exit
// status.
int frame(const Options &o, int k, const sbr_mser_config_t &cfg, cv::Ptr<cv::MSER> &ocv,
          std::vector<sbr_mser_region_t> &regions, Figures &fig) {
    const sbr_map_kind_t kind = o.map == "blue" ? SBR_MAP_BLUE : SBR_MAP_INTENSITY;
    char name[32];
    std::snprintf(name, sizeof name, "%05d.jpg", o.first + k);
    const std::string path = sbr_host::gtsdb_image_dir(o.data) + "/" + name;
    cv::Mat im = cv::imread(path);
    if (im.empty()) {
        std::fprintf(stderr, "sbr_bench_mser: cannot read %s\n", path.c_str());
        return 1;
    }
    const sbr_image_t src = sbr_host::bgr_view(im);
    std::vector<uint8_t> buf(size_t(im.cols) * size_t(im.rows));
    sbr_image_t mv;
    if (sbr_map_make(&src, kind, uint32_t(o.subsample), buf.data(), uint32_t(im.cols), buf.size(), &mv) != SBR_OK) {
        std::fprintf(stderr, "sbr_bench_mser: sbr_map_make failed on %s\n", name);
        return 1;
    }
    fig.ws_bytes = sbr_mser_workspace_size(&cfg, mv.width, mv.height);
    std::vector<uint32_t> ws(fig.ws_bytes / 4u + 1u);
    fig.pixels = size_t(mv.width) * size_t(mv.height);
    double best = 1e30, peer_best = 1e30;
    uint32_t count = 0;
    size_t peer_count = 0;
    const cv::Mat peer_map(int(mv.height), int(mv.width), CV_8UC1, buf.data(), size_t(mv.stride));  // mv views buf
    for (int r = 0; r < o.rounds; ++r) {
        if (o.peer) {
            std::vector<std::vector<cv::Point>> pts;
            std::vector<cv::Rect> boxes;
            const auto p0 = std::chrono::steady_clock::now();
            ocv->detectRegions(peer_map, pts, boxes);
            const auto p1 = std::chrono::steady_clock::now();
            peer_best = std::min(peer_best, std::chrono::duration<double, std::milli>(p1 - p0).count());
            peer_count = pts.size();
        }
        const auto t0 = std::chrono::steady_clock::now();
        const sbr_status_t st = sbr_mser_detect(&mv, &cfg, ws.data(), fig.ws_bytes, regions.data(),
                                                uint32_t(regions.size()), &count);
        const auto t1 = std::chrono::steady_clock::now();
        if (st != SBR_OK) {
            std::fprintf(stderr, "sbr_bench_mser: sbr_mser_detect failed on %s (%s)\n", name, sbr_status_str(st));
            return 1;
        }
        best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
    fig.ms.push_back(best);
    fig.total += count;
    if (o.peer) {
        fig.peer_ms.push_back(peer_best);
        fig.peer_total += peer_count;
    }
    fig.sum = checksum(fig.sum, regions, count);
    return 0;
}

double mean_of(const std::vector<double> &v) {
    double m = 0.0;
    for (double t : v) m += t;
    return m / double(v.size());
}

double median_of(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char **argv) {
    Options o;
    const int parsed = parse_options(argc, argv, o);
    if (parsed >= 0) return parsed;
    sbr_recog_config_t rc;
    sbr_recog_config_default(&rc);
    const sbr_mser_config_t cfg = rc.parts.mser;
    std::vector<sbr_mser_region_t> regions(1u << 18);
    cv::Ptr<cv::MSER> ocv;
    if (o.peer) {
        cv::setNumThreads(1);
        ocv = cv::MSER::create(int(cfg.delta), int(cfg.min_area), int(cfg.max_area), double(cfg.max_variation),
                               double(cfg.min_diversity));
    }
    Figures fig;
    for (int k = 0; k < o.images; ++k) {
        const int st = frame(o, k, cfg, ocv, regions, fig);
        if (st != 0) return st;
    }
    const double mean = mean_of(fig.ms);
    std::printf("images=%d map=%s subsample=%d pixels=%zu mean_ms=%.2f median_ms=%.2f ns_per_pixel_pass=%.2f "
                "regions=%llu workspace=%zu checksum=%016llx\n",
                o.images, o.map.c_str(), o.subsample, fig.pixels, mean, median_of(fig.ms),
                1e6 * mean / (2.0 * double(fig.pixels)), fig.total, fig.ws_bytes,
                static_cast<unsigned long long>(fig.sum));
    if (o.peer) {
        const double pm = mean_of(fig.peer_ms);
        std::printf("peer=opencv-mser-%s mean_ms=%.2f median_ms=%.2f regions=%llu time_ratio=%.3f\n", CV_VERSION, pm,
                    median_of(fig.peer_ms), fig.peer_total, mean / pm);
    }
    return 0;
}
