// SPDX-License-Identifier: MIT
// sbr_train: learns the recogniser's prototype library from annotated GTSDB images.
//
//   sbr_train [--data DIR] [--range A-B] [--out-c FILE] [--out-model FILE]
//             [--vote-error E] [--min-support N] [--max-protos N] [--min-weight W]
//             [--no-calibrate] [--map-subsample I,R,B,Y] [--map-min-area I,R,B,Y]
//   sbr_train --from-model FILE --out-c FILE     (the C table of a saved library)
//
// Defaults: --data DATA/gtsdb (DATA: the build's SBR_DATA_DIR), --range 0-399 (the training split; 400-599 is
// the development split and is never read), --vote-error 0.12, --min-support 2,
// --max-protos 640, --min-weight 0. Writes the generated C table (--out-c, e.g. lib/models/sbr_model_gtsdb.c)
// and/or the file form (--out-model, e.g. sbr_gtsdb.sbrm). Parts are learned with every
// map at full resolution unless --map-subsample / --map-min-area (sbr_detect's options of
// those names) give the part stage to learn with (to measure a coarser front end with
// prototypes of its own: docs/results/realtime.md).
//
// Method (paper D's part model, learned from data instead of synthetic icons):
//  1. Parts of every training image with the recogniser's default part extraction.
//  2. Instances: parts inside an annotated box (10 % margin) whose box is at least a
//     quarter of the sign's size, with the sign centre offset and size in part scales.
//     Background: parts that touch no annotated box.
//  3. Stable parts: two instances of different signs are neighbours when they lie in the
//     same map/polarity group, match with error <= vote-error (covariant, rotation
//     <= 0.35 rad), and predict the same centre (within 0.2 of the sign size) and size
//     (within a factor 1.3). Greedily, the instance with most neighbouring signs becomes a
//     prototype and takes its unassigned neighbours; stops below --min-support signs.
//     Classes left without a prototype get their instances' largest parts (support 1).
//  4. Classes of a prototype: the classes of its member signs (up to 4, with shares).
//     Weight: its precision as a voter, signs / (signs + background parts it matches);
//     prototypes below --min-weight are dropped (they mostly vote for clutter).
//  5. Cascade per class: its prototypes by share x support x weight.
//  6. Operating point: the recogniser runs over the training images with the new library
//     and the score threshold with the best class-level F1 there is stored in the model.
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cli.hpp"
#include "gtsdb.hpp"
#include "model_io.hpp"
#include "parallel.hpp"
#include "recog_run.hpp"

extern "C" {
#include "sbr/recog.h"
#include "sbr/models.h"
}

using namespace sbr_host;

namespace {

constexpr unsigned kThreads = 4;  // at most, for parts extraction and calibration

struct Instance {
    sbr_fd_t fd;
    int group = 0;
    float dx = 0, dy = 0, w = 0, h = 0;
    int cls = 0;
    int sign = 0;      // global sign index
    float area = 0;    // part box area, for "largest part"
};

struct Frame {
    std::vector<sbr_part_t> parts;
};

int group_of(const sbr_part_t &p) { return int(sbr_model_group(p.map, p.polarity)); }

// Parts of one image (workspace per thread).
bool extract(const std::string &path, const sbr_recog_config_t &cfg, std::vector<uint64_t> &ws,
             std::vector<sbr_part_t> &out) {
    cv::Mat img = cv::imread(path, cv::IMREAD_COLOR);
    if (img.empty()) return false;
    sbr_image_t v = bgr_view(img);
    const size_t need = sbr_parts_workspace_size(&cfg.parts, v.width, v.height);
    if (ws.size() * 8 < need) ws.assign(need / 8 + 1, 0);
    sbr_fft_t fft;
    sbr_fft_init(&fft, cfg.parts.fd_n);
    out.resize(cfg.max_parts);
    uint32_t n = 0;
    sbr_status_t st = sbr_parts_extract(&v, &cfg.parts, &fft, ws.data(), ws.size() * 8, out.data(),
                                        cfg.max_parts, &n, nullptr);
    if (st != SBR_OK && st != SBR_ERR_CAPACITY) return false;
    out.resize(n);
    return true;
}

bool consistent(const Instance &a, const Instance &b, float centre_tol, float size_f) {
    return std::fabs(a.dx - b.dx) <= centre_tol * b.w && std::fabs(a.dy - b.dy) <= centre_tol * b.h &&
           a.w <= b.w * size_f && a.w * size_f >= b.w && a.h <= b.h * size_f && a.h * size_f >= b.h;
}

struct Options {
    std::string data = std::string(SBR_DATA_ROOT) + "/gtsdb", out_c, out_model, from_model;
    ImageRanges range{{{0, 399}}};
    float vote_error = 0.12f;
    int min_support = 2;
    size_t max_protos = 640;
    bool calibrate = true;
    float min_weight = 0.0f;
    FrontEnd front_end;  // --map-subsample, --map-min-area: the part stage learned with
};

// -1: go on; otherwise the exit status.
int parse_options(int argc, char **argv, Options &o) {
    CLI::App app{"sbr_train: learns the recogniser's prototype library (part FDs, star-model votes, cascade) "
                 "from GTSDB (docs/usage/detect.md); --from-model: regenerate the C table from a file"};
    app.add_option("--data", o.data, "GTSDB folder")->capture_default_str();
    add_range_option(app, o.range, "training images (default 0-399)");
    app.add_option("--out-c", o.out_c, "write the library as a C table (lib/models/sbr_model_gtsdb.c)");
    app.add_option("--out-model", o.out_model, "write the library as a model file (.sbrm)");
    app.add_option("--vote-error", o.vote_error, "largest FD error of a vote")
        ->check(finite_range(1e-6, 4.0))
        ->capture_default_str();
    app.add_option("--min-support", o.min_support, "training parts a prototype needs")
        ->check(CLI::Range(1, 1000000))
        ->capture_default_str();
    app.add_option("--max-protos", o.max_protos, "prototypes kept")
        ->check(CLI::Range(size_t(1), size_t(65535)))
        ->capture_default_str();
    app.add_flag("--no-calibrate", [&o](int64_t) { o.calibrate = false; }, "keep the vote weights uncalibrated");
    app.add_option("--min-weight", o.min_weight, "drop prototypes with a smaller vote weight")
        ->check(finite_range(0.0, 1.0))
        ->capture_default_str();
    app.add_option("--from-model", o.from_model, "regenerate --out-c from this model file, without training");
    add_front_end_options(app, o.front_end);
    return parse_cli(app, argc, argv);
}

// --from-model: the C table of a file form, without training.
int regenerate(const Options &o) {
    Model m;
    std::string e = load_model(o.from_model, m);
    if (e.empty() && !o.out_c.empty()) {
        char head[512];
        std::snprintf(head, sizeof head,
                      "Prototype library for sbr's recogniser. GENERATED by sbr_train - do not edit.\n"
                      "Regenerate: ./sbr.sh train (learns from GTSDB 00000-00399), or from a file form:\n"
                      "            sbr_train --from-model FILE --out-c lib/models/sbr_model_gtsdb.c\n"
                      "Library: %u prototypes, %u cascade entries, operating point score >= %.4f.",
                      m.view.proto_count, unsigned(m.cascade.size()), double(m.view.score_threshold));
        e = write_model_c(m, o.out_c, head);
    }
    if (!e.empty()) {
        std::fprintf(stderr, "sbr_train: %s\n", e.c_str());
        return 1;
    }
    std::printf("prototypes=%u cascade=%zu score_threshold=%.4f\n", m.view.proto_count, m.cascade.size(),
                double(m.view.score_threshold));
    return 0;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The training images and their annotations.
struct TrainingSet {
    std::vector<std::string> files;
    std::map<int, std::vector<GtBox>> gt;
    const std::vector<GtBox> &boxes(const std::string &file) const {
        static const std::vector<GtBox> none;
        const auto it = gt.find(image_number(file));
        return it == gt.end() ? none : it->second;
    }
};

// Step 2's result: part instances inside annotated signs, background parts per group.
struct Instances {
    std::vector<Instance> inst;
    std::vector<std::vector<sbr_fd_t>> background = std::vector<std::vector<sbr_fd_t>>(SBR_MODEL_GROUPS);
    std::map<int, int> signs_per_class;
    int nsigns = 0;
    size_t background_count() const {
        size_t n = 0;
        for (const auto &g : background) n += g.size();
        return n;
    }
};

// 1. Parts of every image, on up to kThreads threads.
std::vector<Frame> extract_all(const TrainingSet &ts, const sbr_recog_config_t &cfg) {
    std::vector<Frame> frames(ts.files.size());
    parallel_for<std::vector<uint64_t>>(ts.files.size(), kThreads, [&](size_t i, std::vector<uint64_t> &ws) {
        extract(ts.files[i], cfg, ws, frames[i].parts);
    });
    return frames;
}

// 2. One image's parts: an instance per annotated box that holds the part (10 % margin)
// and whose size it reaches a quarter of; background when it touches no box.
void collect_frame(const std::vector<GtBox> &boxes, const std::vector<int> &sign_ids, const Frame &frame,
                   Instances &out) {
    for (const auto &p : frame.parts) {
        const float px0 = float(p.bbox.x), py0 = float(p.bbox.y);
        const float px1 = px0 + float(p.bbox.width), py1 = py0 + float(p.bbox.height);
        bool touches = false;
        for (size_t k = 0; k < boxes.size(); ++k) {
            const PixBox g = gt_pixbox(boxes[k]);
            const float x0 = float(g.x0), y0 = float(g.y0), x1 = float(g.x1), y1 = float(g.y1);
            const float bw = x1 - x0, bh = y1 - y0;
            const float m = 0.1f * std::max(bw, bh) + 1.0f;
            if (px1 > x0 - 2 * m && px0 < x1 + 2 * m && py1 > y0 - 2 * m && py0 < y1 + 2 * m) touches = true;
            const bool inside = px0 >= x0 - m && py0 >= y0 - m && px1 <= x1 + m && py1 <= y1 + m;
            if (!inside || std::max(p.bbox.width, p.bbox.height) < 0.25f * std::max(bw, bh)) continue;
            Instance in;
            in.fd = p.fd;
            in.group = group_of(p);
            const float s = p.fd.scale;
            in.dx = (0.5f * (x0 + x1) - p.fd.cx) / s;
            in.dy = (0.5f * (y0 + y1) - p.fd.cy) / s;
            in.w = bw / s;
            in.h = bh / s;
            in.cls = boxes[k].class_id;
            in.sign = sign_ids[k];
            in.area = float(p.bbox.width) * float(p.bbox.height);
            out.inst.push_back(in);
        }
        if (!touches) out.background[size_t(group_of(p))].push_back(p.fd);
    }
}

Instances collect_instances(const TrainingSet &ts, const std::vector<Frame> &frames) {
    Instances out;
    for (size_t i = 0; i < ts.files.size(); ++i) {
        const auto &boxes = ts.boxes(ts.files[i]);
        std::vector<int> sign_ids;
        for (const auto &b : boxes) {
            sign_ids.push_back(out.nsigns++);
            out.signs_per_class[b.class_id]++;
        }
        collect_frame(boxes, sign_ids, frames[i], out);
    }
    std::set<int> any;
    for (const auto &in : out.inst) any.insert(in.sign);
    std::fprintf(stderr, "sbr_train: signs with at least one part instance: %zu of %d\n", any.size(), out.nsigns);
    return out;
}

// The matcher of steps 3 and 4: rotation covariant, the recogniser's rotation bound.
struct Matcher {
    sbr_fft_t fft;
    sbr_fd_match_config_t mc;
    std::vector<sbr_complex_t> work;
    explicit Matcher(const sbr_recog_config_t &cfg) : work(SBR_FD_TABLE_WORK_LEN(cfg.match_p)) {
        sbr_fft_init(&fft, cfg.match_p);
        sbr_fd_match_config_default(&mc);
        mc.mode = SBR_FD_ROTATION_COVARIANT;
        mc.max_rotation = cfg.max_rotation;
    }
    // q against every descriptor of table into res; false when the matcher refuses.
    bool match(const sbr_fd_t &q, const std::vector<sbr_fd_t> &table, std::vector<sbr_fd_match_t> &res) {
        uint32_t best = 0;
        res.resize(table.size());
        return !table.empty() && sbr_fd_match_table(&fft, &mc, &q, table.data(), uint32_t(table.size()), work.data(),
                                                    uint32_t(work.size()), res.data(), &best) == SBR_OK;
    }
};

// 3. Neighbours: instances of other signs in the same group that match and predict the
// same centre and size.
std::vector<std::vector<int>> neighbours(const std::vector<Instance> &inst, const sbr_recog_config_t &cfg,
                                         float vote_error, Matcher &mt) {
    const float centre_tol = cfg.centre_tol, size_f = 1.0f + cfg.size_tol;
    std::vector<std::vector<int>> by_group(SBR_MODEL_GROUPS);
    for (size_t i = 0; i < inst.size(); ++i) by_group[size_t(inst[i].group)].push_back(int(i));
    std::vector<std::vector<int>> nb(inst.size());
    std::vector<sbr_fd_t> table;
    std::vector<sbr_fd_match_t> res;
    for (const auto &g : by_group) {
        table.clear();
        for (int j : g) table.push_back(inst[size_t(j)].fd);
        for (int i : g) {
            if (!mt.match(inst[size_t(i)].fd, table, res)) continue;
            for (size_t k = 0; k < g.size(); ++k) {
                const int j = g[k];
                if (inst[size_t(j)].sign != inst[size_t(i)].sign && res[k].error <= vote_error &&
                    consistent(inst[size_t(i)], inst[size_t(j)], centre_tol, size_f))
                    nb[size_t(i)].push_back(j);
            }
        }
    }
    return nb;
}

struct Proto {
    int seed;
    std::vector<int> members;
    std::set<int> signs;
};

// Greedy stable parts: the instance with most neighbouring signs becomes a prototype and
// takes its free neighbours, until fewer than min_support signs.
std::vector<Proto> stable_parts(const std::vector<Instance> &inst, const std::vector<std::vector<int>> &nb,
                                int min_support) {
    std::vector<Proto> protos;
    std::vector<char> taken(inst.size(), 0);
    auto sign_count = [&](int i) {
        std::set<int> s{inst[size_t(i)].sign};
        for (int j : nb[size_t(i)]) if (!taken[size_t(j)]) s.insert(inst[size_t(j)].sign);
        return s;
    };
    for (;;) {
        int best = -1;
        size_t best_n = 0;
        for (size_t i = 0; i < inst.size(); ++i) {
            if (taken[i]) continue;
            const size_t n = sign_count(int(i)).size();
            if (n > best_n) { best_n = n; best = int(i); }
        }
        if (best < 0 || best_n < size_t(min_support)) break;
        Proto p;
        p.seed = best;
        p.signs = sign_count(best);
        p.members.push_back(best);
        taken[size_t(best)] = 1;
        for (int j : nb[size_t(best)]) if (!taken[size_t(j)]) { taken[size_t(j)] = 1; p.members.push_back(j); }
        protos.push_back(p);
    }
    return protos;
}

// Classes without a prototype: their signs' largest parts (two per sign, four per class).
void add_uncovered_classes(const Instances &in, std::vector<Proto> &protos) {
    const auto &inst = in.inst;
    std::set<int> covered;
    for (const auto &p : protos)
        for (int j : p.members) covered.insert(inst[size_t(j)].cls);
    for (const auto &sc : in.signs_per_class) {
        if (covered.count(sc.first)) continue;
        std::map<int, std::vector<int>> per_sign;
        for (size_t i = 0; i < inst.size(); ++i) if (inst[i].cls == sc.first) per_sign[inst[i].sign].push_back(int(i));
        int added = 0;
        for (auto &ps : per_sign) {
            auto &v = ps.second;
            std::sort(v.begin(), v.end(), [&](int a, int b) { return inst[size_t(a)].area > inst[size_t(b)].area; });
            for (size_t k = 0; k < v.size() && k < 2 && added < 4; ++k, ++added) {
                Proto p;
                p.seed = v[k];
                p.members = {v[k]};
                p.signs = {inst[size_t(v[k])].sign};
                protos.push_back(p);
            }
        }
    }
}

struct Built {
    sbr_fd_t fd;
    sbr_model_proto_t p;
    float rank;
};

// 4. One prototype: mean geometry of its members, classes by share of signs, weight =
// its precision as a voter against the background parts of its group.
Built build_proto(const Proto &pr, const Instances &in, const sbr_recog_config_t &cfg, float vote_error,
                  Matcher &mt, std::vector<sbr_fd_match_t> &res) {
    const auto &inst = in.inst;
    const Instance &s = inst[size_t(pr.seed)];
    Built b{};
    b.fd = s.fd;
    double dx = 0, dy = 0, w = 0, h = 0;
    std::map<int, std::set<int>> cls_signs;
    for (int j : pr.members) {
        const Instance &m = inst[size_t(j)];
        dx += m.dx; dy += m.dy; w += m.w; h += m.h;
        cls_signs[m.cls].insert(m.sign);
    }
    const double n = double(pr.members.size());
    b.p.dx = float(dx / n); b.p.dy = float(dy / n); b.p.w = float(w / n); b.p.h = float(h / n);
    b.p.map = uint8_t(s.group / 2);
    b.p.polarity = uint8_t(s.group % 2 + 1);
    b.p.support = uint16_t(std::min<size_t>(65535, pr.signs.size()));
    std::vector<std::pair<int, int>> cs;
    for (const auto &c : cls_signs) cs.push_back({int(c.second.size()), c.first});
    std::sort(cs.rbegin(), cs.rend());
    for (unsigned k = 0; k < SBR_MODEL_PROTO_CLASSES; ++k) {
        b.p.class_id[k] = SBR_MODEL_NO_CLASS;
        b.p.class_p[k] = 0.0f;
        if (k < cs.size()) {
            b.p.class_id[k] = uint8_t(cs[k].second);
            b.p.class_p[k] = float(cs[k].first) / float(pr.signs.size());
        }
    }
    // background matches that would vote for a sign of plausible size. The error is
    // symmetric (swapping query and prototype conjugates r and mirrors the shift; max Re r
    // and |rotation| stay), so the prototype is the query and the background group the
    // table: one four-lane pass instead of a call per part.
    size_t neg = 0;
    const auto &bg = in.background[size_t(s.group)];
    if (mt.match(b.fd, bg, res)) {
        for (size_t k = 0; k < bg.size(); ++k) {
            const float size = std::max(b.p.w, b.p.h) * bg[k].scale;
            if (res[k].error <= vote_error && size >= cfg.min_size && size <= cfg.max_size) ++neg;
        }
    }
    const float pos = float(pr.signs.size());
    b.p.weight = std::max(1e-4f, pos / (pos + float(neg)));
    b.rank = pos * b.p.weight;
    return b;
}

// The prototypes kept: weight >= min_weight, the max_protos best ranked, in group order.
std::vector<Built> select_protos(std::vector<Built> built, float min_weight, size_t max_protos) {
    const size_t before_prune = built.size();
    built.erase(std::remove_if(built.begin(), built.end(), [&](const Built &b) { return b.p.weight < min_weight; }),
                built.end());
    std::fprintf(stderr, "sbr_train: %zu of %zu prototypes kept with weight >= %g\n", built.size(), before_prune,
                 double(min_weight));
    std::sort(built.begin(), built.end(), [](const Built &a, const Built &b) { return a.rank > b.rank; });
    if (built.size() > max_protos) built.resize(max_protos);
    std::stable_sort(built.begin(), built.end(), [](const Built &a, const Built &b) {
        return sbr_model_group(a.p.map, a.p.polarity) < sbr_model_group(b.p.map, b.p.polarity);
    });
    return built;
}

// 5. The model: groups, GTSDB's classes and their cascades.
Model assemble(const std::vector<Built> &built, const sbr_recog_config_t &cfg, float vote_error) {
    Model m;
    m.view.version = SBR_MODEL_VERSION;
    m.view.fd_n = cfg.parts.fd_n;
    m.view.fd_m = cfg.parts.fd_m;
    m.view.vote_error = vote_error;
    m.view.score_threshold = 0.5f;
    for (const auto &b : built) { m.fds.push_back(b.fd); m.protos.push_back(b.p); }
    for (unsigned g = 0; g <= SBR_MODEL_GROUPS; ++g) {
        size_t first = 0;
        while (first < m.protos.size() && sbr_model_group(m.protos[first].map, m.protos[first].polarity) < g) ++first;
        m.view.group_first[g] = uint16_t(first);
    }
    m.view.class_count = kGtsdbClasses;
    for (unsigned c = 0; c < kGtsdbClasses; ++c) {
        m.view.class_outline[c] = class_outline_of(int(c));
        m.view.class_first[c] = uint16_t(m.cascade.size());
        std::vector<std::pair<float, int>> order;
        for (size_t k = 0; k < m.protos.size(); ++k)
            for (unsigned t = 0; t < SBR_MODEL_PROTO_CLASSES; ++t)
                if (m.protos[k].class_id[t] == c)
                    order.push_back({m.protos[k].class_p[t] * m.protos[k].support * m.protos[k].weight, int(k)});
        std::sort(order.rbegin(), order.rend());
        for (const auto &o : order) m.cascade.push_back(uint16_t(o.second));
    }
    m.view.class_first[kGtsdbClasses] = uint16_t(m.cascade.size());
    m.bind();
    return m;
}

struct Scored {
    float score;
    bool tp;
};

// The recogniser's detections on one image, each marked true when it takes a free
// annotated box of its class at IoU >= 0.5.
void score_image(const std::string &file, const std::vector<GtBox> &boxes, const sbr_recog_config_t &rc,
                 const Model &m, std::vector<uint64_t> &ws, std::vector<Scored> &local) {
    std::vector<sbr_detection_t> dets(256);
    cv::Mat img = cv::imread(file, cv::IMREAD_COLOR);
    if (img.empty()) return;
    sbr_image_t v = bgr_view(img);
    uint32_t n = 0;
    if (sbr_host::recog_once(rc, m.view, m.picto_view(), ws, v, nullptr, dets.data(), uint32_t(dets.size()), &n,
                             nullptr) < 0 &&
        n == 0)
        return;
    std::vector<char> used(boxes.size(), 0);
    for (uint32_t k = 0; k < n; ++k) {
        const auto &d = dets[k];
        bool tp = false;
        for (size_t g = 0; g < boxes.size() && !tp; ++g) {
            if (used[g] || boxes[g].class_id != d.class_id) continue;
            if (box_iou(gt_pixbox(boxes[g]), rect_pixbox(d.box)) >= 0.5) { used[g] = 1; tp = true; }
        }
        local.push_back({d.score, tp});
    }
}

// 6. The operating point: the score threshold with the best class-level F1 on the
// training images.
void calibrate(Model &m, const sbr_recog_config_t &cfg, const TrainingSet &ts, int nsigns,
               std::chrono::steady_clock::time_point t0) {
    sbr_recog_config_t rc = cfg;
    rc.min_score = 0.0f;
    std::vector<std::vector<Scored>> per_image(ts.files.size());
    parallel_for<std::vector<uint64_t>>(ts.files.size(), kThreads, [&](size_t i, std::vector<uint64_t> &ws) {
        score_image(ts.files[i], ts.boxes(ts.files[i]), rc, m, ws, per_image[i]);
    });
    std::vector<Scored> scored;
    for (const auto &l : per_image) scored.insert(scored.end(), l.begin(), l.end());
    std::sort(scored.begin(), scored.end(), [](const Scored &a, const Scored &b) { return a.score > b.score; });
    int tp = 0, fp = 0;
    float best_f1 = -1, best_t = 0.5f;
    for (size_t k = 0; k < scored.size(); ++k) {
        scored[k].tp ? ++tp : ++fp;
        if (k + 1 < scored.size() && scored[k + 1].score == scored[k].score) continue;
        const float p = float(tp) / float(tp + fp), r = float(tp) / float(nsigns);
        const float f1 = p + r > 0 ? 2 * p * r / (p + r) : 0;
        if (f1 > best_f1) { best_f1 = f1; best_t = scored[k].score; }
    }
    m.view.score_threshold = best_t;
    std::fprintf(stderr, "sbr_train: operating point score >= %.4f (class-level F1 %.3f on the training images, %.1f s)\n",
                 best_t, best_f1, seconds_since(t0));
}

// The recogniser's configuration the library is learned with: every map (the recogniser
// runs a subset; its default leaves the red map out, an integrator may add it), at full
// resolution (descriptors are scale-normalised, see parts.map_subsample) unless
// --map-subsample / --map-min-area say otherwise.
sbr_recog_config_t training_config(const Options &o) {
    sbr_recog_config_t cfg;
    sbr_recog_config_default(&cfg);
    cfg.parts.maps = 0x7u;
    parts_at_full_resolution(cfg.parts);
    training_bounds(cfg);
    apply_front_end(o.front_end, cfg.parts);
    return cfg;
}

// Steps 1 to 5: the library before its operating point.
Model learn_library(const Options &o, const TrainingSet &ts, const sbr_recog_config_t &cfg, Instances &in,
                    std::chrono::steady_clock::time_point t0) {
    const std::vector<Frame> frames = extract_all(ts, cfg);
    in = collect_instances(ts, frames);
    std::fprintf(stderr, "sbr_train: %zu images, %d signs, %zu part instances, %zu background parts (%.1f s)\n",
                 ts.files.size(), in.nsigns, in.inst.size(), in.background_count(), seconds_since(t0));
    Matcher mt(cfg);
    const auto nb = neighbours(in.inst, cfg, o.vote_error, mt);
    std::vector<Proto> protos = stable_parts(in.inst, nb, o.min_support);
    add_uncovered_classes(in, protos);
    std::vector<Built> built;
    std::vector<sbr_fd_match_t> res;
    for (const auto &pr : protos) built.push_back(build_proto(pr, in, cfg, o.vote_error, mt, res));
    return assemble(select_protos(std::move(built), o.min_weight, o.max_protos), cfg, o.vote_error);
}

// The outputs: the C table and/or the file form.
int write_outputs(const Options &o, const Model &m, const Instances &in) {
    char head[512];
    std::snprintf(head, sizeof head,
                  "Prototype library for sbr's recogniser. GENERATED by sbr_train - do not edit.\n"
                  "Regenerate: ./sbr.sh train   (runs sbr_train --range %s --vote-error %g --min-support %d\n"
                  "            --max-protos %zu --out-c lib/models/sbr_model_gtsdb.c on GTSDB)\n"
                  "Training: GTSDB images %s, %d signs, %zu part instances, %zu background parts.\n"
                  "Library: %zu prototypes, %zu cascade entries, operating point score >= %.4f.",
                  o.range.str().c_str(), double(o.vote_error), o.min_support, o.max_protos, o.range.str(true).c_str(),
                  in.nsigns, in.inst.size(), in.background_count(), m.protos.size(), m.cascade.size(),
                  double(m.view.score_threshold));
    if (!o.out_c.empty() && !report_write("sbr_train", o.out_c, write_model_c(m, o.out_c, head))) return 1;
    if (!o.out_model.empty() && !report_write("sbr_train", o.out_model, save_model(m, o.out_model))) return 1;
    std::printf("prototypes=%zu cascade=%zu score_threshold=%.4f\n", m.protos.size(), m.cascade.size(),
                double(m.view.score_threshold));
    return 0;
}

}  // namespace

int main(int argc, char **argv) {
    Options o;
    const int parsed = parse_options(argc, argv, o);
    if (parsed >= 0) return parsed;
    if (!o.from_model.empty()) return regenerate(o);
    TrainingSet ts;
    const std::string dir = gtsdb_image_dir(o.data);
    ts.gt = read_gt(dir + "/gt.txt");
    ts.files = list_images(dir, o.range);
    if (ts.files.empty() || ts.gt.empty()) {
        std::fprintf(stderr, "sbr_train: no training images or no gt.txt in %s\n", dir.c_str());
        return 77;
    }
    const sbr_recog_config_t cfg = training_config(o);
    const auto t0 = std::chrono::steady_clock::now();
    Instances in;
    Model m = learn_library(o, ts, cfg, in, t0);
    const sbr_status_t st = sbr_model_check(&m.view);
    if (st != SBR_OK) {
        std::fprintf(stderr, "sbr_train: the built model fails its check: %s\n", sbr_status_str(st));
        return 1;
    }
    int shared = 0;
    for (const auto &p : m.protos) shared += p.class_id[1] != SBR_MODEL_NO_CLASS;
    std::fprintf(stderr, "sbr_train: %zu prototypes (%d shared by several classes), cascade %zu entries (%.1f s)\n",
                 m.protos.size(), shared, m.cascade.size(), seconds_since(t0));
    if (o.calibrate) calibrate(m, cfg, ts, in.nsigns, t0);
    return write_outputs(o, m, in);
}
