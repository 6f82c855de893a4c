// SPDX-License-Identifier: MIT
// The annotated pictures (host_tools/common/annotate.hpp) and the image checks of
// sbr_detect (image_file_problem() in gtsdb.hpp):
//  - a constructed scene with a known found sign, a known false detection and a known
//    missed sign: the judgement, and the pixels (the false detection's box magenta, the
//    missed sign's box dashed white and black, the found one in its superclass's colour,
//    nothing filled, no magenta elsewhere); labels inside the image and apart, also for
//    crowded boxes at the image's edges;
//  - the contact sheet keeps the worst images, worst first, and a tile holds its labels;
//  - the class names are the DBC's (--dbc);
//  - truncated and empty JPEG, PNG and PPM files are named as such, whole ones pass;
//  - with --detect and --data: sbr_detect on GTSDB 00444 with a ground truth that leaves
//    out one of its signs (a known false detection) and adds one in the sky (a known miss):
//    the annotated JPEG has magenta on the first's box and dashes on the second's; a
//    folder with a truncated JPEG beside a whole one exits with status 3 and names it; a
//    folder that does not exist is named as such (status 2, docs/usage/exit-status.md).
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "annotate.hpp"
#include "gtsdb.hpp"

#include "test_help.hpp"

namespace fs = std::filesystem;
using namespace sbr_host;

namespace {

int failures = 0;

void check(bool ok, const std::string &what) {
    if (!ok) {
        std::printf("FAIL %s\n", what.c_str());
        ++failures;
    }
}

// A detection on image 444 with the inclusive box l..r x t..b (as a detection file gives it).
Detection det(int l, int t, int r, int b, int cls, double score) {
    return {444, from_inclusive(l, t, r, b), cls, score};
}

cv::Vec3b px(const cv::Mat &m, int x, int y) { return m.at<cv::Vec3b>(y, x); }
bool is(const cv::Vec3b &p, const cv::Scalar &c) { return p[0] == c[0] && p[1] == c[1] && p[2] == c[2]; }

bool inside(const cv::Rect &r, const cv::Mat &m) { return r.x >= 0 && r.y >= 0 && r.x + r.width <= m.cols && r.y + r.height <= m.rows; }

// Labels inside the image and pairwise disjoint.
void check_labels(const std::vector<cv::Rect> &labels, const cv::Mat &img, const std::string &what) {
    for (size_t i = 0; i < labels.size(); ++i) {
        check(inside(labels[i], img), what + ": label " + std::to_string(i) + " inside the image");
        for (size_t j = i + 1; j < labels.size(); ++j)
            check((labels[i] & labels[j]).area() == 0, what + ": labels " + std::to_string(i) + " and " +
                                                           std::to_string(j) + " apart");
    }
}

void test_constructed_scene() {
    cv::Mat img(200, 320, CV_8UC3, cv::Scalar(128, 128, 128));
    // A (class 1) found, B (class 14) false, C (class 25) missed, D (class 2) found at the right edge
    const std::vector<Detection> dets = {det(40, 60, 79, 99, 1, 0.9), det(150, 60, 189, 99, 14, 0.7),
                                       det(290, 10, 319, 39, 2, 0.8)};
    const std::vector<GtBox> gts = {{40, 60, 79, 99, 1}, {230, 120, 269, 159, 25}, {291, 11, 319, 39, 2}};
    const std::vector<Mark> marks = judge(dets, gts, true);
    check(marks.size() == 4, "three detections and one missed sign");
    if (marks.size() != 4) return;
    check(marks[0].kind == MarkKind::kFound && marks[1].kind == MarkKind::kFalse &&
              marks[2].kind == MarkKind::kFound && marks[3].kind == MarkKind::kMissed && marks[3].class_id == 25,
          "the judgement: found, false, found, missed 25");
    check(judge(dets, gts, false)[1].kind == MarkKind::kDetected, "no ground truth: plain detections");
    const std::vector<cv::Rect> labels = draw_marks(img, marks);
    check(is(px(img, 150, 80), kFalseColour) && is(px(img, 189, 80), kFalseColour) &&
              is(px(img, 170, 99), kFalseColour),
          "the false detection's box is magenta");
    check(is(px(img, 40, 80), superclass_colour(1)) && is(px(img, 40, 80), cv::Scalar(0, 0, 255)),
          "the found prohibitory sign's box is red");
    int white = 0, black = 0, changes = 0;
    for (int x = 231; x < 269; ++x) {
        const cv::Vec3b p = px(img, x, 120);
        white += is(p, cv::Scalar(255, 255, 255));
        black += is(p, cv::Scalar(0, 0, 0));
        changes += p != px(img, x - 1, 120);
    }
    check(white >= 12 && black >= 12 && changes >= 4, "the missed sign's top edge is dashed white and black (white " +
                                                          std::to_string(white) + ", black " + std::to_string(black) +
                                                          ", changes " + std::to_string(changes) + ")");
    check(is(px(img, 250, 140), cv::Scalar(128, 128, 128)) && is(px(img, 170, 80), cv::Scalar(128, 128, 128)),
          "boxes are not filled");
    long stray = 0;
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x) {
            const cv::Point p(x, y);
            const bool near_b = cv::Rect(148, 58, 44, 44).contains(p) || labels[1].contains(p);
            if (!near_b && is(px(img, x, y), kFalseColour)) ++stray;
        }
    check(stray == 0, "magenta only on the false detection and its label (" + std::to_string(stray) + " stray)");
    check_labels(labels, img, "scene");
    check(labels[2].x + labels[2].width <= img.cols, "the right-edge label is not cut");
}

void test_crowded_labels() {
    cv::Mat img(120, 200, CV_8UC3, cv::Scalar(90, 90, 90));
    std::vector<Mark> marks;
    for (int k = 0; k < 6; ++k)  // a column of touching boxes at the left edge, another at the right
        marks.push_back({{double(k % 2 ? 180 : 0), double(20 * (k / 2) + 2), double(k % 2 ? 200 : 20),
                          double(20 * (k / 2) + 20)},
                         20 + k, 0.5, MarkKind::kFound});
    check_labels(draw_marks(img, marks), img, "crowded");
}

std::string read_text(const std::string &path) {
    std::ifstream s(path);
    return std::string((std::istreambuf_iterator<char>(s)), std::istreambuf_iterator<char>());
}

void test_worst_images() {
    WorstImages worst(2);
    const cv::Mat img(300, 400, CV_8UC3, cv::Scalar(50, 50, 50));
    const Mark missed{{100, 100, 130, 130}, 25, 0.0, MarkKind::kMissed};
    const Mark fp{{200, 100, 230, 130}, 14, 0.6, MarkKind::kFalse};
    const Mark found{{10, 10, 40, 40}, 1, 0.9, MarkKind::kFound};
    worst.offer("00001", img, {found}, {});
    check(worst.size() == 0, "an image without errors is not kept");
    worst.offer("00002", img, {fp}, {});
    worst.offer("00003", img, {missed, fp}, {});
    worst.offer("00004", img, {missed}, {});
    check(worst.size() == 2, "the two worst kept");
    const std::string path = (fs::temp_directory_path() / "sbr_test_overview.png").string();
    check(worst.write(path), "the sheet is written");
    const cv::Mat sheet = cv::imread(path);
    check(sheet.cols == 6 + 3 * (420 + 6) && sheet.rows > 280, "the sheet's size");
    fs::remove(path);
    // a missed sign at the right edge with its label to its left: the tile keeps the label
    // whole (a crop around the box alone would start at x 1135 and cut it)
    WorstImages edge(1);
    const cv::Mat frame(800, 1360, CV_8UC3, cv::Scalar(50, 50, 50));
    const Mark far{{1300, 400, 1331, 431}, 42, 0.0, MarkKind::kMissed};
    const cv::Rect label(1100, 400, 196, 20);
    edge.offer("00005", frame, {far}, {label});
    check(edge.size() == 1 && (edge.crop(0) & label) == label && (edge.crop(0) & cv::Rect(1300, 400, 31, 31)) ==
                                                                      cv::Rect(1300, 400, 31, 31),
          "the tile holds the missed sign and its whole label");
}

// The one table of class names is the DBC's: every value name of SBR_Sign_Class in
// dbc/sbr.dbc equals class_name() of its id.
void test_class_names(const std::string &dbc) {
    const std::string text = read_text(dbc);
    const size_t at = text.find("VAL_ 768 SBR_Sign_Class ");
    check(at != std::string::npos, "the DBC has SBR_Sign_Class's value names");
    if (at == std::string::npos) return;
    std::istringstream is(text.substr(at + 24, text.find(';', at) - at - 24));
    int id = 0, seen = 0;
    std::string quoted;
    while (is >> id >> std::quoted(quoted)) {
        if (id > 42) continue;
        ++seen;
        check(quoted == class_name(id), "class " + std::to_string(id) + ": DBC '" + quoted + "', table '" +
                                            class_name(id) + "'");
    }
    check(seen == 43, "43 class names in the DBC (" + std::to_string(seen) + ")");
}

void write_bytes(const std::string &path, const std::vector<uchar> &b, size_t n) {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char *>(b.data()), std::streamsize(n));
}

void test_file_problems() {
    const fs::path dir = fs::temp_directory_path() / "sbr_test_files";
    fs::create_directories(dir);
    cv::Mat img(64, 80, CV_8UC3);
    cv::randu(img, 0, 255);
    for (const std::string ext : {".jpg", ".png", ".ppm"}) {
        std::vector<uchar> b;
        cv::imencode(ext, img, b);
        const std::string whole = (dir / ("whole" + ext)).string(), cut = (dir / ("cut" + ext)).string();
        write_bytes(whole, b, b.size());
        write_bytes(cut, b, b.size() * 2 / 3);
        check(image_file_problem(whole).empty(), ext + " whole: no problem (" + image_file_problem(whole) + ")");
        check(image_file_problem(cut).find("truncated") == 0, ext + " cut: truncated (" + image_file_problem(cut) + ")");
    }
    write_bytes((dir / "empty.jpg").string(), {}, 0);
    check(image_file_problem((dir / "empty.jpg").string()) == "empty file", "empty file");
    fs::remove_all(dir);
}

// sbr_detect end to end on GTSDB 00444 with a constructed ground truth.
void test_sbr_detect(const std::string &detect, const std::string &data, const std::string &work) {
    const std::string src = (fs::path(gtsdb_image_dir(data)) / "00444.jpg").string();
    if (!fs::is_regular_file(src)) { std::printf("no %s: end-to-end part skipped\n", src.c_str()); return; }
    fs::remove_all(work);
    fs::create_directories(fs::path(work) / "in");
    fs::copy_file(src, fs::path(work) / "in" / "00444.jpg");
    // the sign at 972,572 left out (its detection is false), a "road works" sign in the sky (missed)
    std::ofstream(fs::path(work) / "in" / "gt.txt") << "00444.ppm;379;528;427;573;20\n00444.ppm;964;531;1009;573;20\n"
                                                        "00444.ppm;389;569;419;600;7\n00444.ppm;600;150;650;200;25\n";
    const std::string cmd = detect + " --input " + work + "/in --quiet --detections " + work + "/det.txt --annotated " +
                            work + "/ann --overview " + work + "/overview.png --summary " + work + "/summary.txt >/dev/null";
    check(std::system(cmd.c_str()) == 0, "sbr_detect runs");
    const cv::Mat a = cv::imread(work + "/ann/00444.jpg");
    check(!a.empty() && fs::is_regular_file(work + "/overview.png"), "annotated image and overview written");
    if (a.empty()) return;
    std::ifstream f(work + "/det.txt");
    bool seen = false;
    for (std::string line; std::getline(f, line);) {
        Detection det_line;
        if (!parse_detection_line(line, det_line) || det_line.class_id != 7) continue;
        const InclusiveBox d = to_inclusive(det_line.box);
        if (d.left < 900) continue;
        seen = true;
        int magenta = 0;
        for (int y = int(d.top) + 3; y <= int(d.bottom) - 3; ++y) {
            const cv::Vec3b p = px(a, int(d.left), y);
            magenta += p[0] > 170 && p[2] > 170 && p[1] < 110;
        }
        check(magenta >= int(d.bottom - d.top) - 8, "the false detection's left edge is magenta (" +
                                                        std::to_string(magenta) + " px)");
    }
    check(seen, "the sign left out of the ground truth is detected (the known false detection)");
    int bright = 0, dark = 0;
    for (int x = 602; x < 648; ++x) {
        const cv::Vec3b p = px(a, x, 150);
        bright += p[0] > 215 && p[1] > 215 && p[2] > 215;
        dark += p[0] < 60 && p[1] < 60 && p[2] < 60;
    }
    check(bright >= 10 && dark >= 10, "the missed sign's box in the sky is dashed (bright " + std::to_string(bright) +
                                          ", dark " + std::to_string(dark) + ")");
    const cv::Vec3b sw = px(a, 8, a.rows - 9);  // the legend's first swatch: prohibitory red
    check(sw[2] > 180 && sw[1] < 90 && sw[0] < 90, "the legend at the bottom left starts with the red swatch");
    const std::string text = read_text(work + "/summary.txt");
    check(text.find("1 signs missed (dashed boxes), 1 false detections") != std::string::npos,
          "the summary counts one miss and one false detection");
}

int exit_status(const std::string &cmd) {
    const int st = std::system(cmd.c_str());
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

// A truncated JPEG is a failed image (status 3, named in the summary), the whole one is
// still processed; a missing folder is named.
void test_failed_images(const std::string &detect, const std::string &data, const std::string &work) {
    const std::string src = (fs::path(gtsdb_image_dir(data)) / "00444.jpg").string();
    if (!fs::is_regular_file(src)) return;
    const fs::path dir = fs::path(work) / "bad";
    fs::create_directories(dir);
    fs::copy_file(src, dir / "00444.jpg", fs::copy_options::overwrite_existing);
    fs::copy_file(src, dir / "00445.jpg", fs::copy_options::overwrite_existing);
    fs::resize_file(dir / "00445.jpg", fs::file_size(dir / "00445.jpg") / 2);
    const std::string out = work + "/bad_out";
    const int st = exit_status(detect + " --input " + dir.string() + " --quiet --detections " + out + ".txt --summary " +
                               out + ".summary >/dev/null 2>" + out + ".err");
    check(st == 3, "some images failed: exit status 3 (" + std::to_string(st) + ")");
    const std::string summary = read_text(out + ".summary");
    check(summary.find("(2 images, 1 failed)") != std::string::npos &&
              summary.find("failed: 00445.jpg: truncated JPEG") != std::string::npos,
          "the summary counts and names the truncated image");
    check(read_text(out + ".txt").find("00444.jpg;") == 0, "the whole image is still processed");
    const int missing = exit_status(detect + " --input " + work + "/no-such-folder --detections " + out +
                                    "2.txt >/dev/null 2>" + out + ".err2");
    check(missing == 2 && read_text(out + ".err2").find("no such folder") != std::string::npos,
          "a missing folder is named (status " + std::to_string(missing) + ")");
}

}  // namespace

int main(int argc, char **argv) {
    static const char *const options[] = {"--detect", "--data", "--work", "--dbc", nullptr};
    const int h = test_help(argc, argv, "test_annotate: the annotated pictures and the contact sheet of sbr_detect",
                            "test_annotate [--detect SBR_DETECT --data GTSDB_DIR] [--work DIR] [--dbc dbc/sbr.dbc]", options);
    if (h >= 0) return h;
    std::string detect, data, dbc, work = (fs::temp_directory_path() / "sbr_test_annotate").string();
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string k = argv[i];
        if (k == "--detect") detect = argv[i + 1];
        else if (k == "--data") data = argv[i + 1];
        else if (k == "--work") work = argv[i + 1];
        else if (k == "--dbc") dbc = argv[i + 1];
    }
    test_constructed_scene();
    test_crowded_labels();
    test_worst_images();
    test_file_problems();
    if (!dbc.empty()) test_class_names(dbc);
    if (!detect.empty() && !data.empty()) {
        test_sbr_detect(detect, data, work);
        test_failed_images(detect, data, work);
    }
    std::printf("%s (%d failures)\n", failures == 0 ? "ok" : "FAILED", failures);
    return failures == 0 ? 0 : 1;
}
