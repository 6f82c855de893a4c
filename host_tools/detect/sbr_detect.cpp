// SPDX-License-Identifier: MIT
// sbr_detect: runs sbr's recogniser over a folder of recorded images. Its options and what
// they do are its --help (the tool's own below; the recogniser's and the class stage's from
// the core's tables, docs/usage/configuration.md); docs/usage/detect.md describes the
// outputs and is checked against --help (tests/python/test_cli.py).
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "annotate.hpp"
#include "can_output.hpp"
#include "cli.hpp"
#include "gtsdb.hpp"
#include "model_io.hpp"
#include "output_file.hpp"
#include "video.hpp"

#if defined(__has_include)
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define SBR_HAVE_CALLGRIND 1
#endif
#endif

extern "C" {
#include "sbr/recog.h"
#include "sbr/models.h"
#include "sbr/recog_strips.h"
}

namespace fs = std::filesystem;
using namespace sbr_host;

namespace {

uint32_t host_clock(void *) {
    return static_cast<uint32_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                                     std::chrono::steady_clock::now().time_since_epoch())
                                     .count());
}

// --callgrind: the recogniser's stage clock ends a callgrind dump at every stage boundary
// (the ticks it returns only number the dumps), so each dump holds one stage's instructions.
struct CallgrindClock {
    std::string frame;
    uint32_t tick = 0;
};

uint32_t callgrind_clock(void *ctx) {
    auto *c = static_cast<CallgrindClock *>(ctx);
#ifdef SBR_HAVE_CALLGRIND
    // per sbr_recog_detect call (one per band with --strips): the first call ends the
    // set-up (checks, workspace layout), call k + 1 ends stage k
    const uint32_t k = c->tick % (uint32_t(SBR_RECOG_STAGES) + 1u);
    const std::string label =
        "frame " + c->frame + (k == 0 ? std::string(" setup") : " stage " + std::to_string(k - 1));
    CALLGRIND_DUMP_STATS_AT(label.c_str());
#endif
    return ++c->tick;
}

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const double pos = p * double(v.size() - 1);
    const size_t i = size_t(pos);
    const double f = pos - double(i);
    return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}

// The progress bar with the time left, on a terminal only (a log gets none).
void progress(size_t done, size_t total, double ms_avg, double elapsed_s) {
    const int width = 30;
    const int filled = total ? int(double(width) * double(done) / double(total)) : width;
    const double left_s = done ? elapsed_s / double(done) * double(total - done) : 0.0;
    std::fprintf(stderr, "\r[%s%s] %zu/%zu  %.0f ms/frame  %d:%02d left ", std::string(size_t(filled), '#').c_str(),
                 std::string(size_t(width - filled), '.').c_str(), done, total, ms_avg, int(left_s) / 60,
                 int(left_s) % 60);
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
}

// Everything the command line sets.
struct Options {
    std::string input, det_path, all_path, annotated, overview, gt_path, canlog, model_path, picto_path, summary_path;
    std::string annotated_video;  // --annotated-video
    bool video = false;           // --input is a video file
    bool no_picto = false, quiet = false, sequence = false, callgrind = false, grey = false;
    bool canlog_fixed_time = false;
    bool progress = false;  // a progress bar: stderr is a terminal and not --quiet
    ImageRanges range;
    float threshold = -1.0f;  // < 0: the model's operating point
    int repeat = 1;
    std::vector<unsigned> roi_v;  // X, Y, W, H
    sbr_rect_t roi{};
    bool use_roi = false;
    bool strips = false;
    std::vector<unsigned> strips_v;  // ROWS, OVERLAP
    uint32_t strip_rows = 0, strip_overlap = 0;  // rows 0: whole frames
    sbr_recog_config_t cfg{};
    RecogCli rc;
    LooksCli looks;  // the class stage's looks given on the command line
};

// -1: go on; otherwise the exit status.
int parse_options(int argc, char **argv, Options &o) {
    sbr_recog_config_default(&o.cfg);
    // --strips starts from the strip configuration's bounds; explicit --max-* options,
    // parsed into the same fields afterwards, still override them
    for (int i = 1; i < argc; ++i)
        if (std::string(argv[i]) == "--strips") sbr_recog_config_strips(&o.cfg);
    CLI::App app{"sbr_detect: sbr's recogniser over a folder of recorded images (docs/usage/detect.md)"};
    app.add_option("--input", o.input,
                   "folder of JPEG/PNG/PPM images (or a GTSDB folder), or a video file (.mp4, .avi, .mkv, .mov, ...: "
                   "a drive, its frames consecutive, at the file's own times)")
        ->required();
    app.add_option("--annotated-video", o.annotated_video,
                   "with a video --input: the video with the boxes, the confirmed signs and the limit in force drawn "
                   "(.mp4 or .avi)");
    app.add_option("--detections", o.det_path,
                   "detections at the operating point, NNNNN.jpg;left;top;right;bottom;class_id;score")
        ->required();
    app.add_option("--all-detections", o.all_path, "every detection down to score 0.05 (PR curves, AP)");
    app.add_option("--annotated", o.annotated,
                   "folder for the images with their boxes (JPEG); with ground truth, misses and false detections marked");
    app.add_option("--overview", o.overview, "contact sheet (PNG) of the images with the most errors (needs ground truth)");
    app.add_option("--gt", o.gt_path, "ground truth for --annotated/--overview (default: gt.txt beside the images; none: without)");
    app.add_option("--canlog", o.canlog, "candump log of the CAN frames (dbc/sbr.dbc)");
    app.add_option("--summary", o.summary_path, "write the summary (also printed) to this file");
    app.add_option("--model", o.model_path, "prototype library file (sbr_train --out-model); default built-in");
    auto *picto = app.add_option("--picto", o.picto_path, "class-stage file (sbr_train_picto --out)");
    app.add_flag("--no-picto", o.no_picto, "no class stage: part evidence alone scores and classifies")
        ->excludes(picto);
    add_range_option(app, o.range, "keep images numbered A..B");
    app.add_option("--threshold", o.threshold, "operating point (default: the model's)")
        ->check(finite_range(0.0, 1.0));
    auto *roi = app.add_option("--roi", o.roi_v, "run on this region of each image only")
                    ->delimiter(',')
                    ->expected(4)
                    ->type_name("X,Y,W,H");
    auto *strips = app.add_flag("--strips", o.strips,
                                "the strip configuration: each frame in bands of 256 full rows overlapping by 128, "
                                "the bands' bounds (sbr_recog_config_strips, sbr_recog_detect_strips; "
                                "explicit --max-* options still apply)")
                       ->excludes(roi);
    app.add_option("--strip-bands", o.strips_v, "with --strips: bands of ROWS rows, neighbours sharing OVERLAP")
        ->delimiter(',')
        ->expected(2)
        ->type_name("ROWS,OVERLAP")
        ->needs(strips);
    app.add_flag("--quiet", o.quiet, "no progress bar");
    app.add_flag("--grey", o.grey, "give the recogniser each image as a grey (GRAY8) frame");
    app.add_option("--repeat", o.repeat, "runs per frame; the fastest is reported")
        ->check(CLI::Range(1, 20))
        ->capture_default_str();
    app.add_flag("--sequence", o.sequence,
                 "the images are consecutive frames (10 per second): confirmed signs from the tracker");
    app.add_flag("--canlog-fixed-time", o.canlog_fixed_time,
                 "the CAN log's status frames say 0 ms of processing time, so that the log depends on the frames "
                 "alone (compared with the Cortex-M4's, cmake/compare_ecu_log.py)");
    app.add_flag("--callgrind", o.callgrind,
                 "count instructions per stage under valgrind's callgrind (./sbr.sh cost)");
    add_recog_options(app, o.cfg, o.rc);
    add_look_options(app, o.looks);
    o.rc.options["min_score"]->description(
        "score floor of a reported detection (default: the operating point, or 0.05 with --all-detections)");
    const int rc = parse_cli(app, argc, argv);
    if (rc >= 0) return rc;
    o.progress = !o.quiet && isatty(STDERR_FILENO) != 0;
    if (!o.roi_v.empty()) {
        o.roi = {o.roi_v[0], o.roi_v[1], o.roi_v[2], o.roi_v[3]};
        o.use_roi = true;
        if (o.roi.width == 0 || o.roi.height == 0) {
            std::fprintf(stderr, "sbr_detect: --roi %u,%u,%u,%u: the width and height must be at least 1\n", o.roi.x,
                         o.roi.y, o.roi.width, o.roi.height);
            return 2;
        }
    }
    if (o.strips) {
        o.strip_rows = SBR_RECOG_STRIP_ROWS;
        o.strip_overlap = SBR_RECOG_STRIP_OVERLAP;
    }
    if (!o.strips_v.empty()) {
        o.strip_rows = o.strips_v[0];
        o.strip_overlap = o.strips_v[1];
        if (o.strip_rows == 0 || o.strip_overlap >= o.strip_rows) {
            std::fprintf(stderr, "sbr_detect: --strip-bands %u,%u: ROWS must be at least 1 and OVERLAP below ROWS\n",
                         o.strip_rows, o.strip_overlap);
            return 2;
        }
    }
    apply_recog_cli(o.rc, o.cfg);
#ifndef SBR_HAVE_CALLGRIND
    if (o.callgrind) {
        std::fprintf(stderr, "sbr_detect: --callgrind: built without valgrind/callgrind.h\n");
        return 2;
    }
#endif
    return -1;
}

// The part model and the class stage the run uses.
struct Models {
    Model loaded;
    Picto picto;
    sbr_model_t builtin{};
    sbr_picto_model_t builtin_picto{};
    const sbr_model_t *model = nullptr;
    const sbr_picto_model_t *class_stage = nullptr;  // nullptr: none
    sbr_picto_model_t stage{};  // the class stage in use with the looks given (tables borrowed)
};

bool load_models(const Options &o, Models &m) {
    sbr_model_gtsdb(&m.builtin);
    sbr_picto_gtsdb(&m.builtin_picto);
    m.model = &m.builtin;
    m.class_stage = &m.builtin_picto;
    if (!o.model_path.empty()) {
        const std::string e = load_model(o.model_path, m.loaded);
        if (!e.empty()) { std::fprintf(stderr, "sbr_detect: %s\n", e.c_str()); return false; }
        m.model = &m.loaded.view;
        m.class_stage = m.loaded.picto_view();
    }
    if (!o.picto_path.empty()) {
        const std::string e = load_picto(o.picto_path, m.picto);
        if (!e.empty()) { std::fprintf(stderr, "sbr_detect: %s\n", e.c_str()); return false; }
        m.class_stage = &m.picto.view;
    } else if (o.no_picto) {
        m.class_stage = nullptr;
    }
    if (m.class_stage != nullptr) {
        m.stage = *m.class_stage;
        apply_looks(o.looks, m.stage);
        m.class_stage = &m.stage;
    }
    return true;
}

// The operating point (the class stage's, or the part model's without one) and the
// score floor that follows from it; the clock. False for a configuration or models the
// core refuses (sbr_recog_init() on a token workspace checks them together).
bool configure(Options &o, const Models &m, CallgrindClock &cg) {
    if (o.threshold < 0.0f) o.threshold = m.class_stage != nullptr ? m.class_stage->threshold : m.model->score_threshold;
    if (!o.rc.given("min_score")) {
        o.cfg.min_score = std::min(o.cfg.min_score, o.threshold);
        if (!o.all_path.empty()) o.cfg.min_score = std::min(o.cfg.min_score, 0.05f);  // the curve's tail
    }
    o.cfg.clock = host_clock;
    if (o.callgrind) {
        o.cfg.clock = callgrind_clock;
        o.cfg.clock_ctx = &cg;
        o.repeat = 1;
    }
    const std::string problem = config_problem(o.cfg);
    if (!problem.empty()) {
        std::fprintf(stderr, "sbr_detect: %s\n", problem.c_str());
        return false;
    }
    sbr_status_t st;
    uint64_t token = 0;
    sbr_recog_t rec;
    st = sbr_recog_init(&rec, &o.cfg, m.model, m.class_stage, &token, sizeof token);
    if (st != SBR_OK)
        std::fprintf(stderr, "sbr_detect: the recogniser refuses these models with this configuration (%s)\n",
                     sbr_status_str(st));
    return st == SBR_OK;
}

// The ground truth the annotated pictures are judged by, and what they found.
struct Annotation {
    std::string gt_path;  // empty: no ground truth
    std::map<int, std::vector<GtBox>> gt;
    WorstImages worst{12};
    size_t missed = 0, false_dets = 0;
    std::string annotated_failed;  // the first annotated image that could not be written
};

// The output files, each written under a temporary name and renamed over its target at
// the end of a run that wrote it whole (commit_outputs): an earlier run's files survive
// every error.
struct Outputs {
    OutputFile det, all, summary;
    std::unique_ptr<CanLogWriter> can;
    VideoInput video;
    VideoOutput video_out;
    std::string can_tmp;
    Annotation ann;
    bool overview_written = false;
};

// --gt, or the gt.txt beside the images; false when a given file cannot be read or
// --overview has no ground truth.
bool load_ground_truth(const Options &o, const std::string &dir, Annotation &a) {
    if (o.annotated.empty() && o.overview.empty()) return true;
    if (o.gt_path == "none") a.gt_path.clear();
    else if (!o.gt_path.empty()) a.gt_path = o.gt_path;
    else if (fs::is_regular_file(fs::path(dir) / "gt.txt")) a.gt_path = (fs::path(dir) / "gt.txt").string();
    if (!a.gt_path.empty()) {
        a.gt = read_gt(a.gt_path);
        if (a.gt.empty() && !fs::is_regular_file(a.gt_path)) {
            std::fprintf(stderr, "sbr_detect: --gt %s: cannot read it\n", a.gt_path.c_str());
            return false;
        }
    }
    if (!o.overview.empty() && a.gt_path.empty()) {
        std::fprintf(stderr, "sbr_detect: --overview needs ground truth (--gt FILE or a gt.txt beside the images)\n");
        return false;
    }
    return true;
}

// Every output opened (or, for the contact sheet, probed) before the first image: one
// that cannot be written is named with the reason, and nothing runs.
bool open_outputs(const Options &o, Outputs &out) {
    const auto cannot = [](const char *opt, const std::string &path, const std::string &why) {
        std::fprintf(stderr, "sbr_detect: %s %s: cannot write it: %s (nothing was run)\n", opt, path.c_str(),
                     why.c_str());
        return false;
    };
    std::string why = out.det.open(o.det_path);
    if (!why.empty()) return cannot("--detections", o.det_path, why);
    if (!o.all_path.empty() && !(why = out.all.open(o.all_path)).empty())
        return cannot("--all-detections", o.all_path, why);
    if (!o.summary_path.empty() && !(why = out.summary.open(o.summary_path)).empty())
        return cannot("--summary", o.summary_path, why);
    if (!o.overview.empty() && !(why = probe_writable(o.overview)).empty()) return cannot("--overview", o.overview, why);
    if (!o.annotated_video.empty() && !(why = probe_writable(o.annotated_video)).empty())
        return cannot("--annotated-video", o.annotated_video, why);
    if (o.video && o.canlog.empty()) out.can.reset(new CanLogWriter(""));  // the job, without a log
    if (!o.canlog.empty()) {
        std::error_code ec;
        if (fs::is_directory(o.canlog, ec)) return cannot("--canlog", o.canlog, "a folder, not a file");
        out.can_tmp = temp_path_of(o.canlog);
        out.can.reset(new CanLogWriter(out.can_tmp));
        if (!out.can->ok()) {
            const std::string why = out.can->open_error().empty() ? "the CAN output could not be set up"
                                                                   : out.can->open_error();
            out.can.reset();
            return cannot("--canlog", o.canlog, why);
        }
    }
    return true;
}

// The files of a run that got to its end: renamed over their targets. False, with each
// path that failed named, when one of them could not be written whole.
bool commit_outputs(const Options &o, Outputs &out) {
    bool ok = true;
    const auto failed = [&ok](const char *opt, const std::string &path, const std::string &why) {
        std::fprintf(stderr, "sbr_detect: %s %s: the write failed: %s\n", opt, path.c_str(), why.c_str());
        ok = false;
    };
    std::string why;
    if (!(why = out.det.commit()).empty()) failed("--detections", o.det_path, why);
    if (out.all.is_open() && !(why = out.all.commit()).empty()) failed("--all-detections", o.all_path, why);
    if (out.summary.is_open() && !(why = out.summary.commit()).empty()) failed("--summary", o.summary_path, why);
    if (out.can && !o.canlog.empty()) {
        const bool closed = out.can->close();
        std::error_code ec;
        if (!closed) {
            fs::remove(out.can_tmp, ec);
            failed("--canlog", o.canlog, "a write failed (disk full?)");
        } else if (!(why = commit_temp(out.can_tmp, o.canlog)).empty()) {
            failed("--canlog", o.canlog, why);
        }
    }
    if (!out.ann.annotated_failed.empty()) failed("--annotated", out.ann.annotated_failed, "an image could not be written");
    return ok;
}

// What the run counts, for the summary.
// The bits of sbr_recog_stats_t::capacity_hit (SBR_RECOG_HIT_PARTS .. SBR_RECOG_HIT_OUTLINES).
constexpr unsigned kHitKinds = 7;
static_assert((1u << (kHitKinds - 1)) == SBR_RECOG_HIT_OUTLINES, "capacity_hit's bits");

struct Tally {
    std::vector<uint64_t> ws;
    sbr_recog_t rec{};
    bool rec_ready = false;  // rec initialised on ws as it is
    size_t ws_bytes = 0;
    std::vector<sbr_detection_t> dets = std::vector<sbr_detection_t>(256);
    std::vector<double> ms_total;
    std::vector<std::vector<double>> ms_stage = std::vector<std::vector<double>>(SBR_RECOG_STAGES);
    size_t ndet = 0, nall = 0, failed = 0, capacity_frames = 0;
    std::vector<std::string> failures;  // "file: why", the first few
    size_t capacity_kind[kHitKinds] = {};  // frames on which bit b of capacity_hit was set
    uint32_t max_candidates = 0;  // the class stage's bound, for the summary
    size_t classified = 0, outlines = 0, refined = 0, views = 0, rim_rejected = 0, gated = 0, frames_run = 0;
    uint32_t max_extra_looks = 0;  // the most extra looks of one frame
    uint64_t parts_total = 0;
    uint32_t parts_max = 0;
    double sum_ms = 0;
};

// The recogniser on one frame, `repeat` times: the fastest run's time and statistics.
sbr_status_t detect_timed(const Options &o, CallgrindClock &cg, const std::string &file,
                          const sbr_image_t &v, Tally &t, uint32_t &n, double &ms, sbr_recog_stats_t &stats) {
    sbr_status_t st = SBR_OK;
    for (int r = 0; r < o.repeat; ++r) {
        sbr_recog_stats_t run_stats{};
        const auto t0 = std::chrono::steady_clock::now();
#ifdef SBR_HAVE_CALLGRIND
        if (o.callgrind) {  // collect only inside sbr_recog_detect
            cg.frame = fs::path(file).stem().string();
            cg.tick = 0;
            CALLGRIND_ZERO_STATS;
            CALLGRIND_TOGGLE_COLLECT;
        }
#else
        (void)cg;
        (void)file;
#endif
        if (o.strip_rows != 0)
            st = sbr_recog_detect_strips(&t.rec, &v, o.strip_rows, o.strip_overlap, t.dets.data(),
                                         uint32_t(t.dets.size()), &n, &run_stats);
        else
            st = sbr_recog_detect(&t.rec, &v, o.use_roi ? &o.roi : nullptr, t.dets.data(), uint32_t(t.dets.size()),
                                  &n, &run_stats);
#ifdef SBR_HAVE_CALLGRIND
        if (o.callgrind) {
            const std::string label = "frame " + cg.frame + " end";
            CALLGRIND_DUMP_STATS_AT(label.c_str());
            CALLGRIND_TOGGLE_COLLECT;
        }
#endif
        const double run_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        if (r == 0 || run_ms < ms) {
            ms = run_ms;
            stats = run_stats;
        }
    }
    return st;
}

void count_stats(const sbr_recog_stats_t &stats, sbr_status_t st, double ms, Tally &t) {
    t.ms_total.push_back(ms);
    t.sum_ms += ms;
    for (unsigned s = 0; s < SBR_RECOG_STAGES; ++s) t.ms_stage[s].push_back(stats.stage_ticks[s] / 1000.0);
    t.parts_total += stats.parts;
    t.parts_max = std::max(t.parts_max, stats.parts);
    if (stats.capacity_hit != 0 || st == SBR_ERR_CAPACITY) ++t.capacity_frames;
    for (unsigned b = 0; b < kHitKinds; ++b) t.capacity_kind[b] += (stats.capacity_hit >> b) & 1u;
    t.max_extra_looks = std::max(t.max_extra_looks, stats.extra_looks);
    t.classified += stats.classified;
    t.outlines += stats.outlines;
    t.refined += stats.refined;
    t.views += stats.views;
    t.rim_rejected += stats.rim_rejected;
    t.gated += stats.gated;
    ++t.frames_run;
}

// A failed image: reported (below the progress bar), counted, the first few kept for the
// summary.
void image_failed(const Options &o, const std::string &file, const std::string &why, Tally &t) {
    std::fprintf(stderr, "%ssbr_detect: %s: %s\n", o.progress ? "\n" : "", file.c_str(), why.c_str());
    ++t.failed;
    if (t.failures.size() < 10) t.failures.push_back(fs::path(file).filename().string() + ": " + why);
}

// What keeps the recogniser from taking a decoded image, in the user's terms, or "": a
// side above the core's limit, a --roi that does not lie inside the image.
std::string frame_problem(const Options &o, const cv::Mat &img) {
    char buf[200];
    if (img.cols > int(SBR_IMAGE_MAX_DIM) || img.rows > int(SBR_IMAGE_MAX_DIM)) {
        std::snprintf(buf, sizeof buf, "the image is %d x %d pixels; the recogniser takes at most %u on a side "
                      "(SBR_IMAGE_MAX_DIM)", img.cols, img.rows, SBR_IMAGE_MAX_DIM);
        return buf;
    }
    const sbr_rect_t &r = o.roi;
    if (o.use_roi && (uint64_t(r.x) + r.width > uint64_t(img.cols) || uint64_t(r.y) + r.height > uint64_t(img.rows))) {
        std::snprintf(buf, sizeof buf, "--roi %u,%u,%u,%u does not lie inside the image (%d x %d pixels: x + w <= %d, "
                      "y + h <= %d)", r.x, r.y, r.width, r.height, img.cols, img.rows, img.cols, img.rows);
        return buf;
    }
    return "";
}

// The recogniser on a decoded image: detections written and counted; `kept` those at the
// operating point. False when the core refused the frame.
bool detect_image(const Options &o, const Models &m, CallgrindClock &cg, const std::string &file,
                  const cv::Mat &img, Outputs &out, Tally &t, std::vector<sbr_detection_t> &kept,
                  sbr_recog_stats_t &stats, float &frame_ms) {
    const std::string name = fs::path(file).stem().string() + ".jpg";
    cv::Mat grey;
    if (o.grey) cv::cvtColor(img, grey, cv::COLOR_BGR2GRAY);
    const sbr_image_t v = bgr_view(o.grey ? grey : img);
    const uint32_t w = o.use_roi ? o.roi.width : v.width, h = o.use_roi ? o.roi.height : v.height;
    const size_t need = o.strip_rows != 0 ? sbr_recog_strip_workspace_size(&o.cfg, w, h, o.strip_rows)
                                          : sbr_recog_workspace_size(&o.cfg, w, h);
    if (!t.rec_ready || need > t.ws.size() * 8) {  // a larger workspace: the recogniser set up on it
        if (need > t.ws.size() * 8 || t.ws.empty()) t.ws.assign(need / 8 + 1, 0);
        const sbr_status_t ist = sbr_recog_init(&t.rec, &o.cfg, m.model, m.class_stage, t.ws.data(), t.ws.size() * 8);
        t.rec_ready = ist == SBR_OK;
        if (!t.rec_ready) {
            image_failed(o, file, std::string("sbr_recog_init refused it: ") + sbr_status_str(ist), t);
            return false;
        }
    }
    t.ws_bytes = std::max(t.ws_bytes, need);
    uint32_t n = 0;
    double ms = 0.0;
    const sbr_status_t st = detect_timed(o, cg, file, v, t, n, ms, stats);
    frame_ms = float(ms);
    count_stats(stats, st, ms, t);
    if (st != SBR_OK && st != SBR_ERR_CAPACITY) {
        image_failed(o, file, std::string("the recogniser refused it: ") + sbr_status_str(st), t);
        return false;
    }
    const int number = image_number(file);
    for (uint32_t k = 0; k < n; ++k) {
        const auto &d = t.dets[k];
        const std::string line = detection_line(name, from_core(d, number));
        if (out.all.is_open()) { out.all << line; ++t.nall; }
        if (d.score >= o.threshold) { out.det << line; kept.push_back(d); ++t.ndet; }
    }
    return true;
}

// The annotated picture of one image, judged against its ground truth when there is one;
// offered to the contact sheet.
void annotate_image(const Options &o, const std::string &file, cv::Mat &img,
                    const std::vector<sbr_detection_t> &kept, Annotation &a) {
    const int number = image_number(file);
    std::vector<Detection> dets;
    for (const auto &d : kept) dets.push_back(from_core(d, number));
    const auto g = a.gt.find(number);
    const std::vector<Mark> marks =
        judge(dets, g != a.gt.end() ? g->second : std::vector<GtBox>{}, !a.gt_path.empty());
    for (const Mark &m : marks) {
        a.missed += m.kind == MarkKind::kMissed;
        a.false_dets += m.kind == MarkKind::kFalse;
    }
    const std::vector<cv::Rect> labels = draw_marks(img, marks);
    // the contact sheet's tiles without the legend (the sheet has its own)
    if (!o.overview.empty()) a.worst.offer(fs::path(file).stem().string(), img, marks, labels);
    draw_legend(img, !a.gt_path.empty());
    const std::string name = fs::path(file).stem().string() + ".jpg";
    if (!o.annotated.empty()) {
        const std::string path = (fs::path(o.annotated) / name).string();
        bool written = false;
        try {
            written = cv::imwrite(path, img);
        } catch (const cv::Exception &) {
            written = false;
        }
        if (!written && a.annotated_failed.empty()) a.annotated_failed = path;
    }
}

// One image: read, detections written, counted, drawn, and its CAN frames. False when
// the CAN log's tracker cannot be set up.
// A video's frame comes decoded (`given`) with its time from the file's start (`time_us`).
bool run_image(const Options &o, const Models &m, CallgrindClock &cg, const std::string &file, bool first,
               Outputs &out, Tally &t, const cv::Mat *given = nullptr, int64_t time_us = -1) {
    std::vector<sbr_detection_t> kept;
    sbr_recog_stats_t stats{};
    float frame_ms = 0.0f;
    cv::Mat img;
    std::string problem;
    if (given) img = given->clone();
    else problem = read_image(file, img);
    if (problem.empty()) problem = frame_problem(o, img);
    bool error = !problem.empty();
    if (error) image_failed(o, file, problem, t);
    else error = !detect_image(o, m, cg, file, img, out, t, kept, stats, frame_ms);
    if (!error && (!o.annotated.empty() || !o.overview.empty())) annotate_image(o, file, img, kept, out.ann);
    if (out.can) {
        if (o.sequence && first && !out.can->enable_tracking(float(img.cols), float(img.rows))) {
            std::fprintf(stderr, "sbr_detect: sign tracker set-up failed\n");
            return false;
        }
#ifdef SBR_HAVE_CALLGRIND
        if (o.callgrind) CALLGRIND_TOGGLE_COLLECT;  // the ECU job's dump: sbr_ecu_output and the port
#endif
        out.can->write_image(kept, o.canlog_fixed_time ? 0.0f : frame_ms, stats.parts_stats.regions, error,
                             (stats.capacity_hit & SBR_RECOG_HIT_LOSSES) != 0u, time_us);
#ifdef SBR_HAVE_CALLGRIND
        if (o.callgrind) {
            const std::string label = "frame " + fs::path(file).stem().string() + " ecu";
            CALLGRIND_DUMP_STATS_AT(label.c_str());
            CALLGRIND_TOGGLE_COLLECT;
        }
#endif
    }
    return true;
}

// What the internal bounds did: each bounds a frame's work and memory. The class stage's
// candidate bound is meant to be reached on street frames (it decides the class stage's
// cost); the others, when reached, may lose evidence.
std::string bounds_text(const Options &o, const Tally &t) {
    std::ostringstream s;
    const size_t fr = t.frames_run;
    s << (o.strip_rows != 0 ? "internal bounds (each caps a band's work and memory, --strips; a frame counts when one "
                              "of its bands reached it; docs/usage/detect.md):\n"
                            : "internal bounds (each caps a frame's work and memory; docs/usage/detect.md):\n");
    s << "  class-stage candidates (--max-candidates " << o.cfg.max_candidates << "): reached on "
      << t.capacity_kind[4] << " of " << fr << " frames";
    if (t.capacity_kind[4] > 0)
        s << ", as designed:\n    the class stage classifies the " << o.cfg.max_candidates
          << " candidates of best part score of a frame and skips the rest,\n"
             "    which fixes its time per frame; a sign skipped there counts as a miss";
    s << "\n";
    s << "  class-stage extra looks (--max-extra-looks " << o.cfg.max_extra_looks << "): reached on "
      << t.capacity_kind[5] << " of " << fr << " frames (the most a frame spent: " << t.max_extra_looks << ")";
    if (t.capacity_kind[5] > 0)
        s << ":\n    on those frames the last candidates kept the box, class and score of their last look";
    s << "\n";
    s << "  outline candidates (--max-outline-candidates " << o.cfg.max_outline_candidates << "): reached on "
      << t.capacity_kind[6] << " of " << fr << " frames";
    if (t.capacity_kind[6] > 0) s << ":\n    on those frames the later sign-shaped regions got no candidate of their own";
    s << "\n";
    const char *names[4] = {"parts (--max-parts ", "votes (--max-votes ", "hypotheses (--max-hypotheses ",
                            "MSER tree nodes or boundary heap (--max-nodes "};
    const uint32_t limits[4] = {o.cfg.max_parts, o.cfg.max_votes, o.cfg.max_hypotheses, o.cfg.parts.mser.max_nodes};
    std::string unreached;
    for (unsigned b = 0; b < 4; ++b) {
        const std::string what = names[b] + std::to_string(limits[b]) +
                                 (b == 3 ? ", --max-heap " + std::to_string(o.cfg.parts.mser.max_heap) : "") + ")";
        if (t.capacity_kind[b] == 0) {
            unreached += (unreached.empty() ? "" : ", ") + what;
            continue;
        }
        s << "  " << what << ": reached on " << t.capacity_kind[b] << " of " << fr
          << " frames: those frames lost some " << (b == 3 ? "regions of a map" : "evidence")
          << " (a larger bound: more workspace)\n";
    }
    if (!unreached.empty()) s << "  not reached: " << unreached << "\n";
    return s.str();
}

std::string summary(const Options &o, const Models &m, const std::string &dir, size_t nfiles,
                    const Outputs &out, const Tally &t) {
    std::ostringstream s;
    const char *stage_names[SBR_RECOG_STAGES] = {"parts (maps, MSER, contours, FDs)", "matching and votes",
                                                 "grouping", "evidence and cascade", "NMS on part scores",
                                                 "class stage (pictograms)"};
    s << "sbr_detect summary\n";
    s << "input: " << (o.video ? o.input : dir) << " (" << nfiles << (o.video ? " frames of a video, " : " images, ")
      << t.failed << " failed)\n";
    for (const std::string &f : t.failures) s << "  failed: " << f << "\n";
    if (t.failed > t.failures.size()) s << "  (and " << t.failed - t.failures.size() << " more)\n";
    s << "model: " << (o.model_path.empty() ? "built-in (lib/models/sbr_model_gtsdb.c)" : o.model_path) << ", "
      << m.model->proto_count << " prototypes, class stage "
      << (m.class_stage == nullptr  ? "none"
          : !o.picto_path.empty()   ? o.picto_path
          : !o.model_path.empty()   ? o.model_path
                                    : "built-in (lib/models/sbr_picto_gtsdb.c)")
      << ", operating point score >= " << o.threshold << "\n";
    s << "detections: " << t.ndet << " at the operating point";
    if (out.all.is_open()) s << ", " << t.nall << " in all";
    s << "\nparts per frame (mean): " << (t.ms_total.empty() ? 0 : t.parts_total / t.ms_total.size())
      << " (most in one frame: " << t.parts_max << ")\n";
    char buf[256];
    const std::string runs = o.repeat > 1 ? ", fastest of " + std::to_string(o.repeat) + " runs" : "";
    std::snprintf(buf, sizeof buf, "time per frame (one core%s): median %.1f ms, 95th percentile %.1f ms\n",
                  runs.c_str(), percentile(t.ms_total, 0.5), percentile(t.ms_total, 0.95));
    s << buf;
    for (unsigned k = 0; k < SBR_RECOG_STAGES; ++k) {
        std::snprintf(buf, sizeof buf, "  %-36s median %.1f ms, 95th percentile %.1f ms\n", stage_names[k],
                      percentile(t.ms_stage[k], 0.5), percentile(t.ms_stage[k], 0.95));
        s << buf;
    }
    s << "workspace: " << t.ws_bytes << " bytes ("
      << (o.use_roi ? std::string("ROI")
                    : o.strip_rows != 0 ? "bands of " + std::to_string(o.strip_rows) + " rows overlapping by " +
                                              std::to_string(o.strip_overlap)
                                        : std::string("frame"))
      << ", subsample " << o.cfg.parts.subsample << ")\n";
    s << bounds_text(o, t);
    if (t.frames_run > 0 && t.classified > 0) {
        const double fr = double(t.frames_run);
        std::snprintf(buf, sizeof buf,
                      "class stage per frame (mean): %.1f candidates classified (%.1f of them outline candidates), "
                      "%.1f boxes refined, %.1f extra views, "
                      "%.1f rejected by the gate; colour check: %zu candidates dropped in all\n",
                      double(t.classified) / fr, double(t.outlines) / fr, double(t.refined) / fr, double(t.views) / fr,
                      double(t.gated) / fr, t.rim_rejected);
        s << buf;
    }
    if (out.can) s << "CAN log: " << o.canlog << " (" << out.can->frames_written() << " frames)\n";
    if (!o.annotated.empty()) s << "annotated images: " << o.annotated << "\n";
    if (!out.ann.gt_path.empty() && (!o.annotated.empty() || !o.overview.empty()))
        s << "judged against " << out.ann.gt_path << " (class level, IoU >= 0.5): " << out.ann.missed
          << " signs missed (dashed boxes), " << out.ann.false_dets << " false detections (magenta, FP)\n";
    if (!o.overview.empty()) {
        if (out.overview_written)
            s << "overview of the worst images: " << o.overview << " (" << out.ann.worst.size() << " images)\n";
        else
            s << "no overview: no image with a missed sign or a false detection\n";
    }
    return s.str();
}

// --roi against the first image before anything runs (a folder's images share a size; one
// of another size is refused on its own, naming --roi). False, with the reason printed,
// when it does not fit.
bool roi_fits_first(const Options &o, const std::string &file) {
    if (!o.use_roi) return true;
    cv::Mat img;
    if (!read_image(file, img).empty()) return true;  // an unreadable image fails on its own later
    const std::string problem = frame_problem(o, img);
    if (problem.empty()) return true;
    std::fprintf(stderr, "sbr_detect: %s: %s (nothing was run)\n", fs::path(file).filename().c_str(), problem.c_str());
    return false;
}

// Everything checked before the first image (docs/usage/exit-status.md: 2, nothing
// written): the models, the configuration, the input, --roi, --annotated, the ground
// truth. -1 to go on, else the exit status.
int prepare(Options &o, Models &m, CallgrindClock &cg, std::string &dir, std::vector<std::string> &files,
            Outputs &out) {
    (void)files;
    if (!load_models(o, m) || !configure(o, m, cg)) return 2;
    std::error_code ec;
    if (fs::is_regular_file(o.input, ec)) {
        std::string why = is_video_path(o.input) ? "" : "a file, not a folder of images nor a video (.mp4, .avi, ...)";
        if (why.empty() && !out.video.open(o.input, why)) why = why.empty() ? "cannot be opened" : why;
        if (!why.empty()) {
            std::fprintf(stderr, "sbr_detect: --input %s: %s (nothing was run)\n", o.input.c_str(), why.c_str());
            return 2;
        }
        o.video = true;
        o.sequence = true;  // a drive: consecutive frames
        dir = fs::path(o.input).parent_path().string();
        return open_outputs(o, out) ? -1 : 1;
    }
    if (!o.annotated_video.empty()) {
        std::fprintf(stderr, "sbr_detect: --annotated-video needs a video --input (nothing was run)\n");
        return 2;
    }
    if (!fs::is_directory(o.input, ec)) {
        const bool missing = !ec || ec == std::errc::no_such_file_or_directory;
        std::fprintf(stderr, "sbr_detect: --input %s: %s\n", o.input.c_str(),
                     missing ? "no such folder" : ec.message().c_str());
        return 2;
    }
    dir = gtsdb_image_dir(o.input);
    std::string unreadable;
    files = list_images(dir, o.range, &unreadable);
    if (files.empty() && !unreadable.empty()) {
        std::fprintf(stderr, "sbr_detect: --input %s: %s (nothing was run)\n", o.input.c_str(), unreadable.c_str());
        return 2;
    }
    if (files.empty()) {
        std::fprintf(stderr, "sbr_detect: no .jpg, .jpeg, .png or .ppm images in %s%s\n", dir.c_str(),
                     o.range.empty() ? "" : (" numbered " + o.range.str()).c_str());
        return 2;
    }
    if (!roi_fits_first(o, files.front())) return 2;
    if (!o.annotated.empty() && fs::equivalent(o.annotated, dir, ec)) {
        std::fprintf(stderr, "sbr_detect: --annotated %s is the input folder: its images would be overwritten\n",
                     o.annotated.c_str());
        return 2;
    }
    if (!o.annotated.empty()) {
        ec.clear();
        if (fs::exists(o.annotated, ec) && !fs::is_directory(o.annotated, ec)) {
            std::fprintf(stderr, "sbr_detect: --annotated %s: a file, not a folder (nothing was run)\n",
                         o.annotated.c_str());
            return 2;
        }
        fs::create_directories(o.annotated, ec);
        if (ec) {
            std::fprintf(stderr, "sbr_detect: --annotated %s: cannot make the folder: %s (nothing was run)\n",
                         o.annotated.c_str(), ec.message().c_str());
            return 2;
        }
    }
    if (!load_ground_truth(o, dir, out.ann)) return 2;
    return open_outputs(o, out) ? -1 : 1;
}

// A video --input: every frame in order at its own time, the annotated video written.
// -1 to go on (summary and outputs), else the exit status.
int run_video(const Options &o, const Models &m, CallgrindClock &cg, Outputs &out, Tally &t) {
    cv::Mat frame;
    uint64_t t_us = 0;
    for (int64_t k = 0; out.video.next(frame, t_us); ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "%05lld.frame", static_cast<long long>(k));
        if (!run_image(o, m, cg, name, k == 0, out, t, &frame, int64_t(t_us))) return 1;
        if (!o.annotated_video.empty()) {
            std::string why;
            if (k == 0 && !out.video_out.open(o.annotated_video, out.video.fps(), frame.size(), why)) {
                std::fprintf(stderr, "sbr_detect: --annotated-video %s: %s\n", o.annotated_video.c_str(), why.c_str());
                return 1;
            }
            draw_cycle(frame, decode_cycle(out.can->last_cycle()), double(t_us) * 1e-6);
            out.video_out.write(frame);
        }
    }
    const std::string early = out.video.ended_early();
    if (!early.empty()) {  // a failed input: the run goes on with what was read (exit 3)
        std::fprintf(stderr, "sbr_detect: --input %s: %s\n", o.input.c_str(), early.c_str());
        ++t.failed;
        t.failures.push_back(fs::path(o.input).filename().string() + ": " + early);
    }
    if (out.video_out.is_open()) {
        const std::string why = out.video_out.close();
        if (!why.empty()) {
            std::fprintf(stderr, "sbr_detect: --annotated-video %s: the write failed: %s\n",
                         o.annotated_video.c_str(), why.c_str());
            return 1;
        }
    }
    return -1;
}

// The contact sheet of this run, or none (an earlier run's file removed: it would not
// show this run). False when it could not be written (the earlier one is then kept).
bool write_overview(const Options &o, Outputs &out) {
    if (o.overview.empty()) return true;
    std::error_code ec;
    if (out.ann.worst.size() == 0) {
        fs::remove(o.overview, ec);
        return true;
    }
    const std::string tmp = temp_path_of(o.overview);
    bool written = false;
    try {
        written = out.ann.worst.write(tmp);
    } catch (const cv::Exception &) {
        written = false;
    }
    const std::string why = written ? commit_temp(tmp, o.overview) : "the image could not be written";
    if (!written) fs::remove(tmp, ec);
    out.overview_written = why.empty();
    if (!why.empty()) std::fprintf(stderr, "sbr_detect: --overview %s: the write failed: %s\n", o.overview.c_str(),
                                   why.c_str());
    return out.overview_written;
}

}  // namespace

int main(int argc, char **argv) {
    Options o;
    const int rc = parse_options(argc, argv, o);
    if (rc >= 0) return rc;
    Models m;
    CallgrindClock cg;
    std::string dir;
    std::vector<std::string> files;
    Outputs out;
    const int ready = prepare(o, m, cg, dir, files, out);
    if (ready >= 0) return ready;
    Tally t;
    if (o.video) {
        const int vs = run_video(o, m, cg, out, t);
        if (vs >= 0) return vs;
        files.assign(size_t(out.video.frames_read()), std::string());
    }
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t i = 0; i < files.size() && !o.video; ++i) {
        if (!run_image(o, m, cg, files[i], i == 0, out, t)) return 1;  // the temporaries go

        if (o.progress)
            progress(i + 1, files.size(), t.ms_total.empty() ? 0.0 : t.sum_ms / double(t.ms_total.size()),
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    const bool overview_ok = write_overview(o, out);
    const std::string s = summary(o, m, dir, files.size(), out, t);
    std::fputs(s.c_str(), stdout);
    if (out.summary.is_open()) out.summary << s;
    // every output renamed over its target only now: a failed write is exit 1, naming it
    if (!commit_outputs(o, out) || !overview_ok) return 1;
    if (o.video) return t.failed > 0 ? (size_t(out.video.frames_read()) == t.failed ? 1 : 3) : 0;
    if (t.failed > 0) std::fprintf(stderr, "sbr_detect: %zu of %zu images failed\n", t.failed, files.size());
    return t.failed == files.size() ? 1 : (t.failed > 0 ? 3 : 0);
}
