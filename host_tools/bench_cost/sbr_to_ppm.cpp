// sbr_to_ppm: decodes images (JPEG, PNG, ...) with OpenCV and writes them as binary PPM
// (P6, RGB, maxval 255), the form the Cortex-M4 cost image reads through semihosting.
//
//   sbr_to_ppm --out DIR FILE...      writes DIR/<stem>.ppm for each FILE
//
// The host side of `./sbr.sh cost` runs sbr_detect on the same PPM files, so both sides
// see the same pixels.
#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

int main(int argc, char **argv) {
    std::string out;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--out" && i + 1 < argc) out = argv[++i];
        else files.push_back(a);
    }
    if (out.empty() || files.empty()) {
        std::fprintf(stderr, "usage: sbr_to_ppm --out DIR FILE...\n");
        return 2;
    }
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
