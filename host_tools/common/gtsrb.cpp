// SPDX-License-Identifier: MIT
// GTSRB crops: the list, the validation split of their tracks, the class stage's accuracy.
#include "gtsrb.hpp"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>

#include "classes.hpp"
#include "gtsdb.hpp"
#include "parallel.hpp"

namespace fs = std::filesystem;

namespace sbr_host {

namespace {

// "a;b;c" -> fields; false unless exactly n of them.
bool split_fields(const std::string &line, size_t n, std::vector<std::string> &f) {
    f.clear();
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ';');) f.push_back(x);
    return f.size() == n;
}

bool to_int(const std::string &s, int &v) {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return false;
    v = std::atoi(s.c_str());
    return true;
}

// One CSV line: "TTTTT_IIIII.ppm;Width;Height;X1;Y1;X2;Y2;ClassId".
bool parse_crop(const std::string &line, const fs::path &folder, GtsrbCrop &c) {
    std::vector<std::string> f;
    int v[7];
    if (!split_fields(line, 8, f) || f[0].size() < 7 || f[0][5] != '_') return false;
    for (int k = 0; k < 7; ++k)
        if (!to_int(f[size_t(k) + 1], v[k])) return false;
    const int w = v[0], h = v[1], x1 = v[2], y1 = v[3], x2 = v[4], y2 = v[5];
    if (w <= 0 || h <= 0 || x2 < x1 || y2 < y1 || x2 >= w || y2 >= h || v[6] >= int(kGtsdbClasses) ||
        !to_int(f[0].substr(0, 5), c.track))
        return false;
    // the files are resized to 35 x 35 (PROVENANCE.md); the box in the file's pixels
    constexpr double kSide = 35.0;
    c.path = (folder / f[0]).string();
    c.cls = v[6];
    c.box = {x1 * kSide / w, y1 * kSide / h, (x2 + 1) * kSide / w, (y2 + 1) * kSide / h};
    return true;
}

}  // namespace

std::vector<GtsrbCrop> read_gtsrb(const std::string &dir, std::string &err) {
    fs::path images = fs::path(dir) / "Final_Training" / "Images";
    if (!fs::is_directory(images)) images = fs::path(dir);
    std::vector<GtsrbCrop> crops;
    err.clear();
    for (int k = 0; k < int(kGtsdbClasses); ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "%05d", k);
        const fs::path folder = images / name;
        const fs::path csv = folder / (std::string("GT-") + name + ".csv");
        std::ifstream f(csv);
        if (!f) continue;
        std::string line;
        std::getline(f, line);  // the header
        for (int n = 2; std::getline(f, line); ++n) {
            if (!line.empty() && line.back() == '\r') line.pop_back();
            if (line.empty()) continue;
            GtsrbCrop c;
            if (!parse_crop(line, folder, c) || c.cls != k) {
                err = csv.string() + ":" + std::to_string(n) + ": not a GTSRB line of class " + std::to_string(k);
                return {};
            }
            crops.push_back(c);
        }
    }
    if (crops.empty()) {
        err = dir + ": no GTSRB crops (expected Final_Training/Images/000NN/GT-000NN.csv)";
        return {};
    }
    std::sort(crops.begin(), crops.end(), [](const GtsrbCrop &a, const GtsrbCrop &b) {
        return std::tie(a.cls, a.track, a.path) < std::tie(b.cls, b.track, b.path);
    });
    // the split: rank of each track within its class
    std::map<int, std::set<int>> tracks;
    for (const auto &c : crops) tracks[c.cls].insert(c.track);
    for (auto &c : crops) {
        const auto &t = tracks[c.cls];
        const long rank = std::distance(t.begin(), t.find(c.track));
        c.validation = rank % kGtsrbValidationEvery == kGtsrbValidationRank;
    }
    return crops;
}

void GtsrbScore::add(int cls, const float *prob, int k) {
    // the most probable output, "no sign" (k) included: a crop is named right only when
    // its class beats every other class and "no sign"
    const int best = int(std::max_element(prob, prob + k + 1) - prob);
    PerClass &pc = classes[cls];
    ++pc.n;
    pc.right += best == cls;
    pc.background += best == k;
    if (best != cls && best != k) ++confusions[{cls, best}];
}

std::vector<std::vector<float>> classify_gtsrb(const sbr_picto_model_t &picto, const std::vector<GtsrbCrop> &crops,
                                              const std::vector<size_t> &idx, unsigned threads) {
    const int k = int(picto.classes);
    std::vector<std::vector<float>> probs(idx.size());
    struct Worker {
        std::vector<float> ws = std::vector<float>(SBR_PICTO_WORKSPACE_SIZE / sizeof(float) + 1);
        std::vector<float> f = std::vector<float>(SBR_PICTO_FEATURES);
    };
    parallel_for<Worker>(idx.size(), threads, [&](size_t j, Worker &w) {
        const GtsrbCrop &c = crops[idx[j]];
        const cv::Mat img = cv::imread(c.path, cv::IMREAD_COLOR);
        if (img.empty()) return;
        const sbr_image_t v = bgr_view(img);
        const float box[4] = {float(c.box.x0), float(c.box.y0), float(c.box.x1), float(c.box.y1)};
        std::vector<float> p(size_t(k) + 1);
        if (sbr_picto_features(&v, box, w.f.data(), SBR_PICTO_FEATURES, w.ws.data(), w.ws.size() * sizeof(float)) !=
                SBR_OK ||
            sbr_picto_classify(&picto, w.f.data(), SBR_PICTO_FEATURES, p.data(), uint32_t(k) + 1u, w.ws.data(),
                               w.ws.size() * sizeof(float)) != SBR_OK)
            return;
        probs[j] = std::move(p);
    });
    return probs;
}

std::vector<size_t> gtsrb_selection(const std::vector<GtsrbCrop> &crops, bool want, bool all) {
    std::vector<size_t> idx;
    for (size_t i = 0; i < crops.size(); ++i)
        if (all || crops[i].validation == want) idx.push_back(i);
    return idx;
}

GtsrbScore score_gtsrb(const sbr_picto_model_t &picto, const std::vector<GtsrbCrop> &crops, bool want, bool all,
                       unsigned threads) {
    const std::vector<size_t> idx = gtsrb_selection(crops, want, all);
    const std::vector<std::vector<float>> probs = classify_gtsrb(picto, crops, idx, threads);
    GtsrbScore s;
    for (size_t j = 0; j < idx.size(); ++j) {
        if (probs[j].empty()) { ++s.unreadable; continue; }
        s.add(crops[idx[j]].cls, probs[j].data(), int(picto.classes));
    }
    return s;
}

GtsrbSummary summarise(const GtsrbScore &s) {
    GtsrbSummary m;
    for (const auto &[c, pc] : s.classes) {
        m.n += pc.n;
        m.right += pc.right;
        m.background += pc.background;
        m.sn[size_t(superclass_of(c))] += pc.n;
        m.sright[size_t(superclass_of(c))] += pc.right;
    }
    return m;
}

std::string gtsrb_score_json(const GtsrbScore &s) {
    const GtsrbSummary m = summarise(s);
    std::ostringstream o;
    o << "{\"crops\": " << m.n << ", \"right\": " << m.right << ", \"no_sign\": " << m.background
      << ", \"unreadable\": " << s.unreadable << ", \"superclasses\": {";
    for (size_t g = 0; g < 4; ++g)
        o << (g ? ", " : "") << "\"" << kSuperclassNames[g] << "\": {\"crops\": " << m.sn[g]
          << ", \"right\": " << m.sright[g] << "}";
    o << "}, \"classes\": {";
    bool first = true;
    for (const auto &[c, pc] : s.classes) {
        o << (first ? "" : ", ") << "\"" << c << "\": {\"crops\": " << pc.n << ", \"right\": " << pc.right
          << ", \"no_sign\": " << pc.background << ", \"taken_for\": {";
        first = false;
        bool f2 = true;
        for (const auto &[key, n] : s.confusions)
            if (key.first == c) {
                o << (f2 ? "" : ", ") << "\"" << key.second << "\": " << n;
                f2 = false;
            }
        o << "}}";
    }
    o << "}}\n";
    return o.str();
}

void print_gtsrb_score(std::FILE *out, const GtsrbScore &s, const std::string &title) {
    const GtsrbSummary m = summarise(s);
    auto pct = [](int a, int b) { return b ? 100.0 * a / b : 0.0; };
    std::fprintf(out, "%s\n", title.c_str());
    std::fprintf(out, "  class accuracy at the annotated box: %.2f %% (%d/%d); no sign most probable: %.2f %% (%d)\n",
                 pct(m.right, m.n), m.right, m.n, pct(m.background, m.n), m.background);
    for (size_t g = 0; g < 4; ++g)
        std::fprintf(out, "  %-12s %6.2f %% (%d/%d)\n", kSuperclassNames[g], pct(m.sright[g], m.sn[g]), m.sright[g],
                     m.sn[g]);
    if (s.unreadable) std::fprintf(out, "  unreadable or refused crops: %d (not counted)\n", s.unreadable);
    // the danger classes: each one's accuracy and what it is taken for
    std::fprintf(out, "  danger classes (true -> most probable sign class: crops):\n");
    for (const auto &[c, pc] : s.classes) {
        if (superclass_of(c) != 2) continue;
        std::string conf;
        std::vector<std::pair<int, int>> cl;
        for (const auto &[key, n] : s.confusions)
            if (key.first == c) cl.push_back({n, key.second});
        std::sort(cl.rbegin(), cl.rend());
        for (size_t i = 0; i < std::min<size_t>(4, cl.size()); ++i)
            conf += " " + std::to_string(cl[i].second) + " " + class_name(cl[i].second) + ": " +
                    std::to_string(cl[i].first) + ";";
        std::fprintf(out, "    %2d %-14s %6.2f %% (%d/%d), no sign %d;%s\n", c, class_name(c), pct(pc.right, pc.n),
                     pc.right, pc.n, pc.background, conf.c_str());
    }
    // the worst classes of the other superclasses
    std::vector<std::pair<double, int>> worst;
    for (const auto &[c, pc] : s.classes)
        if (superclass_of(c) != 2) worst.push_back({pct(pc.right, pc.n), c});
    std::sort(worst.begin(), worst.end());
    std::fprintf(out, "  lowest of the other classes:");
    for (size_t i = 0; i < std::min<size_t>(6, worst.size()); ++i)
        std::fprintf(out, " %d %s %.1f %%;", worst[i].second, class_name(worst[i].second), worst[i].first);
    std::fprintf(out, "\n");
}

}  // namespace sbr_host
