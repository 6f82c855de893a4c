// SPDX-License-Identifier: MIT
// sbr_train_picto's training samples (picto_samples.hpp) and the helpers every step shares
// (picto_train.hpp).
#include "picto_samples.hpp"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <mutex>

#include "parallel.hpp"
#include "picto_augment.hpp"
#include "recog_run.hpp"

namespace sbr_host::picto_train {

// Boxes of a detection file (sbr_detect's format), keyed by image number.
std::map<int, std::vector<Box>> read_boxes(const std::string &path) {
    std::map<int, std::vector<Box>> out;
    std::ifstream f(path);
    Detection d;
    for (std::string line; std::getline(f, line);)
        if (parse_detection_line(line, d)) out[d.image].push_back(d.box);
    return out;
}

// A deterministic order of the samples, whatever order threads collected them in.
void sort_samples(std::vector<Sample> &s) {
    std::sort(s.begin(), s.end(), [](const Sample &a, const Sample &b) {
        if (a.label != b.label) return a.label < b.label;
        return a.f < b.f;
    });
}

// Regression target of box b for the sign box g: centre shift in units of b's width and
// height, log size ratios (picto.h, sbr_picto_refine()).
void box_target(const Box &b, const Box &g, float t[4]) {
    const float bw = float(b.x1 - b.x0), bh = float(b.y1 - b.y0);
    t[0] = float(0.5 * (g.x0 + g.x1) - 0.5 * (b.x0 + b.x1)) / bw;
    t[1] = float(0.5 * (g.y0 + g.y1) - 0.5 * (b.y0 + b.y1)) / bh;
    t[2] = std::log(float(g.x1 - g.x0) / bw);
    t[3] = std::log(float(g.y1 - g.y0) / bh);
}

// Boxes of one image from the recogniser: without `picto`, its part model's candidates
// (min_parts 1, no score floor); with it, the detections of the whole recogniser with
// that class stage (boxes refined, score >= kMineScore).
constexpr float kMineScore = 0.05f;

// The boxes of sbr_recog_detect() on one image with configuration rc, best first.
std::vector<Box> recog_boxes(const sbr_image_t &v, const sbr_recog_config_t &rc, const sbr_model_t &m,
                             const sbr_picto_model_t *picto, std::vector<uint64_t> &ws) {
    std::vector<sbr_detection_t> dets(4096);
    uint32_t n = 0;
    recog_once(rc, m, picto, ws, v, nullptr, dets.data(), uint32_t(dets.size()), &n, nullptr);
    std::vector<Box> out;
    for (uint32_t i = 0; i < n; ++i)
        out.push_back(rect_pixbox(dets[i].box));
    return out;
}

std::vector<Box> recog_candidates(const sbr_image_t &v, const sbr_model_t &model, const sbr_picto_model_t *picto,
                                  bool triangle_view, const FrontEnd &front_end, std::vector<uint64_t> &ws) {
    sbr_recog_config_t rc;
    sbr_recog_config_default(&rc);
    rc.triangle_view = triangle_view ? 1u : 0u;
    // the looks of the class stage that mines (a copy; its tables are borrowed):
    // the triangle view on every candidate (the recogniser's default skips the ones its
    // first classification does not find danger-like): mining also sees the false danger
    // signs the triangle view makes of those, and the committed class stage was learned so;
    // every candidate refined once, as the committed class stage was learned (the
    // recogniser's default refines only those its first look finds sign-like)
    sbr_picto_model_t miner{};
    if (picto != nullptr) {
        miner = *picto;
        miner.looks.triangle_score = 0.0f;
        miner.looks.refine_first_score = 0.0f;
        picto = &miner;
    }
    // every map at full resolution, as the part model was learned (sbr_train): the finest
    // candidates (the recogniser's default runs the blue map at half resolution; the class
    // stage learned this way scores the same there, see docs/results/recognition.md)
    parts_at_full_resolution(rc.parts);
    training_bounds(rc);
    // the intensity and blue maps, as the committed class stage was learned (the
    // recogniser's default adds the red map's bright regions; measured with the class
    // stage learned so, docs/results/realtime.md)
    rc.parts.maps = (1u << SBR_MAP_INTENSITY) | (1u << SBR_MAP_BLUE);
    apply_front_end(front_end, rc.parts);
    rc.min_parts = 1;
    rc.min_score = picto != nullptr ? kMineScore : 0.0f;
    // the part model's candidates only, as the committed class stage was learned (the
    // recogniser's outline candidates came after it; docs/results/crossval.md)
    rc.outline_maps = 0u;
    return recog_boxes(v, rc, model, picto, ws);
}

bool features(const sbr_image_t &v, const Box &b, std::vector<float> &f, uint32_t outline) {
    alignas(8) static thread_local float ws[SBR_PICTO_WORKSPACE_SIZE / sizeof(float) + 1];
    f.assign(kF, 0.0f);
    const float box[4] = {float(b.x0), float(b.y0), float(b.x1), float(b.y1)};
    return sbr_picto_features_outline(&v, box, outline, f.data(), kF, ws, sizeof ws) == SBR_OK;
}

SampleCollector::SampleCollector(const Options &o, const std::vector<std::string> &files,
                                 const std::map<int, std::vector<GtBox>> &gt, const sbr_model_t &pm)
    : o_(o), files_(files), gt_(gt), pm_(pm) {
    if (!o.cand_path.empty()) cand_file_ = read_boxes(o.cand_path);
    // --rare N: training signs per class
    for (const auto &f : files)
        if (gt.count(image_number(f)))
            for (const auto &g : gt.at(image_number(f))) ++per_class_[g.class_id];
}

// --gtsrb: the training tracks' crops, at most --gtsrb-cap a class, evenly spread over
// the class's crops (its tracks in order)
bool SampleCollector::add_gtsrb(const std::string &dir) {
    std::string err;
    const std::vector<GtsrbCrop> all = read_gtsrb(dir, err);
    if (all.empty()) { std::fprintf(stderr, "sbr_train_picto: --gtsrb %s\n", err.c_str()); return false; }
    std::map<int, std::vector<const GtsrbCrop *>> by_class;
    for (const auto &c : all)
        if (!c.validation) by_class[c.cls].push_back(&c);
    for (const auto &[cls, v] : by_class) {
        const size_t take = std::min(v.size(), size_t(o_.gtsrb_cap));
        for (size_t i = 0; i < take; ++i) gtsrb_.push_back(*v[i * v.size() / take]);
    }
    std::fprintf(stderr, "sbr_train_picto: %zu GTSRB crops of %zu training ones (--gtsrb-cap %d)\n", gtsrb_.size(),
                 size_t(std::count_if(all.begin(), all.end(), [](const GtsrbCrop &c) { return !c.validation; })),
                 o_.gtsrb_cap);
    return true;
}

// Every image on 4 threads; the samples in a deterministic order.
std::vector<Sample> SampleCollector::collect(const sbr_picto_model_t *mine) const {
    std::vector<Sample> samples;
    std::mutex mu;
    struct Worker {
        std::vector<uint64_t> ws;
        std::mt19937 rng;
    };
    parallel_for<Worker>(files_.size(), 4u, [&](size_t i, Worker &wk) {
        std::vector<Sample> local;
        image(i, mine, wk.ws, wk.rng, local);
        std::lock_guard<std::mutex> lk(mu);
        for (auto &x : local) samples.push_back(std::move(x));
    });
    // the GTSRB crops are signs only (no scene, no candidates): the first round's
    if (mine == nullptr)
        parallel_for<Worker>(gtsrb_.size(), 4u, [&](size_t i, Worker &wk) {
            std::vector<Sample> local;
            gtsrb_crop(i, wk.rng, local);
            std::lock_guard<std::mutex> lk(mu);
            for (auto &x : local) samples.push_back(std::move(x));
        });
    sort_samples(samples);
    return samples;
}

// How many rounds of synthetic copies a class with fewer than --rare signs gets
// (ceil(N / n) - 1, at most kRareMax).
int SampleCollector::rare_rounds(int c) const {
    const int n = per_class_.count(c) ? per_class_.at(c) : 0;
    if (o_.rare <= 0 || n == 0 || n >= o_.rare) return 0;
    return std::min(kRareMax, (o_.rare + n - 1) / n - 1);
}

// The jittered, shrunk, re-exposed, re-backgrounded, turned or mirrored copies of a sign
// (make_copy()), each with its box target and every fourth also as the triangle view.
void SampleCollector::sign_copies(const Site &site, int copies, std::mt19937 &rng, std::vector<Sample> &local) const {
    std::vector<float> f;
    for (int j = 0; j <= copies; ++j) {
        const Copy c = make_copy(o_, site, j, rng);
        const sbr_image_t sv = c.seen.empty() ? *site.view : bgr_view(c.seen);
        if (!features(sv, c.qs, f)) continue;
        local.push_back({f, c.label});
        if (o_.box) {
            // the target is the same in the frame's coordinates (shift and scale
            // invariant), mirrored for a mirror image
            local.back().has_box = true;
            box_target(c.q, site.b, local.back().t);
            if (c.mirrored) local.back().t[0] = -local.back().t[0];
        }
        // --triangle-view: every fourth copy also as the triangle view
        if (o_.tview && j % 4 == 0 && features(sv, c.qs, f, kTriangle)) local.push_back({f, c.label});
    }
}

// --rare: synthetic copies of a rare class's sign, from their own random stream (the
// copies above stay as they were): the neighbourhood seen in perspective, blurred, under
// another exposure, partly occluded and often farther away (synth_copy()); for the class
// only (no box target).
void SampleCollector::rare_copies(const Site &site, int num, size_t g, std::vector<Sample> &local) const {
    std::mt19937 srng(o_.seed * 100003u + unsigned(num) * 977u + unsigned(g) + 11u);
    synth_copies(site, rare_rounds(site.cls) * o_.jitter, srng, local);
}

// n synthetic copies of the sign of `site` (synth_copy()) drawn from srng, for the class
// only (no box target); every fourth also as the triangle view.
void SampleCollector::synth_copies(const Site &site, int n, std::mt19937 &srng, std::vector<Sample> &local) const {
    std::vector<float> f;
    for (int j = 0; j < n; ++j) {
        Box qs;
        const cv::Mat seen = synth_copy(*site.img, site.near, site.b, *site.gts, site.mx0, site.my0, srng, qs);
        if (seen.empty()) continue;
        const sbr_image_t sv = bgr_view(seen);
        if (!features(sv, qs, f)) continue;
        local.push_back({f, site.cls});
        if (o_.tview && j % 4 == 0 && features(sv, qs, f, kTriangle)) local.push_back({f, site.cls});
    }
}

// --box-jitter: copies placed farther off (centre up to 25 % of the sign's size away,
// scale 0.74 to 1.35) for the box regression only, from their own random stream so the
// copies above stay as they were.
void SampleCollector::box_jitter_copies(const Site &site, int num, size_t g, std::vector<Sample> &local) const {
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    std::mt19937 brng;
    if (o_.box_jitter > 0) brng.seed(o_.seed * 100003u + unsigned(num) * 131u + unsigned(g) + 7u);
    const Box &b = site.b;
    const float w = site.w, h = site.h;
    std::vector<float> f;
    for (int j = 0; j < o_.box_jitter; ++j) {
        const float cx = 0.5f * float(b.x0 + b.x1) + 0.25f * w * U(brng);
        const float cy = 0.5f * float(b.y0 + b.y1) + 0.25f * h * U(brng);
        const float s = std::exp(0.3f * U(brng));
        const float hw = 0.5f * w * s * (1.0f + 0.04f * U(brng)), hh = 0.5f * h * s * (1.0f + 0.04f * U(brng));
        const Box q{cx - hw, cy - hh, cx + hw, cy + hh};
        if (!features(*site.view, q, f)) continue;
        local.push_back({f, -1});
        local.back().has_box = true;
        box_target(q, b, local.back().t);
    }
}

// The recogniser's boxes: background below IoU 0.3 with every sign; near a sign, its
// class (IoU >= 0.55) and where the sign is. --triangle-view: the triangle view of every
// other candidate and of every mined detection, with the same label.
void SampleCollector::candidates(const sbr_image_t &v, const std::vector<Box> &cands, const std::vector<Box> &gts,
                                 const std::vector<int> &cls, bool mined, std::vector<Sample> &local) const {
    std::vector<float> f;
    for (size_t ci = 0; ci < cands.size(); ++ci) {
        const Box &c = cands[ci];
        float best = 0;
        size_t bg = 0;
        for (size_t g = 0; g < gts.size(); ++g) {
            const float ov = float(box_iou(c, gts[g]));
            if (ov > best) { best = ov; bg = g; }
        }
        const bool tri = o_.tview && (mined || ci % 2 == 0);
        if (best < 0.3f) {
            if (features(v, c, f)) local.push_back({f, kBackground});
            if (tri && features(v, c, f, kTriangle)) local.push_back({f, kBackground});
        } else if ((best >= 0.55f || o_.box) && features(v, c, f)) {
            local.push_back({f, best >= 0.55f ? cls[bg] : -1});
            if (o_.box) {
                local.back().has_box = true;
                box_target(c, gts[bg], local.back().t);
            }
            if (tri && best >= 0.55f && features(v, c, f, kTriangle)) local.push_back({f, cls[bg]});
        }
    }
}

void SampleCollector::image(size_t i, const sbr_picto_model_t *mine, std::vector<uint64_t> &ws, std::mt19937 &rng,
                            std::vector<Sample> &local) const {
    const int num = image_number(files_[i]);
    rng.seed(o_.seed * 100003u + unsigned(num));
    cv::Mat img = cv::imread(files_[i], cv::IMREAD_COLOR);
    if (img.empty()) return;
    const sbr_image_t v = bgr_view(img);
    std::vector<Box> gts;
    std::vector<int> cls;
    if (gt_.count(num))
        for (const auto &g : gt_.at(num)) { gts.push_back(gt_pixbox(g)); cls.push_back(g.class_id); }
    for (size_t g = 0; g < gts.size() && mine == nullptr; ++g) {
        const Site site = make_site(img, v, gts, g, cls[g]);
        sign_copies(site, o_.jitter, rng, local);
        rare_copies(site, num, g, local);
        box_jitter_copies(site, num, g, local);
    }
    const bool from_recogniser = o_.cand_path.empty() || mine != nullptr;
    const std::vector<Box> cands = from_recogniser ? recog_candidates(v, pm_, mine, o_.tview, o_.front_end, ws)
                                                   : (cand_file_.count(num) ? cand_file_.at(num) : std::vector<Box>{});
    candidates(v, cands, gts, cls, mine != nullptr, local);
}

// --gtsrb: GTSRB crop i as a sign of its class, and --gtsrb-copies copies of it made as
// the GTSDB signs' (make_copy(): jittered, shrunk, turned, mirrored; the crop is the whole
// neighbourhood, so no background swap), from a random stream of its own.
void SampleCollector::gtsrb_crop(size_t i, std::mt19937 &rng, std::vector<Sample> &local) const {
    const GtsrbCrop &c = gtsrb_[i];
    cv::Mat img = cv::imread(c.path, cv::IMREAD_COLOR);
    if (img.empty()) return;
    const sbr_image_t v = bgr_view(img);
    const std::vector<Box> gts{c.box};
    rng.seed(o_.seed * 100003u + 7919u * unsigned(i) + 1000003u);
    const Site site = make_site(img, v, gts, 0, c.cls);
    sign_copies(site, o_.gtsrb_copies, rng, local);
    // --gtsrb-synth: synthetic copies from a stream of their own (the copies above stay
    // as they were)
    std::mt19937 srng(o_.seed * 100003u + 7919u * unsigned(i) + 2000003u);
    synth_copies(site, o_.gtsrb_synth, srng, local);
}

Counts count_samples(const std::vector<Sample> &samples, size_t images, double secs) {
    Counts c;
    for (const auto &s : samples) {
        c.bg += s.label == kBackground;
        c.reg += s.label < 0;
    }
    c.fg = samples.size() - c.bg - c.reg;
    std::fprintf(stderr,
                 "sbr_train_picto: %zu sign samples, %zu background samples, %zu boxes for the box regression only, "
                 "from %zu images (%.1f s)\n",
                 c.fg, c.bg, c.reg, images, secs);
    return c;
}

Standard standardise(std::vector<Sample> &samples) {
    Standard st;
    for (const auto &s : samples)
        for (int k = 0; k < kF; ++k) st.mean[k] += s.f[k];
    for (auto &m : st.mean) m /= float(samples.size());
    for (const auto &s : samples)
        for (int k = 0; k < kF; ++k) st.sd[k] += (s.f[k] - st.mean[k]) * (s.f[k] - st.mean[k]);
    for (auto &d : st.sd) d = std::sqrt(d / float(samples.size())) + 1e-3f;
    for (auto &s : samples) st.apply(s);
    return st;
}

// Sample weights: background weighted up to the signs; with --balance, rarer classes'
// samples by (n_c / mean)^-balance, scaled so the signs together weigh as before.
std::vector<float> sample_weights(const std::vector<Sample> &samples, const Counts &n, float balance) {
    std::vector<float> sw(samples.size(), 1.0f);
    const float wbg = float(n.fg) / float(n.bg);
    for (size_t i = 0; i < samples.size(); ++i)
        if (samples[i].label == kBackground && !samples[i].hard) sw[i] = wbg;
    if (balance <= 0.0f) return sw;
    auto sign = [](const Sample &x) { return x.label >= 0 && x.label < kBackground; };
    std::vector<double> nc(kBackground, 0.0);
    for (const auto &x : samples)
        if (sign(x)) nc[size_t(x.label)] += 1.0;
    double present = 0.0, total = 0.0, wsum = 0.0;
    for (double c : nc) { present += c > 0.0; total += c; }
    const double mean_n = total / std::max(present, 1.0);
    for (size_t i = 0; i < samples.size(); ++i)
        if (sign(samples[i])) {
            sw[i] = float(std::pow(nc[size_t(samples[i].label)] / mean_n, -double(balance)));
            wsum += sw[i];
        }
    for (size_t i = 0; i < samples.size(); ++i)
        if (sign(samples[i])) sw[i] *= float(total / wsum);
    return sw;
}

}  // namespace sbr_host::picto_train
