// SPDX-License-Identifier: MIT
// sbr_canlog: writes the CAN traffic sbr sends for a detections file, as a candump log.
//   sbr_canlog --detections FILE --out LOG [--images N] [--first K]
// FILE has GTSDB's format with an optional score: NNNNN.ext;left;top;right;bottom;class[;score]
// (sbr_detect's output, or GTSDB's gt.txt with score 1). Images K .. K+N-1 are one CAN
// cycle each (100 ms apart), whether or not they have detections.
#include "cli_core.hpp"
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "can_output.hpp"
#include "detection.hpp"

int main(int argc, char **argv) {
    std::string det_path, out_path;
    int images = 600, first = 0;
    CLI::App app{"sbr_canlog: a detections file as the CAN frames the ECU would send (candump log, dbc/sbr.dbc)"};
    app.add_option("--detections", det_path, "detections, NNNNN.ext;left;top;right;bottom;class_id[;score]")
        ->required();
    app.add_option("--out", out_path, "the candump log to write")->required();
    app.add_option("--images", images, "images (frames) to write")->check(CLI::Range(1, 100000000))->capture_default_str();
    app.add_option("--first", first, "number of the first image")->check(CLI::Range(0, 99999999))->capture_default_str();
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    std::ifstream in(det_path);
    if (!in) { std::fprintf(stderr, "sbr_canlog: cannot read %s\n", det_path.c_str()); return 1; }
    std::map<int, std::vector<sbr_detection_t>> by_image;
    std::string line;
    size_t lines = 0;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        sbr_host::Detection d;
        sbr_detection_t c{};
        if (!sbr_host::parse_detection_line(line, d) || !sbr_host::to_core(d, c)) {
            std::fprintf(stderr, "sbr_canlog: bad line: %s\n", line.c_str());
            return 1;
        }
        by_image[d.image].push_back(c);
        ++lines;
    }
    sbr_host::CanLogWriter w(out_path);
    if (!w.ok()) { std::fprintf(stderr, "sbr_canlog: cannot write %s\n", out_path.c_str()); return 1; }
    for (int img = first; img < first + images; ++img) {
        auto it = by_image.find(img);
        static const std::vector<sbr_detection_t> none;
        if (w.write_image(it == by_image.end() ? none : it->second, 0.0f, 0, false) < 0) {
            std::fprintf(stderr, "sbr_canlog: CAN output failed at image %d\n", img);
            return 1;
        }
    }
    std::printf("sbr_canlog: %zu detections, %d images, %u frames, %u results dropped -> %s\n",
                lines, images, w.frames_written(), w.results_dropped(), out_path.c_str());
    return 0;
}
