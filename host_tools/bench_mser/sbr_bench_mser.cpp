// sbr_bench_mser: time of sbr_mser_detect() on the maps of recorded frames, as the
// recogniser runs it (sbr_recog_config_default()'s MSER settings: delta 3, variation 0.5,
// both polarities).
//
//   sbr_bench_mser [--data DIR] [--first N] [--images N] [--map intensity|blue]
//                  [--subsample S] [--rounds R]
//
// Defaults: --data ../shared/data/gtsdb (its FullIJCNN2013 folder when it has one),
// --first 400, --images 20 (frames 00400-00419), --map intensity, --subsample 1,
// --rounds 3. Per frame the best round counts (the least disturbed by other load).
// Prints: images, pixels per map, mean and median ms per map (both polarities), ns per
// pixel and polarity, regions, workspace bytes and a checksum (FNV-1a over the regions'
// bytes) that tells whether two builds find bit-identical regions. Exit status 1 when an
// image cannot be read or a call fails.
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "gtsdb.hpp"

extern "C" {
#include "sbr/map.h"
#include "sbr/mser.h"
#include "sbr/recognizer.h"
}

int main(int argc, char **argv) {
    std::string data = "../shared/data/gtsdb", map = "intensity";
    int first = 400, images = 20, subsample = 1, rounds = 3;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--data") data = next();
        else if (a == "--first") first = std::atoi(next().c_str());
        else if (a == "--images") images = std::atoi(next().c_str());
        else if (a == "--map") map = next();
        else if (a == "--subsample") subsample = std::atoi(next().c_str());
        else if (a == "--rounds") rounds = std::atoi(next().c_str());
        else {
            std::fprintf(stderr,
                         "usage: %s [--data DIR] [--first N] [--images N] [--map intensity|blue] "
                         "[--subsample S] [--rounds R]\n",
                         argv[0]);
            return 2;
        }
    }
    if (first < 0 || images < 1 || subsample < 1 || subsample > 8 || rounds < 1 ||
        (map != "intensity" && map != "blue")) {
        std::fprintf(stderr, "sbr_bench_mser: --first >= 0, --images >= 1, --subsample 1..8, --rounds >= 1, "
                             "--map intensity or blue\n");
        return 2;
    }
    const sbr_map_kind_t kind = map == "blue" ? SBR_MAP_BLUE : SBR_MAP_INTENSITY;
    sbr_recog_config_t rc;
    sbr_recog_config_default(&rc);
    const sbr_mser_config_t cfg = rc.parts.mser;
    std::vector<sbr_mser_region_t> regions(1u << 18);
    std::vector<double> ms;
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
        ws_bytes = sbr_mser_workspace_size(mv.width, mv.height, &cfg);
        std::vector<uint32_t> ws(ws_bytes / 4u + 1u);
        pixels = size_t(mv.width) * size_t(mv.height);
        double best = 1e30;
        uint32_t count = 0;
        for (int r = 0; r < rounds; ++r) {
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
        for (uint32_t i = 0; i < count; ++i) {  // field by field: the struct has padding
            const sbr_mser_region_t &g = regions[i];
            const uint32_t f[9] = {g.bbox.x, g.bbox.y, g.bbox.width, g.bbox.height, g.area,
                                   g.seed_x, g.seed_y, g.level, g.polarity};
            sum = sbr_host::fnv1a(sum, f, sizeof f);
            sum = sbr_host::fnv1a(sum, &g.variation, sizeof g.variation);
        }
    }
    double mean = 0.0;
    for (double t : ms) mean += t;
    mean /= double(ms.size());
    std::sort(ms.begin(), ms.end());
    const double median = ms[ms.size() / 2];
    std::printf("images=%d map=%s subsample=%d pixels=%zu mean_ms=%.2f median_ms=%.2f ns_per_pixel_pass=%.2f "
                "regions=%llu workspace=%zu checksum=%016llx\n",
                images, map.c_str(), subsample, pixels, mean, median, 1e6 * mean / (2.0 * double(pixels)), total,
                ws_bytes, static_cast<unsigned long long>(sum));
    return 0;
}
