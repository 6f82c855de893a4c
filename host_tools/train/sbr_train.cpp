// sbr_train: learns the recogniser's prototype library from annotated GTSDB images.
//
//   sbr_train [--data DIR] [--range A-B] [--out-c FILE] [--out-model FILE]
//             [--vote-error E] [--min-support N] [--max-protos N] [--min-weight W]
//             [--no-calibrate] [--map-subsample I,R,B,Y] [--map-min-area I,R,B,Y]
//   sbr_train --from-model FILE --out-c FILE     (the C table of a saved library)
//
// Defaults: --data ../shared/data/gtsdb, --range 0-399 (the training split; 400-599 is
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
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cli.hpp"
#include "gtsdb.hpp"
#include "model_io.hpp"

extern "C" {
#include "sbr/recognizer.h"
}

using namespace sbr_host;

namespace {

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

}  // namespace

int main(int argc, char **argv) {
    std::string data = "../shared/data/gtsdb", out_c, out_model;
    ImageRanges range{{{0, 399}}};
    float vote_error = 0.12f;
    int min_support = 2;
    size_t max_protos = 640;
    bool calibrate = true;
    float min_weight = 0.0f;
    std::string from_model;
    FrontEnd front_end;  // --map-subsample, --map-min-area: the part stage learned with
    {
        CLI::App app{"sbr_train: learns the recogniser's prototype library (part FDs, star-model votes, cascade) "
                     "from GTSDB (docs/usage/detect.md); --from-model: regenerate the C table from a file"};
        app.add_option("--data", data, "GTSDB folder")->capture_default_str();
        add_range_option(app, range, "training images (default 0-399)");
        app.add_option("--out-c", out_c, "write the library as a C table (lib/models/sbr_model_gtsdb.c)");
        app.add_option("--out-model", out_model, "write the library as a model file (.sbrm)");
        app.add_option("--vote-error", vote_error, "largest FD error of a vote")
            ->check(finite_range(1e-6, 4.0))
            ->capture_default_str();
        app.add_option("--min-support", min_support, "training parts a prototype needs")
            ->check(CLI::Range(1, 1000000))
            ->capture_default_str();
        app.add_option("--max-protos", max_protos, "prototypes kept")
            ->check(CLI::Range(size_t(1), size_t(65535)))
            ->capture_default_str();
        app.add_flag("--no-calibrate", [&calibrate](int64_t) { calibrate = false; },
                     "keep the vote weights uncalibrated");
        app.add_option("--min-weight", min_weight, "drop prototypes with a smaller vote weight")
            ->check(finite_range(0.0, 1.0))
            ->capture_default_str();
        app.add_option("--from-model", from_model, "regenerate --out-c from this model file, without training");
        add_front_end_options(app, front_end);
        const int parsed = parse_cli(app, argc, argv);
        if (parsed >= 0) return parsed;
    }
    if (!from_model.empty()) {
        // regenerate the C table from a file form, without training
        Model m;
        std::string e = load_model(from_model, m);
        if (e.empty() && !out_c.empty()) {
            char head[512];
            std::snprintf(head, sizeof head,
                          "Prototype library for sbr's recogniser. GENERATED by sbr_train - do not edit.\n"
                          "Regenerate: ./sbr.sh train (learns from GTSDB 00000-00399), or from a file form:\n"
                          "            sbr_train --from-model FILE --out-c lib/models/sbr_model_gtsdb.c\n"
                          "Library: %u prototypes, %u cascade entries, operating point score >= %.4f.",
                          m.view.proto_count, unsigned(m.cascade.size()), double(m.view.score_threshold));
            e = write_model_c(m, out_c, head);
        }
        if (!e.empty()) { std::fprintf(stderr, "sbr_train: %s\n", e.c_str()); return 1; }
        std::printf("prototypes=%u cascade=%zu score_threshold=%.4f\n", m.view.proto_count, m.cascade.size(),
                    double(m.view.score_threshold));
        return 0;
    }
    const std::string dir = gtsdb_image_dir(data);
    const auto gt = read_gt(dir + "/gt.txt");
    std::vector<std::string> files;
    for (const auto &f : list_images(dir)) {
        const int n = image_number(f);
        if (range.contains(n)) files.push_back(f);
    }
    if (files.empty() || gt.empty()) {
        std::fprintf(stderr, "sbr_train: no training images or no gt.txt in %s\n", dir.c_str());
        return 77;
    }
    sbr_recog_config_t cfg;
    sbr_recog_config_default(&cfg);
    // The library carries prototypes of the intensity, red and blue maps, whichever subset
    // the recogniser runs (its default leaves the red map out; an integrator may add it).
    cfg.parts.maps = 0x7u;
    // ... and learns them at full resolution (the recogniser may run a map coarser:
    // descriptors are scale-normalised, see parts.map_subsample)
    parts_at_full_resolution(cfg.parts);
    apply_front_end(front_end, cfg.parts);
    const float centre_tol = cfg.centre_tol, size_f = 1.0f + cfg.size_tol;
    const auto t0 = std::chrono::steady_clock::now();

    // 1. parts of every image (two threads)
    std::vector<Frame> frames(files.size());
    {
        std::atomic<size_t> next{0};
        auto work = [&]() {
            std::vector<uint64_t> ws;
            for (size_t i; (i = next++) < files.size();) extract(files[i], cfg, ws, frames[i].parts);
        };
        const unsigned nt = std::max(1u, std::min(4u, std::thread::hardware_concurrency()));
        std::vector<std::thread> th;
        for (unsigned t = 0; t < nt; ++t) th.emplace_back(work);
        for (auto &t : th) t.join();
    }

    // 2. instances and background
    std::vector<Instance> inst;
    std::vector<std::vector<sbr_fd_t>> background(SBR_MODEL_GROUPS);
    std::map<int, int> signs_per_class;
    int nsigns = 0;
    for (size_t i = 0; i < files.size(); ++i) {
        const int num = image_number(files[i]);
        const auto it = gt.find(num);
        const std::vector<GtBox> none;
        const auto &boxes = it == gt.end() ? none : it->second;
        std::vector<int> sign_ids;
        for (const auto &b : boxes) {
            sign_ids.push_back(nsigns++);
            signs_per_class[b.class_id]++;
        }
        for (const auto &p : frames[i].parts) {
            const float px0 = float(p.bbox.x), py0 = float(p.bbox.y);
            const float px1 = px0 + float(p.bbox.width), py1 = py0 + float(p.bbox.height);
            bool touches = false;
            for (size_t k = 0; k < boxes.size(); ++k) {
                const auto &b = boxes[k];
                const float bw = float(b.right - b.left + 1), bh = float(b.bottom - b.top + 1);
                const float m = 0.1f * std::max(bw, bh) + 1.0f;
                if (px1 > b.left - 2 * m && px0 < b.right + 1 + 2 * m && py1 > b.top - 2 * m && py0 < b.bottom + 1 + 2 * m)
                    touches = true;
                const bool inside = px0 >= b.left - m && py0 >= b.top - m && px1 <= b.right + 1 + m && py1 <= b.bottom + 1 + m;
                if (!inside || std::max(p.bbox.width, p.bbox.height) < 0.25f * std::max(bw, bh)) continue;
                Instance in;
                in.fd = p.fd;
                in.group = group_of(p);
                const float s = p.fd.scale;
                in.dx = (0.5f * float(b.left + b.right + 1) - p.fd.cx) / s;
                in.dy = (0.5f * float(b.top + b.bottom + 1) - p.fd.cy) / s;
                in.w = bw / s;
                in.h = bh / s;
                in.cls = b.class_id;
                in.sign = sign_ids[k];
                in.area = float(p.bbox.width) * float(p.bbox.height);
                inst.push_back(in);
            }
            if (!touches) {
                background[group_of(p)].push_back(p.fd);
            }
        }
    }
    {
        std::set<int> any;
        for (const auto &in : inst) any.insert(in.sign);
        std::fprintf(stderr, "sbr_train: signs with at least one part instance: %zu of %d\n", any.size(), nsigns);
    }
    size_t nbg = 0;
    for (const auto &g : background) nbg += g.size();
    std::fprintf(stderr, "sbr_train: %zu images, %d signs, %zu part instances, %zu background parts (%.1f s)\n",
                 files.size(), nsigns, inst.size(), nbg,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());

    // 3. neighbours (different signs, same group, matching, consistent geometry)
    sbr_fft_t fftp;
    sbr_fft_init(&fftp, cfg.match_p);
    sbr_fd_match_config_t mc;
    sbr_fd_match_config_default(&mc);
    mc.mode = SBR_FD_ROTATION_COVARIANT;
    mc.max_rotation = cfg.max_rotation;
    std::vector<std::vector<int>> by_group(SBR_MODEL_GROUPS);
    for (size_t i = 0; i < inst.size(); ++i) by_group[inst[i].group].push_back(int(i));
    std::vector<std::vector<int>> nb(inst.size());
    {
        std::vector<sbr_complex_t> work(SBR_FD_TABLE_WORK_LEN(cfg.match_p));
        std::vector<sbr_fd_t> table;
        std::vector<sbr_fd_match_t> res;
        for (const auto &g : by_group) {
            table.clear();
            for (int j : g) table.push_back(inst[j].fd);
            res.resize(table.size());
            for (int i : g) {
                uint32_t best = 0;
                if (table.empty() ||
                    sbr_fd_match_table(&fftp, &mc, &inst[i].fd, table.data(), uint32_t(table.size()), work.data(),
                                       uint32_t(work.size()), res.data(), &best) != SBR_OK)
                    continue;
                for (size_t k = 0; k < g.size(); ++k) {
                    const int j = g[k];
                    if (inst[j].sign != inst[i].sign && res[k].error <= vote_error &&
                        consistent(inst[i], inst[j], centre_tol, size_f))
                        nb[i].push_back(j);
                }
            }
        }
    }

    // greedy stable parts
    struct Proto {
        int seed;
        std::vector<int> members;
        std::set<int> signs;
    };
    std::vector<Proto> protos;
    std::vector<char> taken(inst.size(), 0);
    auto sign_count = [&](int i) {
        std::set<int> s{inst[i].sign};
        for (int j : nb[i]) if (!taken[j]) s.insert(inst[j].sign);
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
        taken[best] = 1;
        for (int j : nb[best]) if (!taken[j]) { taken[j] = 1; p.members.push_back(j); }
        protos.push_back(p);
    }
    // classes without a prototype: their signs' largest parts
    std::set<int> covered;
    for (const auto &p : protos)
        for (int j : p.members) covered.insert(inst[j].cls);
    for (const auto &sc : signs_per_class) {
        if (covered.count(sc.first)) continue;
        std::map<int, std::vector<int>> per_sign;
        for (size_t i = 0; i < inst.size(); ++i) if (inst[i].cls == sc.first) per_sign[inst[i].sign].push_back(int(i));
        int added = 0;
        for (auto &ps : per_sign) {
            auto &v = ps.second;
            std::sort(v.begin(), v.end(), [&](int a, int b) { return inst[a].area > inst[b].area; });
            for (size_t k = 0; k < v.size() && k < 2 && added < 4; ++k, ++added) {
                Proto p;
                p.seed = v[k];
                p.members = {v[k]};
                p.signs = {inst[v[k]].sign};
                protos.push_back(p);
            }
        }
    }

    // 4. classes, geometry, weights
    struct Built {
        sbr_fd_t fd;
        sbr_model_proto_t p;
        float rank;
    };
    std::vector<Built> built;
    {
        std::vector<sbr_complex_t> work(SBR_FD_TABLE_WORK_LEN(cfg.match_p));
        std::vector<sbr_fd_match_t> res;
        for (const auto &pr : protos) {
            const Instance &s = inst[pr.seed];
            Built b{};
            b.fd = s.fd;
            double dx = 0, dy = 0, w = 0, h = 0;
            std::map<int, std::set<int>> cls_signs;
            for (int j : pr.members) {
                dx += inst[j].dx; dy += inst[j].dy; w += inst[j].w; h += inst[j].h;
                cls_signs[inst[j].cls].insert(inst[j].sign);
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
            // background matches that would vote for a sign of plausible size
            size_t neg = 0;
            const auto &bg = background[s.group];
            uint32_t best = 0;
            res.resize(bg.size());
            // The error is symmetric (swapping query and prototype conjugates r and mirrors
            // the shift; max Re r and |rotation| stay), so the prototype is the query and the
            // background group the table: one four-lane pass instead of a call per part.
            if (!bg.empty() && sbr_fd_match_table(&fftp, &mc, &b.fd, bg.data(), uint32_t(bg.size()), work.data(),
                                                  uint32_t(work.size()), res.data(), &best) == SBR_OK) {
                for (size_t k = 0; k < bg.size(); ++k) {
                    const float size = std::max(b.p.w, b.p.h) * bg[k].scale;
                    if (res[k].error <= vote_error && size >= cfg.min_size && size <= cfg.max_size) ++neg;
                }
            }
            const float pos = float(pr.signs.size());
            b.p.weight = std::max(1e-4f, pos / (pos + float(neg)));
            b.rank = pos * b.p.weight;
            built.push_back(b);
        }
    }
    const size_t before_prune = built.size();
    built.erase(std::remove_if(built.begin(), built.end(), [&](const Built &b) { return b.p.weight < min_weight; }),
                built.end());
    std::fprintf(stderr, "sbr_train: %zu of %zu prototypes kept with weight >= %g\n", built.size(), before_prune,
                 double(min_weight));
    std::sort(built.begin(), built.end(), [](const Built &a, const Built &b) { return a.rank > b.rank; });
    if (built.size() > max_protos) built.resize(max_protos);
    std::stable_sort(built.begin(), built.end(), [](const Built &a, const Built &b) {
        return a.p.map * 2 + a.p.polarity < b.p.map * 2 + b.p.polarity;
    });

    // 5. the model: groups and cascades
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
    sbr_status_t st = sbr_model_check(&m.view);
    if (st != SBR_OK) {
        std::fprintf(stderr, "sbr_train: the built model fails its check: %s\n", sbr_status_str(st));
        return 1;
    }
    int shared = 0;
    for (const auto &p : m.protos) shared += p.class_id[1] != SBR_MODEL_NO_CLASS;
    std::fprintf(stderr, "sbr_train: %zu prototypes (%d shared by several classes), cascade %zu entries (%.1f s)\n",
                 m.protos.size(), shared, m.cascade.size(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());

    // 6. operating point on the training images
    if (calibrate) {
        sbr_recog_config_t rc = cfg;
        rc.min_score = 0.0f;
        struct Scored { float score; bool tp; };
        std::vector<Scored> scored;
        std::mutex mu;
        std::atomic<size_t> next{0};
        auto work = [&]() {
            std::vector<uint64_t> ws;
            std::vector<sbr_detection_t> dets(256);
            for (size_t i; (i = next++) < files.size();) {
                cv::Mat img = cv::imread(files[i], cv::IMREAD_COLOR);
                if (img.empty()) continue;
                sbr_image_t v = bgr_view(img);
                const size_t need = sbr_recog_workspace_size(&rc, v.width, v.height);
                if (ws.size() * 8 < need) ws.assign(need / 8 + 1, 0);
                uint32_t n = 0;
                if (sbr_recog_detect(&v, nullptr, &rc, &m.view, ws.data(), ws.size() * 8, dets.data(),
                                     uint32_t(dets.size()), &n, nullptr) < 0 && n == 0)
                    continue;
                const auto it = gt.find(image_number(files[i]));
                std::vector<char> used(it == gt.end() ? 0 : it->second.size(), 0);
                std::vector<Scored> local;
                for (uint32_t k = 0; k < n; ++k) {
                    const auto &d = dets[k];
                    bool tp = false;
                    if (it != gt.end()) {
                        for (size_t g = 0; g < it->second.size() && !tp; ++g) {
                            const auto &b = it->second[g];
                            if (used[g] || b.class_id != d.class_id) continue;
                            const float ix = std::min<float>(b.right + 1, d.box.x + d.box.width) - std::max<float>(b.left, d.box.x);
                            const float iy = std::min<float>(b.bottom + 1, d.box.y + d.box.height) - std::max<float>(b.top, d.box.y);
                            if (ix <= 0 || iy <= 0) continue;
                            const float inter = ix * iy;
                            const float uni = float(b.right - b.left + 1) * float(b.bottom - b.top + 1) +
                                              float(d.box.width) * float(d.box.height) - inter;
                            if (inter / uni >= 0.5f) { used[g] = 1; tp = true; }
                        }
                    }
                    local.push_back({d.score, tp});
                }
                std::lock_guard<std::mutex> lk(mu);
                scored.insert(scored.end(), local.begin(), local.end());
            }
        };
        const unsigned nt = std::max(1u, std::min(4u, std::thread::hardware_concurrency()));
        std::vector<std::thread> th;
        for (unsigned t = 0; t < nt; ++t) th.emplace_back(work);
        for (auto &t : th) t.join();
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
                     best_t, best_f1, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }

    char head[512];
    std::snprintf(head, sizeof head,
                  "Prototype library for sbr's recogniser. GENERATED by sbr_train - do not edit.\n"
                  "Regenerate: ./sbr.sh train   (runs sbr_train --range %s --vote-error %g --min-support %d\n"
                  "            --max-protos %zu --out-c lib/models/sbr_model_gtsdb.c on GTSDB)\n"
                  "Training: GTSDB images %s, %d signs, %zu part instances, %zu background parts.\n"
                  "Library: %zu prototypes, %zu cascade entries, operating point score >= %.4f.",
                  range.str().c_str(), double(vote_error), min_support, max_protos, range.str(true).c_str(), nsigns, inst.size(), nbg,
                  m.protos.size(), m.cascade.size(), double(m.view.score_threshold));
    if (!out_c.empty() && !report_write("sbr_train", out_c, write_model_c(m, out_c, head))) return 1;
    if (!out_model.empty() && !report_write("sbr_train", out_model, save_model(m, out_model))) return 1;
    std::printf("prototypes=%zu cascade=%zu score_threshold=%.4f\n", m.protos.size(), m.cascade.size(),
                double(m.view.score_threshold));
    return 0;
}
