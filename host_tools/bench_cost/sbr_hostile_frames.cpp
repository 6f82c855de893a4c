// SPDX-License-Identifier: MIT
// sbr_hostile_frames: writes the cost benchmark's hostile frames, frames made to cost the
// recogniser as much as a camera could make it (docs/usage/cost.md), as binary PPM (P6,
// RGB, maxval 255), the same pixels on every machine (a fixed linear congruential
// generator, no library's random numbers):
//
//   sbr_hostile_frames --out DIR [--width W] [--height H]
//
//   hostile_noise.ppm         uniform noise, every channel of every pixel
//   hostile_checker.ppm       a black and white checkerboard of 8-pixel cells (each cell
//                             a region above the MSER's smallest area: the most parts)
//   hostile_rings.ppm         a grid of sign-like rings (red rim, white inside, a dark
//                             bar) on grey, 36 px apart: the most sign hypotheses
//   hostile_grey_blocks.ppm   16-pixel blocks of random grey
//   hostile_colour_blocks.ppm 16-pixel blocks of random colour (the colour maps' worst)
//
// Default size 1360 x 800 (a GTSDB frame).
#include "cli_core.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

struct Frame {
    uint32_t w, h;
    std::vector<uint8_t> rgb;
    Frame(uint32_t width, uint32_t height) : w(width), h(height), rgb(size_t(width) * height * 3u, 0) {}
    void set(uint32_t x, uint32_t y, uint8_t r, uint8_t g, uint8_t b) {
        uint8_t *p = &rgb[(size_t(y) * w + x) * 3u];
        p[0] = r;
        p[1] = g;
        p[2] = b;
    }
};

// Numerical Recipes' 32-bit LCG: the same sequence everywhere.
struct Lcg {
    uint32_t s;
    uint8_t next() {
        s = s * 1664525u + 1013904223u;
        return uint8_t(s >> 24);
    }
};

Frame noise(uint32_t w, uint32_t h) {
    Frame f(w, h);
    Lcg g{1u};
    for (auto &v : f.rgb) v = g.next();
    return f;
}

Frame checker(uint32_t w, uint32_t h) {
    Frame f(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const uint8_t v = (((x / 8u) + (y / 8u)) % 2u) ? 255 : 0;
            f.set(x, y, v, v, v);
        }
    return f;
}

Frame rings(uint32_t w, uint32_t h) {
    Frame f(w, h);
    const float pitch = 36.0f, outer = 15.0f, inner = 11.0f;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const float cx = (std::floor(float(x) / pitch) + 0.5f) * pitch;
            const float cy = (std::floor(float(y) / pitch) + 0.5f) * pitch;
            const float dx = float(x) + 0.5f - cx, dy = float(y) + 0.5f - cy;
            const float r = std::sqrt(dx * dx + dy * dy);
            if (r <= inner && std::fabs(dy) < 2.5f && std::fabs(dx) < 7.0f)
                f.set(x, y, 20, 20, 20);  // the bar
            else if (r <= inner)
                f.set(x, y, 245, 245, 245);
            else if (r <= outer)
                f.set(x, y, 200, 30, 40);
            else
                f.set(x, y, 120, 125, 120);
        }
    return f;
}

Frame blocks(uint32_t w, uint32_t h, bool colour, uint32_t seed) {
    Frame f(w, h);
    Lcg g{seed};
    const uint32_t bw = (w + 15u) / 16u, bh = (h + 15u) / 16u;
    std::vector<uint8_t> c(size_t(bw) * bh * 3u);
    for (auto &v : c) v = g.next();
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const uint8_t *b = &c[(size_t(y / 16u) * bw + x / 16u) * 3u];
            if (colour)
                f.set(x, y, b[0], b[1], b[2]);
            else
                f.set(x, y, b[0], b[0], b[0]);
        }
    return f;
}

bool write_ppm(const std::string &path, const Frame &f) {
    FILE *fp = std::fopen(path.c_str(), "wb");
    if (fp == nullptr) return false;
    std::fprintf(fp, "P6\n%u %u\n255\n", f.w, f.h);
    const bool ok = std::fwrite(f.rgb.data(), 1, f.rgb.size(), fp) == f.rgb.size();
    return (std::fclose(fp) == 0) && ok;
}

}  // namespace

int main(int argc, char **argv) {
    std::string out;
    uint32_t w = 1360, h = 800;
    CLI::App app{"sbr_hostile_frames: the cost benchmark's hostile frames as binary PPM"};
    app.add_option("--out", out, "output folder")->required();
    app.add_option("--width", w, "frame width")->check(CLI::Range(16u, 8192u))->capture_default_str();
    app.add_option("--height", h, "frame height")->check(CLI::Range(16u, 8192u))->capture_default_str();
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    std::filesystem::create_directories(out);
    const std::pair<const char *, Frame> frames[] = {
        {"hostile_noise", noise(w, h)},
        {"hostile_checker", checker(w, h)},
        {"hostile_rings", rings(w, h)},
        {"hostile_grey_blocks", blocks(w, h, false, 7u)},
        {"hostile_colour_blocks", blocks(w, h, true, 11u)},
    };
    for (const auto &[name, frame] : frames) {
        const std::string path = (std::filesystem::path(out) / name).string() + ".ppm";
        if (!write_ppm(path, frame)) {
            std::fprintf(stderr, "sbr_hostile_frames: cannot write %s\n", path.c_str());
            return 1;
        }
    }
    return 0;
}
