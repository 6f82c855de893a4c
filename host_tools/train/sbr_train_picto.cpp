// sbr_train_picto: learns the recogniser's class stage (pictogram.h) from annotated GTSDB
// images: a classifier of candidate boxes into the 43 GTSDB classes and "no sign".
//
//   sbr_train_picto [--data DIR] [--range A-B] [--model FILE.sbrm] [--candidates FILE]
//                   [--hidden H] [--epochs E] [--jitter J] [--lr L] [--seed S] [--threshold T]
//                   [--out-c FILE] [--out FILE]
//                   [--eval-range A-B]
//
// Defaults: --data ../shared/data/gtsdb, --range 0-399 (the training split; the
// development split 400-599 is never read for training), --hidden 128, --epochs 20,
// --jitter 20 (copies per annotated sign), --lr 0.01, --seed 1, --threshold 0.5 (the
// operating point stored with it: the class more probable than everything else together).
//
// Training samples:
//  - every annotated sign's box, and jittered copies of it (shifts up to 8 % of its size,
//    scale up to 8 %), labelled with its class; every other copy is taken from the
//    sign's neighbourhood shrunk 1.5-4 times (area averaging; only while the sign stays
//    >= 12 px), so each class is also seen as small, far signs look;
//  - the recogniser's candidate boxes on the training images (its part model with
//    min_parts 1 and no score floor, or the boxes of --candidates, a detection file):
//    IoU >= 0.55 with a sign -> that sign's class; IoU < 0.3 with every sign -> background;
//    in between -> not used.
// Features: sbr_picto_features() (the core's own code). Standardised, then a layer of
// rectified units (--hidden, 0 = none) and a softmax, trained by minibatch SGD with
// momentum (deterministic: fixed seed, one thread). Background samples are weighted so
// they count as much as all signs together.
//
// --eval-range: a diagnostic on other images (normally the development split): class
// accuracy on their annotated boxes and the most frequent confusions. Nothing from it
// feeds back into the trained weights. (Detection figures come from sbr_detect and
// sbr_eval.)
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "gtsdb.hpp"
#include "model_io.hpp"

extern "C" {
#include "sbr/pictogram.h"
#include "sbr/recognizer.h"
}

using namespace sbr_host;

namespace {

constexpr int kF = int(SBR_PICTO_FEATURES);
constexpr int kK = int(SBR_PICTO_OUTPUTS);

using Box = PixBox;

// Boxes of a detection file (sbr_detect's format), keyed by image number.
std::map<int, std::vector<Box>> read_boxes(const std::string &path) {
    std::map<int, std::vector<Box>> out;
    std::ifstream f(path);
    DetLine d;
    for (std::string line; std::getline(f, line);)
        if (parse_detection_line(line, d)) out[d.image].push_back(d.box());
    return out;
}

struct Sample { std::vector<float> f; int label; };

// Candidate boxes of one image from the recogniser's part model.
std::vector<Box> recog_candidates(const sbr_image_t &v, const sbr_model_t &model, std::vector<uint64_t> &ws) {
    sbr_recog_config_t rc;
    sbr_recog_config_default(&rc);
    rc.min_parts = 1;
    rc.min_score = 0.0f;
    sbr_model_t parts_only = model;
    parts_only.picto.version = 0;
    const size_t need = sbr_recog_workspace_size(v.width, v.height, &rc);
    if (ws.size() * 8 < need) ws.assign(need / 8 + 1, 0);
    std::vector<sbr_detection_t> dets(4096);
    uint32_t n = 0;
    sbr_recog_detect(&v, nullptr, &rc, &parts_only, ws.data(), ws.size() * 8, dets.data(), uint32_t(dets.size()), &n, nullptr);
    std::vector<Box> out;
    for (uint32_t i = 0; i < n; ++i)
        out.push_back(rect_pixbox(dets[i].box));
    return out;
}

bool features(const sbr_image_t &v, const Box &b, std::vector<float> &f) {
    alignas(8) static thread_local float ws[SBR_PICTO_WORKSPACE_SIZE / sizeof(float) + 1];
    f.assign(kF, 0.0f);
    const float box[4] = {float(b.x0), float(b.y0), float(b.x1), float(b.y1)};
    return sbr_picto_features(&v, box, f.data(), kF, ws, sizeof ws) == SBR_OK;
}

// The network in training form.
struct Net {
    int h = 0;
    std::vector<float> w1, w2;  // h x (F+1), K x (nin+1)
    int nin() const { return h > 0 ? h : kF; }
};

void forward(const Net &n, const float *x, std::vector<float> &a, std::vector<float> &p) {
    const float *in = x;
    if (n.h > 0) {
        a.resize(n.h);
        for (int j = 0; j < n.h; ++j) {
            const float *w = &n.w1[size_t(j) * (kF + 1)];
            float s = w[kF];
            for (int k = 0; k < kF; ++k) s += w[k] * x[k];
            a[j] = s > 0 ? s : 0;
        }
        in = a.data();
    }
    const int ni = n.nin();
    p.resize(kK);
    float mx = -1e30f;
    for (int c = 0; c < kK; ++c) {
        const float *w = &n.w2[size_t(c) * (ni + 1)];
        float s = w[ni];
        for (int k = 0; k < ni; ++k) s += w[k] * in[k];
        p[c] = s;
        mx = std::max(mx, s);
    }
    float sum = 0;
    for (int c = 0; c < kK; ++c) { p[c] = std::exp(p[c] - mx); sum += p[c]; }
    for (int c = 0; c < kK; ++c) p[c] /= sum;
}

void train(Net &n, const std::vector<Sample> &s, const std::vector<float> &sw, int epochs, unsigned seed, float lr0) {
    std::mt19937 rng(seed);
    const int ni = n.nin();
    std::normal_distribution<float> nd(0.0f, 1.0f);
    if (n.h > 0) {
        n.w1.assign(size_t(n.h) * (kF + 1), 0.0f);
        const float sc = std::sqrt(2.0f / float(kF));
        for (int j = 0; j < n.h; ++j)
            for (int k = 0; k < kF; ++k) n.w1[size_t(j) * (kF + 1) + k] = nd(rng) * sc;
    }
    n.w2.assign(size_t(kK) * (ni + 1), 0.0f);
    if (n.h > 0) {
        const float sc = std::sqrt(1.0f / float(ni));
        for (int c = 0; c < kK; ++c)
            for (int k = 0; k < ni; ++k) n.w2[size_t(c) * (ni + 1) + k] = nd(rng) * sc;
    }
    std::vector<float> v1(n.w1.size(), 0.0f), v2(n.w2.size(), 0.0f), g1(n.w1.size()), g2(n.w2.size());
    std::vector<size_t> order(s.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    const size_t batch = 64;
    const float decay = 1e-4f, mom = 0.9f;
    std::vector<float> a, p, da(std::max(1, n.h));
    for (int e = 0; e < epochs; ++e) {
        const float lr = lr0 * 0.5f * (1.0f + std::cos(3.14159265f * float(e) / float(epochs)));
        std::shuffle(order.begin(), order.end(), rng);
        double loss = 0, wsum = 0;
        for (size_t b0 = 0; b0 < order.size(); b0 += batch) {
            std::fill(g1.begin(), g1.end(), 0.0f);
            std::fill(g2.begin(), g2.end(), 0.0f);
            float bw = 0;
            for (size_t bi = b0; bi < std::min(order.size(), b0 + batch); ++bi) {
                const Sample &x = s[order[bi]];
                const float w = sw[order[bi]];
                forward(n, x.f.data(), a, p);
                loss -= w * std::log(std::max(p[x.label], 1e-12f));
                wsum += w;
                bw += w;
                const float *in = n.h > 0 ? a.data() : x.f.data();
                if (n.h > 0) std::fill(da.begin(), da.end(), 0.0f);
                for (int c = 0; c < kK; ++c) {
                    const float d = w * (p[c] - (c == x.label ? 1.0f : 0.0f));
                    if (d == 0.0f) continue;
                    float *g = &g2[size_t(c) * (ni + 1)];
                    const float *wc = &n.w2[size_t(c) * (ni + 1)];
                    for (int k = 0; k < ni; ++k) g[k] += d * in[k];
                    g[ni] += d;
                    if (n.h > 0)
                        for (int k = 0; k < ni; ++k) da[k] += d * wc[k];
                }
                if (n.h > 0) {
                    for (int j = 0; j < n.h; ++j) {
                        if (a[j] <= 0.0f) continue;
                        float *g = &g1[size_t(j) * (kF + 1)];
                        const float d = da[j];
                        for (int k = 0; k < kF; ++k) g[k] += d * x.f[k];
                        g[kF] += d;
                    }
                }
            }
            const float inv = 1.0f / std::max(bw, 1e-6f);
            for (size_t i = 0; i < n.w2.size(); ++i) {
                v2[i] = mom * v2[i] - lr * (g2[i] * inv + decay * n.w2[i]);
                n.w2[i] += v2[i];
            }
            for (size_t i = 0; i < n.w1.size(); ++i) {
                v1[i] = mom * v1[i] - lr * (g1[i] * inv + decay * n.w1[i]);
                n.w1[i] += v1[i];
            }
        }
        if (e % 5 == 4 || e + 1 == epochs)
            std::fprintf(stderr, "sbr_train_picto: epoch %d loss %.4f\n", e + 1, loss / std::max(wsum, 1e-9));
    }
}

}  // namespace

int main(int argc, char **argv) {
    std::string data = "../shared/data/gtsdb", cand_path, out_c, out_file, model_path;
    int r0 = 0, r1 = 399, e0 = -1, e1 = -1, hidden = 128, epochs = 20, jitter = 20;
    float lr = 0.01f, threshold = 0.5f;
    unsigned seed = 1;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--data") data = next();
        else if (a == "--range") {
            if (std::sscanf(next().c_str(), "%d-%d", &r0, &r1) != 2) { std::fprintf(stderr, "--range wants A-B\n"); return 2; }
        } else if (a == "--eval-range") {
            if (std::sscanf(next().c_str(), "%d-%d", &e0, &e1) != 2) { std::fprintf(stderr, "--eval-range wants A-B\n"); return 2; }
        } else if (a == "--candidates") cand_path = next();
        else if (a == "--model") model_path = next();
        else if (a == "--hidden") hidden = std::atoi(next().c_str());
        else if (a == "--epochs") epochs = std::atoi(next().c_str());
        else if (a == "--jitter") jitter = std::atoi(next().c_str());
        else if (a == "--threshold") threshold = std::strtof(next().c_str(), nullptr);
        else if (a == "--lr") lr = std::strtof(next().c_str(), nullptr);
        else if (a == "--seed") seed = unsigned(std::atoi(next().c_str()));
        else if (a == "--out-c") out_c = next();
        else if (a == "--out") out_file = next();
        else { std::fprintf(stderr, "sbr_train_picto: unknown option %s (see the file's header)\n", a.c_str()); return 2; }
    }
    if (hidden < 0 || hidden > int(SBR_PICTO_HIDDEN_MAX) || epochs < 1) {
        std::fprintf(stderr, "sbr_train_picto: --hidden 0..%u, --epochs >= 1\n", SBR_PICTO_HIDDEN_MAX);
        return 2;
    }
    const auto t0 = std::chrono::steady_clock::now();
    auto secs = [&]() { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    const std::string dir = gtsdb_image_dir(data);
    const auto gt = read_gt(dir + "/gt.txt");
    if (gt.empty()) { std::fprintf(stderr, "sbr_train_picto: no ground truth in %s\n", dir.c_str()); return 77; }
    Model part_model;
    sbr_model_t builtin{};
    const sbr_model_t *pm = &builtin;
    if (!model_path.empty()) {
        const std::string e = load_model(model_path, part_model);
        if (!e.empty()) { std::fprintf(stderr, "sbr_train_picto: %s\n", e.c_str()); return 1; }
        pm = &part_model.view;
    } else {
        sbr_model_gtsdb(&builtin);
    }
    const auto cand_file = cand_path.empty() ? std::map<int, std::vector<Box>>{} : read_boxes(cand_path);

    std::vector<std::string> files;
    for (const auto &f : list_images(dir)) {
        const int n = image_number(f);
        if (n >= r0 && n <= r1) files.push_back(f);
    }
    std::vector<Sample> samples;
    std::mutex mu;
    std::atomic<size_t> next{0};
    auto work = [&]() {
        std::vector<uint64_t> ws;
        std::mt19937 rng;
        std::uniform_real_distribution<float> U(-1.0f, 1.0f);
        for (size_t i; (i = next++) < files.size();) {
            const int num = image_number(files[i]);
            rng.seed(seed * 100003u + unsigned(num));
            cv::Mat img = cv::imread(files[i], cv::IMREAD_COLOR);
            if (img.empty()) continue;
            const sbr_image_t v = bgr_view(img);
            std::vector<Box> gts;
            std::vector<int> cls;
            if (gt.count(num))
                for (const auto &g : gt.at(num)) { gts.push_back(gt_pixbox(g)); cls.push_back(g.class_id); }
            std::vector<Sample> local;
            std::vector<float> f;
            for (size_t g = 0; g < gts.size(); ++g) {
                const Box &b = gts[g];
                const float w = float(b.x1 - b.x0), h = float(b.y1 - b.y0);
                for (int j = 0; j <= jitter; ++j) {
                    Box q = b;
                    if (j > 0) {
                        const float cx = 0.5f * float(b.x0 + b.x1) + 0.08f * w * U(rng);
                        const float cy = 0.5f * float(b.y0 + b.y1) + 0.08f * h * U(rng);
                        const float s = 1.0f + 0.08f * U(rng);
                        const float hw = 0.5f * w * s * (1.0f + 0.04f * U(rng)), hh = 0.5f * h * s * (1.0f + 0.04f * U(rng));
                        q = {cx - hw, cy - hh, cx + hw, cy + hh};
                    }
                    // every other copy as a farther sign: the neighbourhood shrunk (area
                    // averaging) so the sign is 1.5 to 4 times smaller, at least 12 px
                    const float shrink = 1.5f + 1.25f * (U(rng) + 1.0f);
                    if (j % 2 == 1 && w / shrink >= 12.0f) {
                        const int mx0 = std::max(0, int(b.x0 - w)), my0 = std::max(0, int(b.y0 - h));
                        const int mx1 = std::min(img.cols, int(b.x1 + w) + 1), my1 = std::min(img.rows, int(b.y1 + h) + 1);
                        cv::Mat small;
                        cv::resize(img(cv::Rect(mx0, my0, mx1 - mx0, my1 - my0)), small, cv::Size(), 1.0 / shrink,
                                   1.0 / shrink, cv::INTER_AREA);
                        const sbr_image_t sv = bgr_view(small);
                        const float fx = float(small.cols) / float(mx1 - mx0), fy = float(small.rows) / float(my1 - my0);
                        const Box qs = {(float(q.x0) - float(mx0)) * fx, (float(q.y0) - float(my0)) * fy,
                                        (float(q.x1) - float(mx0)) * fx, (float(q.y1) - float(my0)) * fy};
                        if (features(sv, qs, f)) local.push_back({f, cls[g]});
                    } else if (features(v, q, f)) {
                        local.push_back({f, cls[g]});
                    }
                }
            }
            const std::vector<Box> cands = cand_path.empty() ? recog_candidates(v, *pm, ws)
                                                             : (cand_file.count(num) ? cand_file.at(num) : std::vector<Box>{});
            for (const Box &c : cands) {
                float best = 0;
                int bc = -1;
                for (size_t g = 0; g < gts.size(); ++g) {
                    const float o = float(box_iou(c, gts[g]));
                    if (o > best) { best = o; bc = cls[g]; }
                }
                int label = -1;
                if (best >= 0.55f) label = bc;
                else if (best < 0.3f) label = int(SBR_PICTO_BACKGROUND);
                if (label >= 0 && features(v, c, f)) local.push_back({f, label});
            }
            std::lock_guard<std::mutex> lk(mu);
            for (auto &s : local) samples.push_back(std::move(s));
        }
    };
    {
        const unsigned nt = std::max(1u, std::min(4u, std::thread::hardware_concurrency()));
        std::vector<std::thread> th;
        for (unsigned t = 0; t < nt; ++t) th.emplace_back(work);
        for (auto &t : th) t.join();
    }
    // deterministic order whatever the threads did
    std::sort(samples.begin(), samples.end(), [](const Sample &a, const Sample &b) {
        if (a.label != b.label) return a.label < b.label;
        return a.f < b.f;
    });
    size_t nbg = 0;
    for (const auto &s : samples) nbg += s.label == int(SBR_PICTO_BACKGROUND);
    const size_t nfg = samples.size() - nbg;
    std::fprintf(stderr, "sbr_train_picto: %zu sign samples, %zu background samples from %zu images (%.1f s)\n", nfg, nbg,
                 files.size(), secs());
    if (nfg == 0 || nbg == 0) { std::fprintf(stderr, "sbr_train_picto: nothing to learn from\n"); return 1; }

    // standardise
    std::vector<float> mean(kF, 0.0f), sd(kF, 0.0f);
    for (const auto &s : samples)
        for (int k = 0; k < kF; ++k) mean[k] += s.f[k];
    for (auto &m : mean) m /= float(samples.size());
    for (const auto &s : samples)
        for (int k = 0; k < kF; ++k) sd[k] += (s.f[k] - mean[k]) * (s.f[k] - mean[k]);
    for (auto &d : sd) d = std::sqrt(d / float(samples.size())) + 1e-3f;
    for (auto &s : samples)
        for (int k = 0; k < kF; ++k) s.f[k] = (s.f[k] - mean[k]) / sd[k];
    std::vector<float> sw(samples.size(), 1.0f);
    const float wbg = float(nfg) / float(nbg);
    for (size_t i = 0; i < samples.size(); ++i)
        if (samples[i].label == int(SBR_PICTO_BACKGROUND)) sw[i] = wbg;

    Net net;
    net.h = hidden;
    train(net, samples, sw, epochs, seed, lr);
    std::fprintf(stderr, "sbr_train_picto: trained (%.1f s)\n", secs());

    // fold the standardisation into the first layer
    Picto out;
    out.hidden = uint32_t(hidden);
    out.threshold = threshold;
    {
        std::vector<float> &w = hidden > 0 ? net.w1 : net.w2;
        const int rows = hidden > 0 ? hidden : kK;
        for (int r = 0; r < rows; ++r) {
            float *row = &w[size_t(r) * (kF + 1)];
            float bias = row[kF];
            for (int k = 0; k < kF; ++k) {
                row[k] /= sd[k];
                bias -= row[k] * mean[k];
            }
            row[kF] = bias;
        }
    }
    out.w1 = net.w1;
    out.w2 = net.w2;
    out.bind();
    if (sbr_picto_check(&out.view) != SBR_OK) { std::fprintf(stderr, "sbr_train_picto: trained weights fail the check\n"); return 1; }

    char head[512];
    std::snprintf(head, sizeof head,
                  "Class stage (pictogram classifier) of sbr's recogniser. GENERATED by sbr_train_picto - do not edit.\n"
                  "Regenerate: ./sbr.sh train   (runs sbr_train_picto --range %d-%d --hidden %d --epochs %d --jitter %d\n"
                  "            --seed %u --out-c lib/models/sbr_picto_gtsdb.c on GTSDB)\n"
                  "Training: GTSDB images %05d-%05d, %zu sign samples, %zu background samples.",
                  r0, r1, hidden, epochs, jitter, seed, r0, r1, nfg, nbg);
    if (!out_c.empty()) {
        const std::string e = write_picto_c(out, out_c, head);
        if (!e.empty()) { std::fprintf(stderr, "sbr_train_picto: %s\n", e.c_str()); return 1; }
        std::fprintf(stderr, "sbr_train_picto: wrote %s\n", out_c.c_str());
    }
    if (!out_file.empty()) {
        const std::string e = save_picto(out, out_file);
        if (!e.empty()) { std::fprintf(stderr, "sbr_train_picto: %s\n", e.c_str()); return 1; }
        std::fprintf(stderr, "sbr_train_picto: wrote %s\n", out_file.c_str());
    }

    if (e0 >= 0) {
        // diagnostic on other images (normally the development split), with the core's
        // classifier: the class of every annotated box
        int n_gt = 0, n_ok = 0;
        std::map<std::pair<int, int>, int> conf;
        alignas(8) static float cws[SBR_PICTO_WORKSPACE_SIZE / sizeof(float) + 1];
        std::vector<float> f, p(kK);
        for (const auto &file : list_images(dir)) {
            const int num = image_number(file);
            if (num < e0 || num > e1 || !gt.count(num)) continue;
            cv::Mat img = cv::imread(file, cv::IMREAD_COLOR);
            if (img.empty()) continue;
            const sbr_image_t v = bgr_view(img);
            for (const auto &g : gt.at(num)) {
                ++n_gt;
                if (!features(v, gt_pixbox(g), f) ||
                    sbr_picto_classify(&out.view, f.data(), kF, p.data(), kK, cws, sizeof cws) != SBR_OK)
                    continue;
                const int best = int(std::max_element(p.begin(), p.end() - 1) - p.begin());
                n_ok += best == g.class_id;
                if (best != g.class_id) conf[{g.class_id, best}]++;
            }
        }
        std::printf("eval: class accuracy on annotated boxes %d / %d = %.4f\n", n_ok, n_gt, n_gt ? double(n_ok) / n_gt : 0.0);
        std::vector<std::pair<int, std::pair<int, int>>> cl;
        for (const auto &c : conf) cl.push_back({c.second, c.first});
        std::sort(cl.rbegin(), cl.rend());
        for (size_t i = 0; i < std::min<size_t>(8, cl.size()); ++i)
            std::printf("  true %d -> %d: %d\n", cl[i].second.first, cl[i].second.second, cl[i].first);
    }
    return 0;
}
