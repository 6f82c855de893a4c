// sbr_bench_mser: time of sbr_mser_detect() on the maps of recorded frames, as the
// recogniser runs it (sbr_recog_config_default()'s MSER settings: delta 3, variation 0.5,
// both polarities).
//
//   sbr_bench_mser [--data DIR] [--first N] [--images N] [--map intensity|blue]
//                  [--subsample S] [--rounds R] [--peer]
//
// Defaults: --data ../shared/data/gtsdb (its FullIJCNN2013 folder when it has one),
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
#include "sbr/recognizer.h"
}

int main(int argc, char **argv) {
    std::string data = "../shared/data/gtsdb", map = "intensity";
    int first = 400, images = 20, subsample = 1, rounds = 3;
    bool peer = false;
    CLI::App app{"sbr_bench_mser: time of sbr_mser_detect() on the recogniser's maps of recorded frames"};
    app.add_option("--data", data, "GTSDB folder")->capture_default_str();
    app.add_option("--first", first, "first image number")->check(CLI::Range(0, 99999999))->capture_default_str();
    app.add_option("--images", images, "images")->check(CLI::Range(1, 100000))->capture_default_str();
    app.add_option("--map", map, "map kind")->check(CLI::IsMember({"intensity", "blue"}))->capture_default_str();
    app.add_option("--subsample", subsample, "map subsampling")->check(CLI::Range(1, 8))->capture_default_str();
    app.add_option("--rounds", rounds, "rounds per frame (the best counts)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    app.add_flag("--peer", peer, "also time OpenCV's MSER on the same maps");
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    const sbr_map_kind_t kind = map == "blue" ? SBR_MAP_BLUE : SBR_MAP_INTENSITY;
    sbr_recog_config_t rc;
    sbr_recog_config_default(&rc);
    const sbr_mser_config_t cfg = rc.parts.mser;
    std::vector<sbr_mser_region_t> regions(1u << 18);
    std::vector<double> ms, peer_ms;
    unsigned long long peer_total = 0;
    cv::Ptr<cv::MSER> ocv;
    if (peer) {
        cv::setNumThreads(1);
        ocv = cv::MSER::create(int(cfg.delta), int(cfg.min_area), int(cfg.max_area), double(cfg.max_variation),
                               double(cfg.min_diversity));
    }
    uint64_t sum = sbr_host::kFnvStart;
    unsigned long long total = 0;
    size_t pixels = 0, ws_bytes = 0;
    for (int k = 0; k < images; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "%05d.jpg", first + k);
        const std::string path = sbr_host::gtsdb_image_dir(data) + "/" + name;
        cv::Mat im = cv::imread(path);
        if (im.empty()) {
            std::fprintf(stderr, "sbr_bench_mser: cannot read %s\n", path.c_str());
            return 1;
        }
        const sbr_image_t src = sbr_host::bgr_view(im);
        std::vector<uint8_t> buf(size_t(im.cols) * size_t(im.rows));
        sbr_image_t mv;
        if (sbr_map_make(&src, kind, uint32_t(subsample), buf.data(), uint32_t(im.cols), buf.size(), &mv) != SBR_OK) {
            std::fprintf(stderr, "sbr_bench_mser: sbr_map_make failed on %s\n", name);
            return 1;
        }
        ws_bytes = sbr_mser_workspace_size(&cfg, mv.width, mv.height);
        std::vector<uint32_t> ws(ws_bytes / 4u + 1u);
        pixels = size_t(mv.width) * size_t(mv.height);
        double best = 1e30, peer_best = 1e30;
        uint32_t count = 0;
        size_t peer_count = 0;
        const cv::Mat peer_map(int(mv.height), int(mv.width), CV_8UC1, buf.data(), size_t(mv.stride));  // mv views buf
        for (int r = 0; r < rounds; ++r) {
            if (peer) {
                std::vector<std::vector<cv::Point>> pts;
                std::vector<cv::Rect> boxes;
                const auto p0 = std::chrono::steady_clock::now();
                ocv->detectRegions(peer_map, pts, boxes);
                const auto p1 = std::chrono::steady_clock::now();
                peer_best = std::min(peer_best, std::chrono::duration<double, std::milli>(p1 - p0).count());
                peer_count = pts.size();
            }
            const auto t0 = std::chrono::steady_clock::now();
            const sbr_status_t st = sbr_mser_detect(&mv, &cfg, ws.data(), ws_bytes, regions.data(),
                                                    uint32_t(regions.size()), &count);
            const auto t1 = std::chrono::steady_clock::now();
            if (st != SBR_OK) {
                std::fprintf(stderr, "sbr_bench_mser: sbr_mser_detect failed on %s (%s)\n", name, sbr_status_str(st));
                return 1;
            }
            best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
        }
        ms.push_back(best);
        total += count;
        if (peer) {
            peer_ms.push_back(peer_best);
            peer_total += peer_count;
        }
        for (uint32_t i = 0; i < count; ++i) {  // field by field: the struct has padding
            const sbr_mser_region_t &g = regions[i];
            const uint32_t f[9] = {g.bbox.x, g.bbox.y, g.bbox.width, g.bbox.height, g.area,
                                   g.seed_x, g.seed_y, g.level, g.polarity};
            sum = sbr_host::fnv1a(sum, f, sizeof f);
            sum = sbr_host::fnv1a(sum, &g.variation, sizeof g.variation);
        }
    }
    const auto mean_of = [](const std::vector<double> &v) {
        double m = 0.0;
        for (double t : v) m += t;
        return m / double(v.size());
    };
    const auto median_of = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    };
    const double mean = mean_of(ms);
    const double median = median_of(ms);
    std::printf("images=%d map=%s subsample=%d pixels=%zu mean_ms=%.2f median_ms=%.2f ns_per_pixel_pass=%.2f "
                "regions=%llu workspace=%zu checksum=%016llx\n",
                images, map.c_str(), subsample, pixels, mean, median, 1e6 * mean / (2.0 * double(pixels)), total,
                ws_bytes, static_cast<unsigned long long>(sum));
    if (peer) {
        const double pm = mean_of(peer_ms);
        std::printf("peer=opencv-mser-%s mean_ms=%.2f median_ms=%.2f regions=%llu time_ratio=%.3f\n", CV_VERSION, pm,
                    median_of(peer_ms), peer_total, mean / pm);
    }
    return 0;
}
