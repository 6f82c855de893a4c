// SPDX-License-Identifier: MIT
// sbr_bench_picto: time per box of the recogniser's class stage (picto.h) on recorded
// frames: sbr_picto_features() and sbr_picto_classify() with the built-in classifier.
//
//   sbr_bench_picto [--data DIR] [--images N] [--boxes N] [--rounds R]
//
// Defaults: --data DATA/gtsdb (DATA: the build's SBR_DATA_DIR) (GTSDB images 00400, 00450, 00500, ... of the
// folder or its FullIJCNN2013), --images 3, --boxes 3000 per image, --rounds 15. The
// boxes are fixed (12-130 px, some reaching past the image border), so two builds see the
// same work.
// Per image the best round counts (the least disturbed by other load); the figure is
// the mean over the images. The checksum (FNV-1a over the features' and probabilities'
// bytes) tells whether two builds compute bit-identical results.
// Prints: images, boxes, features_us, classify_us, checksum. Exit status 1 when an image
// cannot be read or a call fails on a box that should be valid.
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "cli_core.hpp"
#include "gtsdb.hpp"

extern "C" {
#include "sbr/picto.h"
#include "sbr/models.h"
}

namespace {

// Box i of the fixed set, scaled to an image of w x h.
void box_of(int i, uint32_t w, uint32_t h, float b[4]) {
    const float s = float(12 + (i % 9) * 13) + 0.5f * float(i % 4);
    const float x = float(-10 + (i * 37) % int(w - 60)) + 0.37f * float(i % 3);
    const float y = float(-10 + (i * 53) % int(h - 40)) + 0.21f * float(i % 7);
    b[0] = x;
    b[1] = y;
    b[2] = x + s * (1.0f + 0.05f * float(i % 3));
    b[3] = y + s;
}

}  // namespace

int main(int argc, char **argv) {
    std::string data = std::string(SBR_DATA_ROOT) + "/gtsdb";
    int images = 3, boxes = 3000, rounds = 15;
    CLI::App app{"sbr_bench_picto: time per box of the class stage's features and classifier"};
    app.add_option("--data", data, "GTSDB folder")->capture_default_str();
    app.add_option("--images", images, "images")->check(CLI::Range(1, 12))->capture_default_str();
    app.add_option("--boxes", boxes, "boxes per round")->check(CLI::Range(1, 10000000))->capture_default_str();
    app.add_option("--rounds", rounds, "rounds (the best counts)")->check(CLI::Range(1, 1000))->capture_default_str();
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    sbr_picto_model_t model;
    if (sbr_picto_gtsdb(&model) != SBR_OK || sbr_picto_check(&model) != SBR_OK) {
        std::fprintf(stderr, "sbr_bench_picto: the built-in classifier fails its check\n");
        return 1;
    }
    std::vector<float> ws(SBR_PICTO_WORKSPACE_SIZE / sizeof(float) + 1);
    std::vector<float> feat(static_cast<size_t>(boxes) * SBR_PICTO_FEATURES);
    std::vector<int> ok(static_cast<size_t>(boxes));
    std::vector<float> prob(SBR_PICTO_MAX_OUTPUTS);
    double feat_us = 0.0, cls_us = 0.0;
    uint64_t sum = sbr_host::kFnvStart;
    for (int k = 0; k < images; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "%05d.jpg", 400 + 50 * k);
        const std::string path = sbr_host::gtsdb_image_dir(data) + "/" + name;
        cv::Mat im = cv::imread(path);
        if (im.empty() || im.cols < 100 || im.rows < 100) {
            std::fprintf(stderr, "sbr_bench_picto: cannot read %s\n", path.c_str());
            return 1;
        }
        const sbr_image_t v = sbr_host::bgr_view(im);
        double best_f = 1e30, best_c = 1e30;
        for (int r = 0; r < rounds; ++r) {
            auto t0 = std::chrono::steady_clock::now();
            for (int i = 0; i < boxes; ++i) {
                float b[4];
                box_of(i, v.width, v.height, b);
                ok[size_t(i)] = sbr_picto_features(&v, b, &feat[size_t(i) * SBR_PICTO_FEATURES], SBR_PICTO_FEATURES,
                                                   ws.data(), SBR_PICTO_WORKSPACE_SIZE) == SBR_OK;
            }
            auto t1 = std::chrono::steady_clock::now();
            for (int i = 0; i < boxes; ++i) {
                if (ok[size_t(i)] &&
                    sbr_picto_classify(&model, &feat[size_t(i) * SBR_PICTO_FEATURES], SBR_PICTO_FEATURES, prob.data(),
                                       SBR_PICTO_MAX_OUTPUTS, ws.data(), SBR_PICTO_WORKSPACE_SIZE) != SBR_OK) {
                    std::fprintf(stderr, "sbr_bench_picto: classify failed on box %d of %s\n", i, name);
                    return 1;
                }
                if (r == 0 && ok[size_t(i)]) sum = sbr_host::fnv1a(sum, prob.data(), prob.size() * sizeof(float));
            }
            auto t2 = std::chrono::steady_clock::now();
            best_f = std::min(best_f, std::chrono::duration<double, std::micro>(t1 - t0).count() / boxes);
            best_c = std::min(best_c, std::chrono::duration<double, std::micro>(t2 - t1).count() / boxes);
        }
        int valid = 0;
        for (int i = 0; i < boxes; ++i) {
            sum = sbr_host::fnv1a(sum, &ok[size_t(i)], sizeof(int));
            if (ok[size_t(i)]) {
                sum = sbr_host::fnv1a(sum, &feat[size_t(i) * SBR_PICTO_FEATURES], SBR_PICTO_FEATURES * sizeof(float));
                ++valid;
            }
        }
        if (valid == 0) {
            std::fprintf(stderr, "sbr_bench_picto: no valid box on %s\n", name);
            return 1;
        }
        feat_us += best_f;
        cls_us += best_c;
    }
    std::printf("images=%d boxes=%d features_us=%.2f classify_us=%.2f checksum=%016llx\n", images, boxes,
                feat_us / images, cls_us / images, static_cast<unsigned long long>(sum));
    return 0;
}
