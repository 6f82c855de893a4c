// SPDX-License-Identifier: MIT
// sbr_train_picto: learns the recogniser's class stage (picto.h) from annotated GTSDB
// images and GTSRB's training crops: a classifier of candidate boxes into the 43 GTSDB
// classes and "no sign", its box regression, the colour check and the gate.
//
//   sbr_train_picto [--data DIR] [--range A-B] [--model FILE.sbrm] [--candidates FILE]
//                   [--hidden H] [--epochs E] [--jitter J] [--lr L] [--seed S] [--threshold T]
//                   [--bg-fraction F] [--dropout D] [--decay W] [--balance B] [--exposure]
//                   [--mirror | --no-mirror] [--rotate | --no-rotate]
//                   [--bg-swap off|round|triangle|all] [--bg-fill off|round|triangle|all]
//                   [--no-triangle-view] [--no-box] [--box-jitter N] [--rare N]
//                   [--rim-check C[,C] | none] [--rounds R] [--gtsrb DIR | --no-gtsrb]
//                   [--gtsrb-cap N] [--gtsrb-copies N] [--out-c FILE] [--out FILE]
//                   [--eval-range A-B] [--from-picto FILE] [--no-gate] [--gate-hidden H] [--gate-recall R]
//                   [--map-subsample I,R,B,Y] [--map-min-area I,R,B,Y]
//                   [--trainer hand|sklearn] [--python PY] [--trainer-args "..."]
//
// What each option does and how the training works: docs/usage/train.md; the
// measurements behind the defaults and the variants tried and dropped:
// docs/results/class_stage.md. The parts: picto_samples.* (the samples), picto_augment.*
// (the synthetic copies of a sign), picto_net.* (the network trainer; picto_fit.py the
// library one, --trainer sklearn), picto_checks.*
// (the colour check and the gate); this file reads the options and runs the rounds.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "cli.hpp"
#include "gtsdb.hpp"
#include "picto_checks.hpp"
#include "picto_net.hpp"
#include "picto_samples.hpp"

using namespace sbr_host;
using namespace sbr_host::picto_train;

namespace {

// -1: go on; otherwise the exit status.
int parse_options(int argc, char **argv, Options &o) {
    CLI::App app{"sbr_train_picto: learns the class stage (pictogram classifier, box regression, colour check, "
                 "gate) from the recogniser's candidates on GTSDB (docs/usage/detect.md)"};
    const std::map<std::string, BgSwap> swaps{
        {"off", BgSwap::off}, {"round", BgSwap::round}, {"triangle", BgSwap::triangle}, {"all", BgSwap::all}};
    std::string rim_list;
    auto f = [](double lo, double hi) { return finite_range(lo, hi); };
    app.add_option("--data", o.data, "GTSDB folder")->capture_default_str();
    add_range_option(app, o.range, "training images (default 0-399)");
    add_range_option(app, o.eval_range, "also evaluate the classifier on these images", "--eval-range");
    app.add_option("--candidates", o.cand_path, "candidate boxes file (default: the recogniser's)");
    app.add_option("--model", o.model_path, "part model file (default: the built-in one)");
    app.add_option("--hidden", o.hidden, "hidden units")->check(CLI::Range(0, int(SBR_PICTO_HIDDEN_MAX)))->capture_default_str();
    app.add_option("--epochs", o.epochs, "epochs per round")->check(CLI::Range(1, 100000))->capture_default_str();
    app.add_option("--jitter", o.jitter, "training copies per sign (shifts, scales)")->check(CLI::Range(0, 100000))->capture_default_str();
    app.add_option("--box-jitter", o.box_jitter, "extra copies for the box regression")->check(CLI::Range(0, 100000))->capture_default_str();
    app.add_option("--threshold", o.threshold, "operating point stored with the model")->check(f(0.0, 1.0))->capture_default_str();
    app.add_option("--lr", o.lr, "learning rate")->check(f(1e-9, 10.0))->capture_default_str();
    app.add_option("--bg-fraction", o.bg_fraction, "share of background candidates kept")->check(f(1e-6, 1.0))->capture_default_str();
    app.add_option("--dropout", o.dropout, "dropout of the hidden units")->check(f(0.0, 0.9))->capture_default_str();
    app.add_option("--decay", o.decay, "weight decay")->check(f(0.0, 0.999999))->capture_default_str();
    app.add_flag("--no-box", [&o](int64_t) { o.box = false; }, "no box regression");
    app.add_flag("--exposure", o.exposure, "exposure changes in the synthetic copies");
    app.add_flag("--degrade", o.degrade,
                 "a fifth of the synthetic copies under a camera's degradations: motion blur, defocus, sensor noise, "
                 "JPEG compression or haze (picto_augment.cpp, degrade())");
    app.add_option("--bg-swap", o.bg_swap, "synthetic copies on other backgrounds: off, round, triangle, all")
        ->transform(CLI::CheckedTransformer(swaps));
    app.add_option("--bg-fill", o.bg_fill, "background fill of the copies: off, round, triangle, all")
        ->transform(CLI::CheckedTransformer(swaps));
    app.add_flag("--mirror,!--no-mirror", o.mirror, "mirrored copies of the mirror-symmetric classes (default on)");
    app.add_flag("--rotate,!--no-rotate", o.rotate, "small rotations in the copies (default on)");
    app.add_flag("--triangle-view,!--no-triangle-view", o.tview, "train on triangle views too (default on)");
    app.add_option("--balance", o.balance, "class-balanced sampling exponent")->check(f(0.0, 2.0))->capture_default_str();
    app.add_option("--rare", o.rare, "extra copies of classes with few signs")->check(CLI::Range(0, 100000))->capture_default_str();
    app.add_option("--from-picto", o.from_picto, "no training: add the colour check and the gate (unless --no-gate) to this class stage");
    app.add_flag("--gate,!--no-gate", o.gate, "learn the class stage's gate (default on)");
    app.add_option("--gate-recall", o.gate_recall, "share of positive candidates the gate passes")
        ->check(f(1e-6, 1.0))
        ->capture_default_str();
    app.add_option("--gate-hidden", o.gate_hidden, "the gate's rectified units (0: linear)")
        ->check(CLI::Range(0, int(SBR_PICTO_GATE_HIDDEN_MAX)))
        ->capture_default_str();
    app.add_option("--rim-check", rim_list, "classes that get a colour check, e.g. 13, or none (default 13)");
    app.add_option("--rounds", o.rounds, "training rounds")->check(CLI::Range(1, 1000))->capture_default_str();
    app.add_option("--seed", o.seed, "random seed")->capture_default_str();
    app.add_option("--out-c", o.out_c, "write the class stage as a C table (lib/models/sbr_picto_gtsdb.c)");
    app.add_option("--out", o.out_file, "write the class stage as a model file (.sbrp)");
    CLI::Option *gtsrb_opt = app.add_option("--gtsrb", o.gtsrb,
                                            "GTSRB folder: its training tracks' crops are sign samples too (the "
                                            "validation tracks, gtsrb.hpp, never)")
                                 ->capture_default_str();
    bool no_gtsrb = false;
    app.add_flag("--no-gtsrb", no_gtsrb, "train on GTSDB only");
    app.add_option("--gtsrb-cap", o.gtsrb_cap, "GTSRB crops of a class at most")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    app.add_option("--gtsrb-synth", o.gtsrb_synth,
                   "synthetic copies of each GTSRB crop (perspective, exposure, blur, smaller)")
        ->check(CLI::Range(0, 1000))
        ->capture_default_str();
    app.add_option("--gtsrb-copies", o.gtsrb_copies, "jittered copies of each GTSRB crop")
        ->check(CLI::Range(0, 1000))
        ->capture_default_str();
    app.add_option("--trainer", o.trainer,
                   "the network's trainer: hand (SGD with dropout, picto_net.cpp) or sklearn (picto_fit.py)")
        ->check(CLI::IsMember({"hand", "sklearn"}))
        ->capture_default_str();
    app.add_option("--python", o.python, "Python with scikit-learn for --trainer sklearn")->capture_default_str();
    app.add_option("--trainer-args", o.trainer_args, "more options for picto_fit.py (--trainer sklearn), e.g. \"--alpha 0.01\"");
    add_front_end_options(app, o.front_end);
    add_look_options(app, o.looks, true);
    const int parsed = parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    o.gtsrb_given = gtsrb_opt->count() > 0;
    if (no_gtsrb) {
        if (o.gtsrb_given) {
            std::fprintf(stderr, "sbr_train_picto: --gtsrb and --no-gtsrb contradict each other\n");
            return 2;
        }
        o.gtsrb.clear();
    }
    if (!rim_list.empty()) {
        std::stringstream ss(rim_list == "none" ? "" : rim_list);
        o.rim_classes.clear();
        for (std::string c; std::getline(ss, c, ',');) {
            const int k = std::atoi(c.c_str());
            if (c.empty() || c.find_first_not_of("0123456789") != std::string::npos || k >= int(kGtsdbClasses) ||
                class_outline_of(k) == uint8_t(SBR_PICTO_RIM_NONE)) {
                std::fprintf(stderr, "--rim-check wants class ids of discs or triangles, e.g. 13, or none\n");
                return 2;
            }
            o.rim_classes.push_back(k);
        }
    }
    if (o.box_jitter > 0 && !o.box) {
        std::fprintf(stderr, "sbr_train_picto: --box-jitter trains the box regression, which --no-box leaves out\n");
        return 2;
    }
    return -1;
}

// Train the network on the samples; fold the standardisation into the layer that reads
// the features and the target units into the box rows. False when the weights fail the
// core's check.
bool fit(const Options &o, const std::vector<Sample> &samples, const Counts &n, const Standard &st, Picto &out,
         std::chrono::steady_clock::time_point t0) {
    const std::vector<float> sw = sample_weights(samples, n, o.balance);
    Net net;
    net.h = o.hidden;
    if (o.trainer == "sklearn") {
        LibraryFit lf;
        lf.python = o.python;
        lf.script = SBR_PICTO_FIT_SCRIPT;
        lf.args = o.trainer_args;
        lf.hidden = o.hidden;
        lf.epochs = o.epochs;
        lf.seed = o.seed;
        lf.bg_fraction = o.bg_fraction;
        if (!train_library(net, samples, sw, lf)) return false;
    } else {
        train(net, samples, sw, o.epochs, o.seed, o.lr, o.bg_fraction, o.dropout, o.decay);
    }
    std::fprintf(stderr, "sbr_train_picto: trained (%.1f s)\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    out.hidden = uint32_t(o.hidden);
    out.classes = kGtsdbClasses;
    out.threshold = o.threshold;
    {
        // the looks the recogniser uses with this class stage: the table's defaults unless given
        sbr_picto_model_t v{};
        v.looks = out.looks;
        apply_looks(o.looks, v);
        out.looks = v.looks;
    }
    auto fold = [&](std::vector<float> &w) {
        for (size_t r = 0; r < w.size() / (kF + 1); ++r) {
            float *row = &w[r * (kF + 1)];
            float bias = row[kF];
            for (int k = 0; k < kF; ++k) {
                row[k] /= st.sd[k];
                bias -= row[k] * st.mean[k];
            }
            row[kF] = bias;
        }
    };
    if (o.hidden > 0) {
        fold(net.w1);
    } else {
        fold(net.w2);
        fold(net.w3);
    }
    for (auto &x : net.w3) x *= kTargetScale;
    out.w1 = net.w1;
    out.w2 = net.w2;
    out.w3.clear();
    if (o.box) out.w3 = net.w3;
    out.bind();
    return sbr_picto_check(&out.view) == SBR_OK;
}

// The generated table's opening comment: the command that regenerates it and what it
// learned from.
std::string c_header(const Options &o, const Counts &n) {
    char bal[96] = "";
    if (o.balance > 0.0f) std::snprintf(bal, sizeof bal, " --balance %g", double(o.balance));
    if (!o.rim_classes.empty()) {
        std::string r = " --rim-check ";
        for (size_t i = 0; i < o.rim_classes.size(); ++i) r += (i ? "," : "") + std::to_string(o.rim_classes[i]);
        std::snprintf(bal + std::strlen(bal), sizeof bal - std::strlen(bal), "%s", r.c_str());
    }
    if (o.rare > 0) std::snprintf(bal + std::strlen(bal), sizeof bal - std::strlen(bal), " --rare %d", o.rare);
    auto mode_name = [](BgSwap m) {
        return m == BgSwap::all ? "all" : m == BgSwap::round ? "round" : m == BgSwap::triangle ? "triangle" : "off";
    };
    std::string swap_flag = std::string(" --bg-swap ") + mode_name(o.bg_swap);
    if (o.bg_fill != BgSwap::off) swap_flag += std::string(" --bg-fill ") + mode_name(o.bg_fill);
    if (!o.tview) swap_flag += " --no-triangle-view";
    if (o.trainer != "hand")
        swap_flag += " --trainer " + o.trainer + (o.trainer_args.empty() ? "" : " --trainer-args \"" + o.trainer_args + "\"");
    if (!o.gtsrb.empty())
        swap_flag += " --gtsrb GTSRB --gtsrb-cap " + std::to_string(o.gtsrb_cap) + " --gtsrb-copies " +
                     std::to_string(o.gtsrb_copies) +
                     (o.gtsrb_synth > 0 ? " --gtsrb-synth " + std::to_string(o.gtsrb_synth) : std::string());
    else
        swap_flag += " --no-gtsrb";
    {
        char thr[48];
        std::snprintf(thr, sizeof thr, " --threshold %g", double(o.threshold));
        swap_flag += thr;
    }
    char head[896];
    std::snprintf(head, sizeof head,
                  "Class stage (pictogram classifier) of sbr's recogniser. GENERATED by sbr_train_picto - do not edit.\n"
                  "Regenerate: ./sbr.sh train   (runs sbr_train_picto --range %s --hidden %d --epochs %d --jitter %d\n"
                  "            --bg-fraction %g --dropout %g --decay %g%s%s%s%s%s --rounds %d --seed %u\n"
                  "            --out-c lib/models/sbr_picto_gtsdb.c on GTSDB)\n"
                  "Training: GTSDB images %s%s, %zu sign samples, %zu background samples,\n"
                  "%zu boxes for the box regression only.",
                  o.range.str().c_str(), o.hidden, o.epochs, o.jitter, double(o.bg_fraction), double(o.dropout),
                  double(o.decay), o.box ? "" : " --no-box", o.exposure ? (o.degrade ? " --exposure --degrade" : " --exposure") : (o.degrade ? " --degrade" : ""), swap_flag.c_str(),
                  o.mirror ? (o.rotate ? "" : " --no-rotate") : (o.rotate ? " --no-mirror" : " --no-mirror --no-rotate"),
                  bal, o.rounds, o.seed, o.range.str(true).c_str(),
                  o.gtsrb.empty() ? "" : " and GTSRB's training tracks (gtsrb.hpp)", n.fg, n.bg, n.reg);
    return head;
}

// --eval-range: a diagnostic on other images (normally the development split), with the
// core's classifier: the class of every annotated box, and the most frequent confusions.
void evaluate(const Options &o, const std::string &dir, const std::map<int, std::vector<GtBox>> &gt,
              const Picto &out) {
    int n_gt = 0, n_ok = 0;
    std::map<std::pair<int, int>, int> conf;
    alignas(8) static float cws[SBR_PICTO_WORKSPACE_SIZE / sizeof(float) + 1];
    std::vector<float> f, p(kK);
    for (const auto &file : list_images(dir, o.eval_range)) {
        const int num = image_number(file);
        if (!gt.count(num)) continue;
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

// --from-picto: no training, the colour check of --rim-check and the gate (unless --no-gate)
// learned on these images and added to a class stage trained before.
int add_to_picto(const Options &o, const std::vector<std::string> &files, const std::map<int, std::vector<GtBox>> &gt,
                 const sbr_model_t &pm) {
    Picto out;
    const std::string e = load_picto(o.from_picto, out);
    if (!e.empty()) { std::fprintf(stderr, "sbr_train_picto: %s\n", e.c_str()); return 1; }
    if ((o.rim_classes.empty() && !o.gate) || o.out_file.empty()) {
        std::fprintf(stderr, "sbr_train_picto: --from-picto needs --rim-check or the gate, and --out\n");
        return 2;
    }
    if (!o.rim_classes.empty() && !learn_rim_floors(files, gt, o.rim_classes, out)) return 1;
    if (o.gate && !learn_gate(files, gt, pm, out, o.gate_recall, o.gate_hidden, o.seed)) return 1;
    if (!o.out_c.empty()) {
        std::string rim, opts = " --rim-check none", gate = " --no-gate";
        for (size_t i = 0; i < o.rim_classes.size(); ++i) rim += (i ? "," : "") + std::to_string(o.rim_classes[i]);
        if (!rim.empty()) opts = " --rim-check " + rim;
        if (o.gate) {
            char g[64];
            std::snprintf(g, sizeof g, " --gate-hidden %d --gate-recall %g", o.gate_hidden, double(o.gate_recall));
            gate = g;
        }
        const std::string head =
            "Class stage (pictogram classifier) of sbr's recogniser. GENERATED by sbr_train_picto - do not edit.\n"
            "The classifier of " + std::filesystem::path(o.from_picto).filename().string() +
            " (learned by ./sbr.sh train, docs/usage/train.md), with the colour check and\n"
            "the gate learned on GTSDB images " + o.range.str(true) + ": sbr_train_picto --from-picto FILE\n"
            "--range " + o.range.str() + " --seed " + std::to_string(o.seed) + opts + gate + " --out-c FILE.";
        if (!report_write("sbr_train_picto", o.out_c, write_picto_c(out, o.out_c, head))) return 1;
    }
    return report_write("sbr_train_picto", o.out_file, save_picto(out, o.out_file)) ? 0 : 1;
}

// The rounds: train on the first round's samples; each later round adds the recogniser's
// detections with the class stage so far (hard samples) and trains again.
bool train_rounds(const Options &o, const SampleCollector &sc, size_t images, std::vector<Sample> &samples,
                  Counts &n, Picto &out, std::chrono::steady_clock::time_point t0) {
    auto secs = [&]() { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    const Standard st = standardise(samples);
    for (int round = 1; round <= o.rounds; ++round) {
        if (round > 1) {
            std::vector<Sample> mined = sc.collect(&out.view);
            std::fprintf(stderr, "sbr_train_picto: round %d: %zu detections of round %d added\n", round, mined.size(),
                         round - 1);
            for (auto &x : mined) {
                st.apply(x);
                x.hard = true;
            }
            for (auto &x : samples) mined.push_back(std::move(x));
            samples.swap(mined);
            sort_samples(samples);
            n = count_samples(samples, images, secs());
        }
        if (!fit(o, samples, n, st, out, t0)) {
            std::fprintf(stderr, "sbr_train_picto: trained weights fail the check\n");
            return false;
        }
    }
    return true;
}

}  // namespace

int main(int argc, char **argv) {
    Options o;
    const int parsed = parse_options(argc, argv, o);
    if (parsed >= 0) return parsed;
    const auto t0 = std::chrono::steady_clock::now();
    auto secs = [&]() { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    const std::string dir = gtsdb_image_dir(o.data);
    const auto gt = read_gt(dir + "/gt.txt");
    if (gt.empty()) { std::fprintf(stderr, "sbr_train_picto: no ground truth in %s\n", dir.c_str()); return 77; }
    Model part_model;
    sbr_model_t builtin{};
    const sbr_model_t *pm = &builtin;
    if (!o.model_path.empty()) {
        const std::string e = load_model(o.model_path, part_model);
        if (!e.empty()) { std::fprintf(stderr, "sbr_train_picto: %s\n", e.c_str()); return 1; }
        pm = &part_model.view;
    } else {
        sbr_model_gtsdb(&builtin);
    }
    const std::vector<std::string> files = list_images(dir, o.range);
    if (!o.from_picto.empty()) return add_to_picto(o, files, gt, *pm);

    SampleCollector sc(o, files, gt, *pm);
    if (!o.gtsrb.empty() && !o.gtsrb_given && !std::filesystem::is_directory(o.gtsrb)) {
        std::fprintf(stderr, "sbr_train_picto: note: no GTSRB in %s: training on GTSDB only (--gtsrb DIR, or --no-gtsrb)\n",
                     o.gtsrb.c_str());
        o.gtsrb.clear();
    }
    if (!o.gtsrb.empty() && !sc.add_gtsrb(o.gtsrb)) return 2;
    std::vector<Sample> samples = sc.collect(nullptr);
    Counts n = count_samples(samples, files.size(), secs());
    if (n.fg == 0 || n.bg == 0) { std::fprintf(stderr, "sbr_train_picto: nothing to learn from\n"); return 1; }
    Picto out;
    if (!train_rounds(o, sc, files.size(), samples, n, out, t0)) return 1;
    if (!o.rim_classes.empty() && !learn_rim_floors(files, gt, o.rim_classes, out)) return 1;
    std::string head = c_header(o, n);
    if (o.gate) {
        if (!learn_gate(files, gt, *pm, out, o.gate_recall, o.gate_hidden, o.seed)) return 1;
        char g[128];
        std::snprintf(g, sizeof g, "\nGate (--gate-hidden %d --gate-recall %g): threshold %.4f.", o.gate_hidden,
                      double(o.gate_recall), double(out.gate_threshold));
        head += g;
    }
    if (!o.out_c.empty() && !report_write("sbr_train_picto", o.out_c, write_picto_c(out, o.out_c, head))) return 1;
    if (!o.out_file.empty() && !report_write("sbr_train_picto", o.out_file, save_picto(out, o.out_file))) return 1;
    if (!o.eval_range.empty()) evaluate(o, dir, gt, out);
    return 0;
}
