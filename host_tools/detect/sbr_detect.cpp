// sbr_detect: runs sbr's recogniser over a folder of recorded images.
//
//   sbr_detect --input DIR --detections FILE [--annotated DIR] [--canlog FILE]
//              [--all-detections FILE] [--summary FILE] [--model FILE] [--picto FILE]
//              [--no-picto] [--range A-B]
//              [--threshold T] [--subsample S] [--roi X,Y,W,H] [--quiet] [--repeat N] [--callgrind]
//              [--min-parts N] [--vote-error E] [--verify-error E] [--min-score S] [--refine-steps N]
//              [--refine-first-score S] [--refine-score S] [--views N] [--view-score S] [--maps MASK]
//              [--map-subsample I,R,B,Y] [--map-min-area I,R,B,Y] [--max-nodes N] [--max-candidates N]
//              [--max-parts N] [--max-votes N] [--max-hypotheses N] [--gate 0|1] [--candidate-score S]
//              [--candidate-iou U] [--triangle-view 0|1] [--triangle-score S]
//
// --input: a folder of JPEG/PNG/PPM images (a GTSDB folder with FullIJCNN2013/ inside is
//   accepted too). --range A-B keeps images numbered A..B.
// --detections: one line per detection at the operating point (score >= --threshold,
//   default the class stage's operating point, or the part model's without one), exactly
//   `NNNNN.jpg;left;top;right;bottom;class_id;score` (GTSDB's format, inclusive pixel box,
//   plus a score 0..1).
// --all-detections: the same format with every detection down to score 0.05 (the
//   recogniser's floor is lowered to that): for precision-recall curves and AP.
// --annotated: each image with its operating-point boxes and class names (JPEG).
// --canlog: a candump log with the CAN frames of every processed image (dbc/sbr.dbc).
// --sequence: the images (sorted by name) are consecutive frames of one drive, 10 per
//   second: the CAN log's confirmed signs come from the channel tracker (each sign once
//   per pass, with a stable track id) instead of treating every image as a still.
// --model: a prototype library file (sbr_train --out-model); default: the built-in one.
// --picto: a class-stage file (sbr_train_picto --out) used with the library instead of
//   its own; --no-picto: no class stage (part evidence alone scores and classifies).
// --summary: the summary text (also printed): images, detections, time per frame (median
//   and 95th percentile, per stage), workspace bytes, capacity hits.
// --min-parts, --vote-error, --verify-error, --min-score, --refine-steps, --refine-first-score, --refine-score,
//   --views, --view-score, --candidate-score, --candidate-iou, --triangle-view, --triangle-score
//   override the recogniser's options of those names
//   (include/sbr/recognizer.h), for tuning and regression; --maps sets parts.maps (bit k =
//   map kind k of include/sbr/map.h; 0x1 intensity only), --map-subsample
//   parts.map_subsample and --map-min-area parts.map_min_area (per kind, in the order
//   intensity, red, blue, yellow; kinds not given keep their defaults; an area of 0 means
//   the MSER default), --max-nodes parts.mser.max_nodes (MSER tree nodes, most of
//   the workspace; 0 = the worst case), --max-candidates the class stage's candidate
//   bound and --max-parts, --max-votes, --max-hypotheses the recogniser's bounds of those
//   names (smaller: less workspace); --gate 0 turns the class stage's gate off (it is used
//   when the class stage has one).
// Time is measured per frame on one core (the tool is single-threaded). --repeat N runs the
//   recogniser N times on each frame (1..20, default 1) and keeps each frame's fastest run
//   and that run's stage times: a shared or virtual machine's interruptions only ever add
//   time, so the fastest of a few runs is the figure that repeats from one run of the
//   tool to the next. The output is the same for every run (the recogniser is
//   deterministic); the summary says how many runs each frame had.
// --callgrind: for `./sbr.sh cost` (host_tools/bench_cost): run under valgrind's callgrind
//   with --collect-atstart=no; instructions are collected inside sbr_recog_detect only and
//   a dump is written at each stage boundary (one run per frame).
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "can_output.hpp"
#include "gtsdb.hpp"
#include "model_io.hpp"

#if defined(__has_include)
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define SBR_HAVE_CALLGRIND 1
#endif
#endif

extern "C" {
#include "sbr/recognizer.h"
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
    // the first call ends the set-up (checks, workspace layout), call k + 1 ends stage k
    const std::string label =
        "frame " + c->frame + (c->tick == 0 ? std::string(" setup") : " stage " + std::to_string(c->tick - 1));
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

void progress(size_t done, size_t total, double ms_avg) {
    const int width = 40;
    const int filled = total ? int(double(width) * double(done) / double(total)) : width;
    std::fprintf(stderr, "\r[%s%s] %zu/%zu  %.0f ms/frame", std::string(size_t(filled), '#').c_str(),
                 std::string(size_t(width - filled), '.').c_str(), done, total, ms_avg);
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
}

void annotate(cv::Mat &img, const std::vector<sbr_detection_t> &dets) {
    for (const auto &d : dets) {
        const cv::Scalar colour[4] = {{0, 0, 255}, {255, 128, 0}, {0, 200, 255}, {0, 200, 0}};
        const cv::Scalar c = colour[superclass_of(d.class_id)];
        const cv::Rect r(int(d.box.x), int(d.box.y), int(d.box.width), int(d.box.height));
        cv::rectangle(img, r, c, 2);
        char label[96];
        std::snprintf(label, sizeof label, "%d %s %.2f", d.class_id, class_name(d.class_id), double(d.score));
        int base = 0;
        const cv::Size ts = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, 0.45, 1, &base);
        const int y = std::max(ts.height + 2, r.y - 3);
        cv::rectangle(img, cv::Rect(r.x, y - ts.height - 2, ts.width + 4, ts.height + 5), c, cv::FILLED);
        cv::putText(img, label, cv::Point(r.x + 2, y), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1,
                    cv::LINE_AA);
    }
}

}  // namespace

int main(int argc, char **argv) {
    std::string input, det_path, all_path, annotated, canlog, model_path, summary_path, picto_path;
    bool no_picto = false;
    ImageRanges range;
    float threshold = -1.0f;
    uint32_t subsample = 1;
    bool use_roi = false, quiet = false;
    int repeat = 1;
    int max_parts = -1, max_votes = -1, max_hyps = -1;
    int min_parts = -1, refine_steps = -1, maps = -1, max_candidates = -1, views_opt = -1, triangle_view = -1, max_nodes = -1;
    bool sequence = false, callgrind = false;
    FrontEnd front_end;  // --map-subsample, --map-min-area: per map kind, empty = defaults
    int gate_opt = -1;
    float vote_error = -1.0f, verify_error = -1.0f, min_score = -1.0f, refine_score = -1.0f, refine_first_score = -1.0f, view_score = -1.0f, triangle_score = -1.0f, candidate_score = -1.0f, candidate_iou = -1.0f;
    sbr_rect_t roi{};
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--input") input = next();
        else if (a == "--detections") det_path = next();
        else if (a == "--all-detections") all_path = next();
        else if (a == "--annotated") annotated = next();
        else if (a == "--canlog") canlog = next();
        else if (a == "--model") model_path = next();
        else if (a == "--picto") picto_path = next();
        else if (a == "--no-picto") no_picto = true;
        else if (a == "--summary") summary_path = next();
        else if (a == "--threshold") threshold = std::strtof(next().c_str(), nullptr);
        else if (a == "--subsample") subsample = uint32_t(std::atoi(next().c_str()));
        else if (a == "--quiet") quiet = true;
        else if (a == "--repeat") repeat = std::atoi(next().c_str());
        else if (a == "--sequence") sequence = true;
        else if (a == "--callgrind") callgrind = true;
        else if (a == "--min-parts") min_parts = std::atoi(next().c_str());
        else if (a == "--refine-steps") refine_steps = std::atoi(next().c_str());
        else if (a == "--refine-score") refine_score = std::strtof(next().c_str(), nullptr);
        else if (a == "--refine-first-score") refine_first_score = std::strtof(next().c_str(), nullptr);
        else if (a == "--candidate-score") candidate_score = std::strtof(next().c_str(), nullptr);
        else if (a == "--candidate-iou") candidate_iou = std::strtof(next().c_str(), nullptr);
        else if (a == "--view-score") view_score = std::strtof(next().c_str(), nullptr);
        else if (a == "--map-subsample" || a == "--map-min-area") {
            bool ok = true;
            parse_front_end(a, next(), front_end, ok);
            if (!ok) { std::fprintf(stderr, "%s wants I[,R[,B[,Y]]]\n", a.c_str()); return 2; }
        } else if (a == "--maps") maps = int(std::strtol(next().c_str(), nullptr, 0));
        else if (a == "--max-nodes") max_nodes = std::atoi(next().c_str());
        else if (a == "--max-candidates") max_candidates = std::atoi(next().c_str());
        else if (a == "--max-parts") max_parts = std::atoi(next().c_str());
        else if (a == "--gate") gate_opt = std::atoi(next().c_str());
        else if (a == "--max-votes") max_votes = std::atoi(next().c_str());
        else if (a == "--max-hypotheses") max_hyps = std::atoi(next().c_str());
        else if (a == "--views") views_opt = std::atoi(next().c_str());
        else if (a == "--triangle-view") triangle_view = std::atoi(next().c_str());
        else if (a == "--triangle-score") triangle_score = std::strtof(next().c_str(), nullptr);
        else if (a == "--vote-error") vote_error = std::strtof(next().c_str(), nullptr);
        else if (a == "--verify-error") verify_error = std::strtof(next().c_str(), nullptr);
        else if (a == "--min-score") min_score = std::strtof(next().c_str(), nullptr);
        else if (a == "--range") {
            if (!parse_image_ranges(next(), range)) { std::fprintf(stderr, "--range wants A-B[,C-D...]\n"); return 2; }
        } else if (a == "--roi") {
            unsigned x, y, w, h;
            if (std::sscanf(next().c_str(), "%u,%u,%u,%u", &x, &y, &w, &h) != 4) { std::fprintf(stderr, "--roi wants X,Y,W,H\n"); return 2; }
            roi = {x, y, w, h};
            use_roi = true;
        } else {
            std::fprintf(stderr,
                         "usage: %s --input DIR --detections FILE [--annotated DIR] [--canlog FILE]\n"
                         "          [--all-detections FILE] [--summary FILE] [--model FILE] [--range A-B]\n"
                         "          [--threshold T] [--subsample S] [--roi X,Y,W,H] [--quiet] [--repeat N] [--callgrind]\n"
                         "          [--min-parts N] [--vote-error E] [--verify-error E] [--min-score S] [--sequence]\n"
                         "          [--refine-steps N] [--refine-first-score S] [--refine-score S] [--view-score S] [--maps MASK] [--map-subsample I,R,B,Y] [--map-min-area I,R,B,Y] [--max-nodes N] [--max-candidates N] [--max-parts N] [--max-votes N] [--max-hypotheses N] [--gate 0|1] [--candidate-score S] [--candidate-iou U] [--views N] [--triangle-view 0|1] [--triangle-score S] [--picto FILE | --no-picto]\n", argv[0]);
            return 2;
        }
    }
    if (input.empty() || det_path.empty()) {
        std::fprintf(stderr, "sbr_detect: --input and --detections are required (--help)\n");
        return 2;
    }
#ifndef SBR_HAVE_CALLGRIND
    if (callgrind) {
        std::fprintf(stderr, "sbr_detect: --callgrind: built without valgrind/callgrind.h\n");
        return 2;
    }
#endif
    if (repeat < 1 || repeat > 20) {
        std::fprintf(stderr, "sbr_detect: --repeat wants 1..20\n");
        return 2;
    }
    Model loaded;
    sbr_model_t builtin{};
    sbr_model_gtsdb(&builtin);
    const sbr_model_t *model = &builtin;
    if (!model_path.empty()) {
        const std::string e = load_model(model_path, loaded);
        if (!e.empty()) { std::fprintf(stderr, "sbr_detect: %s\n", e.c_str()); return 1; }
        model = &loaded.view;
    }
    Picto picto;
    sbr_model_t with_picto = *model;
    if (!picto_path.empty()) {
        const std::string e = load_picto(picto_path, picto);
        if (!e.empty()) { std::fprintf(stderr, "sbr_detect: %s\n", e.c_str()); return 1; }
        with_picto.picto = picto.view;
        model = &with_picto;
    } else if (no_picto) {
        with_picto.picto = sbr_picto_model_t{};
        model = &with_picto;
    }
    // the operating point: the class stage's, or the part model's without one
    if (threshold < 0.0f) threshold = model->picto.version != 0 ? model->picto.threshold : model->score_threshold;
    sbr_recog_config_t cfg;
    sbr_recog_config_default(&cfg);
    cfg.parts.subsample = subsample;
    cfg.min_score = std::min(cfg.min_score, threshold);
    if (!all_path.empty()) cfg.min_score = std::min(cfg.min_score, 0.05f);  // the curve's tail
    if (min_score >= 0.0f) cfg.min_score = min_score;
    if (min_parts >= 0) cfg.min_parts = uint32_t(min_parts);
    if (refine_steps >= 0) cfg.refine_steps = uint32_t(refine_steps);
    if (refine_score >= 0.0f) cfg.refine_score = refine_score;
    if (refine_first_score >= 0.0f) cfg.refine_first_score = refine_first_score;
    if (view_score >= 0.0f) cfg.view_score = view_score;
    if (candidate_score >= 0.0f) cfg.candidate_score = candidate_score;
    if (candidate_iou >= 0.0f) cfg.candidate_iou = candidate_iou;
    apply_front_end(front_end, cfg.parts);
    if (maps >= 0) cfg.parts.maps = uint32_t(maps);
    if (max_nodes >= 0) cfg.parts.mser.max_nodes = uint32_t(max_nodes);
    if (max_candidates >= 0) cfg.max_candidates = uint32_t(max_candidates);
    if (max_parts >= 0) cfg.max_parts = uint32_t(max_parts);
    if (gate_opt >= 0) cfg.gate = uint32_t(gate_opt);
    if (max_votes >= 0) cfg.max_votes = uint32_t(max_votes);
    if (max_hyps >= 0) cfg.max_hypotheses = uint32_t(max_hyps);
    if (views_opt >= 0) cfg.views = uint32_t(views_opt);
    if (triangle_view >= 0) cfg.triangle_view = uint32_t(triangle_view);
    if (triangle_score >= 0.0f) cfg.triangle_score = triangle_score;
    if (vote_error >= 0.0f) cfg.vote_error = vote_error;
    if (verify_error >= 0.0f) cfg.verify_error = verify_error;
    CallgrindClock cg;
    cfg.clock = host_clock;
    if (callgrind) {
        cfg.clock = callgrind_clock;
        cfg.clock_ctx = &cg;
        repeat = 1;
    }
    sbr_status_t st = sbr_recog_config_check(&cfg);
    if (st != SBR_OK) { std::fprintf(stderr, "sbr_detect: bad configuration: %s\n", sbr_status_str(st)); return 2; }

    const std::string dir = gtsdb_image_dir(input);
    std::vector<std::string> files;
    for (const auto &f : list_images(dir)) {
        const int n = image_number(f);
        if (range.empty() || range.contains(n)) files.push_back(f);
    }
    if (files.empty()) { std::fprintf(stderr, "sbr_detect: no images in %s\n", dir.c_str()); return 1; }
    std::ofstream det(det_path), all;
    if (!det) { std::fprintf(stderr, "sbr_detect: cannot write %s\n", det_path.c_str()); return 1; }
    if (!all_path.empty()) all.open(all_path);
    if (!annotated.empty()) fs::create_directories(annotated);
    std::unique_ptr<CanLogWriter> can;
    if (!canlog.empty()) {
        can.reset(new CanLogWriter(canlog));
        if (!can->ok()) { std::fprintf(stderr, "sbr_detect: cannot write %s\n", canlog.c_str()); return 1; }
    }

    std::vector<uint64_t> ws;
    size_t ws_bytes = 0;
    std::vector<sbr_detection_t> dets(256);
    std::vector<double> ms_total;
    std::vector<std::vector<double>> ms_stage(SBR_RECOG_STAGES);
    size_t ndet = 0, nall = 0, failed = 0, capacity_frames = 0;
    size_t capacity_kind[5] = {0, 0, 0, 0, 0};
    size_t classified = 0, refined = 0, views = 0, rim_rejected = 0, gated = 0, frames_run = 0;
    uint64_t parts_total = 0;
    double sum_ms = 0;
    for (size_t i = 0; i < files.size(); ++i) {
        cv::Mat img = cv::imread(files[i], cv::IMREAD_COLOR);
        const std::string name = fs::path(files[i]).stem().string() + ".jpg";
        std::vector<sbr_detection_t> kept;
        sbr_recog_stats_t stats{};
        float frame_ms = 0.0f;
        bool error = false;
        if (img.empty()) {
            std::fprintf(stderr, "\nsbr_detect: cannot read %s\n", files[i].c_str());
            ++failed;
            error = true;
        } else {
            const sbr_image_t v = bgr_view(img);
            const uint32_t w = use_roi ? roi.width : v.width, h = use_roi ? roi.height : v.height;
            const size_t need = sbr_recog_workspace_size(&cfg, w, h);
            if (need > ws.size() * 8) ws.assign(need / 8 + 1, 0);
            ws_bytes = std::max(ws_bytes, need);
            uint32_t n = 0;
            double ms = 0.0;
            for (int r = 0; r < repeat; ++r) {
                sbr_recog_stats_t run_stats{};
                const auto t0 = std::chrono::steady_clock::now();
#ifdef SBR_HAVE_CALLGRIND
                if (callgrind) {  // collect only inside sbr_recog_detect
                    cg.frame = fs::path(files[i]).stem().string();
                    cg.tick = 0;
                    CALLGRIND_ZERO_STATS;
                    CALLGRIND_TOGGLE_COLLECT;
                }
#endif
                st = sbr_recog_detect(&v, use_roi ? &roi : nullptr, &cfg, model, ws.data(), ws.size() * 8,
                                      dets.data(), uint32_t(dets.size()), &n, &run_stats);
#ifdef SBR_HAVE_CALLGRIND
                if (callgrind) {
                    const std::string label = "frame " + cg.frame + " end";
                    CALLGRIND_DUMP_STATS_AT(label.c_str());
                    CALLGRIND_TOGGLE_COLLECT;
                }
#endif
                const double run_ms =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                if (r == 0 || run_ms < ms) {
                    ms = run_ms;
                    stats = run_stats;
                }
            }
            if (st != SBR_OK && st != SBR_ERR_CAPACITY) {
                std::fprintf(stderr, "\nsbr_detect: %s: %s\n", files[i].c_str(), sbr_status_str(st));
                ++failed;
                error = true;
                n = 0;
            }
            frame_ms = float(ms);
            ms_total.push_back(ms);
            sum_ms += ms;
            for (unsigned s = 0; s < SBR_RECOG_STAGES; ++s) ms_stage[s].push_back(stats.stage_ticks[s] / 1000.0);
            parts_total += stats.parts;
            if (stats.capacity_hit != 0 || st == SBR_ERR_CAPACITY) ++capacity_frames;
            for (unsigned b = 0; b < 5; ++b) capacity_kind[b] += (stats.capacity_hit >> b) & 1u;
            classified += stats.classified;
            refined += stats.refined;
            views += stats.views;
            rim_rejected += stats.rim_rejected;
            gated += stats.gated;
            ++frames_run;
            for (uint32_t k = 0; k < n; ++k) {
                const auto &d = dets[k];
                char line[160];
                std::snprintf(line, sizeof line, "%s;%u;%u;%u;%u;%u;%.4f\n", name.c_str(), d.box.x, d.box.y,
                              d.box.x + d.box.width - 1, d.box.y + d.box.height - 1, unsigned(d.class_id),
                              double(d.score));
                if (all.is_open()) { all << line; ++nall; }
                if (d.score >= threshold) { det << line; kept.push_back(d); ++ndet; }
            }
            if (!annotated.empty()) {
                annotate(img, kept);
                cv::imwrite((fs::path(annotated) / name).string(), img);
            }
        }
        if (can) {
            std::vector<Detection> cd;
            for (const auto &d : kept)
                cd.push_back({int(d.box.x), int(d.box.y), int(d.box.x + d.box.width - 1),
                              int(d.box.y + d.box.height - 1), int(d.class_id), d.score});
            if (sequence && i == 0 && !can->enable_tracking(float(img.cols), float(img.rows))) {
                std::fprintf(stderr, "sbr_detect: sign tracker set-up failed\n");
                return 1;
            }
            can->write_image(cd, frame_ms, stats.parts_stats.regions, error);
        }
        if (!quiet) progress(i + 1, files.size(), ms_total.empty() ? 0.0 : sum_ms / double(ms_total.size()));
    }

    std::ostringstream s;
    const char *stage_names[SBR_RECOG_STAGES] = {"parts (maps, MSER, contours, FDs)", "matching and votes",
                                                 "grouping", "evidence and cascade", "NMS on part scores",
                                                 "class stage (pictograms)"};
    s << "sbr_detect summary\n";
    s << "input: " << dir << " (" << files.size() << " images, " << failed << " failed)\n";
    s << "model: " << (model_path.empty() ? "built-in (lib/models/sbr_model_gtsdb.c)" : model_path) << ", "
      << model->proto_count << " prototypes, class stage "
      << (model->picto.version != 0 ? (picto_path.empty() ? "built-in (lib/models/sbr_picto_gtsdb.c)" : picto_path) : "none")
      << ", operating point score >= " << threshold << "\n";
    s << "detections: " << ndet << " at the operating point";
    if (all.is_open()) s << ", " << nall << " in all";
    s << "\nparts per frame (mean): " << (ms_total.empty() ? 0 : parts_total / ms_total.size()) << "\n";
    char buf[256];
    const std::string runs = repeat > 1 ? ", fastest of " + std::to_string(repeat) + " runs" : "";
    std::snprintf(buf, sizeof buf, "time per frame (one core%s): median %.1f ms, 95th percentile %.1f ms\n",
                  runs.c_str(), percentile(ms_total, 0.5), percentile(ms_total, 0.95));
    s << buf;
    for (unsigned k = 0; k < SBR_RECOG_STAGES; ++k) {
        std::snprintf(buf, sizeof buf, "  %-36s median %.1f ms, 95th percentile %.1f ms\n", stage_names[k],
                      percentile(ms_stage[k], 0.5), percentile(ms_stage[k], 0.95));
        s << buf;
    }
    s << "workspace: " << ws_bytes << " bytes (" << (use_roi ? "ROI" : "frame") << ", subsample " << subsample << ")\n";
    s << "frames with an internal bound reached: " << capacity_frames << " (parts " << capacity_kind[0]
      << ", votes " << capacity_kind[1] << ", hypotheses " << capacity_kind[2] << ", MSER " << capacity_kind[3]
      << ", candidates " << capacity_kind[4] << ")\n";
    if (frames_run > 0 && classified > 0) {
        char cbuf[256];
        std::snprintf(cbuf, sizeof cbuf, "class stage per frame (mean): %.1f candidates classified, %.1f boxes refined, %.1f extra views, "
                      "%.1f rejected by the gate; colour check: %zu candidates dropped in all\n",
                      double(classified) / double(frames_run), double(refined) / double(frames_run),
                      double(views) / double(frames_run), double(gated) / double(frames_run), rim_rejected);
        s << cbuf;
    }
    if (can) s << "CAN log: " << canlog << " (" << can->frames_written() << " frames)\n";
    if (!annotated.empty()) s << "annotated images: " << annotated << "\n";
    std::fputs(s.str().c_str(), stdout);
    if (!summary_path.empty()) std::ofstream(summary_path) << s.str();
    return failed == files.size() ? 1 : 0;
}
