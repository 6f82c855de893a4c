// SPDX-License-Identifier: MIT
// Seed corpora for the fuzz harnesses (tests/fuzz/), made from real data at set-up and
// never committed:
//   image harnesses (recog, regions, picto, conic): GTSDB crops around annotated signs;
//   contour harnesses (fd, conic): MPEG-7 silhouettes' outer contours;
//   model_io: the built-in models in their file forms (.sbrm, .sbrp, tracker text).
// CAN seeds come from the DBC (tests/fuzz/can_seeds.py, cantools).
//
//   sbr_fuzz_seeds --gtsdb DIR --mpeg7 DIR --out DIR [--per-set N]
//
// A harness reads its parameters from the input's end and bulk bytes (pixels, points)
// from its front (libFuzzer's FuzzedDataProvider), so a seed is the real bytes followed by
// a short tail; the fuzzer mutates both from there.
#include "cli_core.hpp"
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "gtsdb.hpp"
#include "model_io.hpp"
#include "track_model_io.hpp"

extern "C" {
#include "sbr/picto.h"
#include "sbr/recog.h"
#include "sbr/track.h"
#include "sbr/models.h"
}

namespace fs = std::filesystem;

namespace {

bool write(const fs::path &p, const std::string &bytes)
{
    std::ofstream f(p, std::ios::binary);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return static_cast<bool>(f);
}

// A tail of parameter bytes: mostly mid-range values.
std::string tail(unsigned k)
{
    std::string t;
    for (unsigned i = 0; i < 48; ++i) t.push_back(static_cast<char>((37u * (i + k) + 11u) & 0xFFu));
    return t;
}

int gtsdb_seeds(const std::string &root, const fs::path &out, int per_set)
{
    const std::string gt = root + "/FullIJCNN2013/gt.txt";
    const auto boxes = sbr_host::read_gt(gt);
    int n = 0;
    for (const auto &[image, list] : boxes) {
        if (n >= per_set) break;
        char name[32];
        std::snprintf(name, sizeof name, "%05d.jpg", image);
        cv::Mat bgr = cv::imread(root + "/FullIJCNN2013/" + name, cv::IMREAD_COLOR);
        if (bgr.empty()) continue;
        for (const auto &b : list) {
            if (n >= per_set) break;
            // a square of about twice the sign around it, at most 96 px (the harnesses' size)
            const int cx = (b.left + b.right) / 2, cy = (b.top + b.bottom) / 2;
            const int side = std::min(96, std::max(24, 2 * (b.right - b.left + 1)));
            cv::Rect r(cx - side / 2, cy - side / 2, side, side);
            r &= cv::Rect(0, 0, bgr.cols, bgr.rows);
            if (r.width < 8 || r.height < 8) continue;
            cv::Mat crop;
            cv::cvtColor(bgr(r), crop, cv::COLOR_BGR2RGB);
            std::string px(reinterpret_cast<const char *>(crop.clone().data), crop.total() * 3u);
            for (const char *t : {"recog", "regions", "picto"}) {
                write(out / t / ("gtsdb-" + std::to_string(n)), px + tail(static_cast<unsigned>(n)));
            }
            cv::Mat grey;
            cv::cvtColor(crop, grey, cv::COLOR_RGB2GRAY);
            std::string g(reinterpret_cast<const char *>(grey.clone().data), grey.total());
            write(out / "conic" / ("gtsdb-" + std::to_string(n)), g + tail(static_cast<unsigned>(n)));
            ++n;
        }
    }
    return n;
}

int mpeg7_seeds(const std::string &root, const fs::path &out, int per_set)
{
    std::vector<fs::path> files;
    for (const auto &e : fs::directory_iterator(root + "/pbm")) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    int n = 0;
    const size_t step = std::max<size_t>(1, files.size() / static_cast<size_t>(per_set));
    for (size_t i = 0; i < files.size() && n < per_set; i += step) {
        cv::Mat m = cv::imread(files[i].string(), cv::IMREAD_GRAYSCALE);
        if (m.empty()) continue;
        cv::Mat bin = (m == 0); // PBM bit 1 = object, decoded as black
        std::vector<std::vector<cv::Point>> cs;
        cv::findContours(bin, cs, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
        if (cs.empty()) continue;
        const auto &c = *std::max_element(cs.begin(), cs.end(),
                                          [](const auto &a, const auto &b) { return a.size() < b.size(); });
        // up to 300 points, as int16 pairs (the fd harness's integer points) and floats
        std::string pts, ptf;
        const size_t k = std::max<size_t>(1, c.size() / 300);
        for (size_t j = 0; j < c.size(); j += k) {
            const int16_t xy[2] = {static_cast<int16_t>(c[j].x), static_cast<int16_t>(c[j].y)};
            const float f[2] = {static_cast<float>(c[j].x), static_cast<float>(c[j].y)};
            pts.append(reinterpret_cast<const char *>(xy), sizeof xy);
            ptf.append(reinterpret_cast<const char *>(f), sizeof f);
        }
        // the harnesses read points from the end: the tail is the points reversed
        std::string rev(pts.rbegin(), pts.rend()), revf(ptf.rbegin(), ptf.rend());
        write(out / "fd" / ("mpeg7-" + std::to_string(n)), tail(static_cast<unsigned>(n)) + rev);
        write(out / "conic" / ("mpeg7-" + std::to_string(n)), tail(static_cast<unsigned>(n)) + revf);
        ++n;
    }
    return n;
}

int model_seeds(const fs::path &out)
{
    sbr_model_t m{};
    sbr_picto_model_t p{};
    sbr_track_model_t t{};
    if (sbr_model_gtsdb(&m) != SBR_OK || sbr_picto_gtsdb(&p) != SBR_OK || sbr_track_model_kitti(&t) != SBR_OK)
        return 0;
    std::string bytes;
    const sbr_host::Model model = sbr_host::model_from_view(m, &p);
    if (!sbr_host::model_bytes(model, bytes).empty()) return 0;
    write(out / "model_io" / "builtin.sbrm", std::string(1, '\0') + bytes);
    const sbr_host::Picto picto = sbr_host::picto_from_view(p);
    if (!sbr_host::picto_bytes(picto, bytes).empty()) return 0;
    write(out / "model_io" / "builtin.sbrp", std::string(1, '\1') + bytes);
    sbr_host::TrackModel tm;
    tm.m = t;
    tm.trans.assign(t.transition, t.transition + SBR_TRACK_MODEL_TRANSITION_LEN(t.regions[0], t.regions[1], t.vel_count));
    tm.birth.assign(t.birth, t.birth + SBR_TRACK_MODEL_BIRTH_LEN(t.regions[0], t.regions[1], t.vel_count));
    tm.bind();
    if (!sbr_host::track_model_bytes(tm, bytes).empty()) return 0;
    write(out / "model_io" / "kitti.stm", std::string(1, '\2') + bytes);
    return 3;
}

}  // namespace

int main(int argc, char **argv)
{
    std::string gtsdb, mpeg7, out;
    int per_set = 40;
    CLI::App app{"sbr_fuzz_seeds: seed corpora for the fuzz harnesses (tests/fuzz) from real data"};
    app.add_option("--gtsdb", gtsdb, "GTSDB folder (sign crops)");
    app.add_option("--mpeg7", mpeg7, "MPEG-7 folder (contours)");
    app.add_option("--out", out, "corpus root folder")->required();
    app.add_option("--per-set", per_set, "seeds per set")->check(CLI::Range(1, 10000))->capture_default_str();
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    for (const char *t : {"recog", "regions", "picto", "conic", "fd", "model_io"}) fs::create_directories(fs::path(out) / t);
    const int g = gtsdb.empty() ? 0 : gtsdb_seeds(gtsdb, out, per_set);
    const int c = mpeg7.empty() ? 0 : mpeg7_seeds(mpeg7, out, per_set);
    const int mo = model_seeds(out);
    std::printf("seeds: %d GTSDB crops, %d MPEG-7 contours, %d model files -> %s\n", g, c, mo, out.c_str());
    return (mo == 3) ? 0 : 1;
}
