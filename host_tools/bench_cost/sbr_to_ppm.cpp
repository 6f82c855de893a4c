// SPDX-License-Identifier: MIT
// sbr_to_ppm: decodes images (JPEG, PNG, ...) with OpenCV and writes them as binary PPM
// (P6, RGB, maxval 255), the form the Cortex-M4 cost image reads through semihosting.
//
//   sbr_to_ppm --out DIR FILE...      writes DIR/<stem>.ppm for each FILE
//
// The host side of `./sbr.sh cost` runs sbr_detect on the same PPM files, so both sides
// see the same pixels.
#include "cli_core.hpp"
#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

int main(int argc, char **argv) {
    std::string out;
    std::vector<std::string> files;
    CLI::App app{"sbr_to_ppm: images as binary PPM (the Cortex-M4 cost image reads frames as PPM)"};
    app.add_option("--out", out, "output folder")->required();
    app.add_option("files", files, "images to convert")->required()->check(CLI::ExistingFile);
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    std::filesystem::create_directories(out);
    for (const auto &f : files) {
        const cv::Mat img = cv::imread(f, cv::IMREAD_COLOR);
        const std::string dst = (std::filesystem::path(out) / std::filesystem::path(f).stem()).string() + ".ppm";
        if (img.empty() || !cv::imwrite(dst, img, {cv::IMWRITE_PXM_BINARY, 1})) {
            std::fprintf(stderr, "sbr_to_ppm: cannot convert %s\n", f.c_str());
            return 1;
        }
    }
    return 0;
}
