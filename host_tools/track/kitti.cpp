// SPDX-License-Identifier: MIT
#include "kitti.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <utility>

namespace sbr_track_host {

std::vector<std::string> split_list(const std::string &s, char c)
{
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, c)) {
        if (!item.empty()) out.push_back(item);
    }
    return out;
}

std::vector<std::string> parse_seqs(const std::string &s)
{
    std::vector<std::string> out;
    for (const auto &part : split_list(s, ',')) {
        const auto dash = part.find('-');
        if (dash == std::string::npos) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "%04d", std::atoi(part.c_str()));
            out.emplace_back(buf);
        } else {
            const int a = std::atoi(part.substr(0, dash).c_str());
            const int b = std::atoi(part.substr(dash + 1).c_str());
            for (int i = a; i <= b; ++i) {
                char buf[8];
                std::snprintf(buf, sizeof buf, "%04d", i);
                out.emplace_back(buf);
            }
        }
    }
    return out;
}

bool load_seq(const std::string &dir, const std::string &name, const std::set<std::string> &classes,
              Seq &seq)
{
    std::ifstream in(dir + "/" + name + ".txt");
    if (!in) return false;
    seq.name = name;
    std::string line;
    std::vector<std::pair<int, Obj>> all;
    int maxf = -1;
    while (std::getline(in, line)) {
        std::istringstream ls(line);
        int frame, id, trunc, occ;
        std::string type;
        double alpha, l, t, r, b;
        if (!(ls >> frame >> id >> type >> trunc >> occ >> alpha >> l >> t >> r >> b)) continue;
        maxf = std::max(maxf, frame);
        if (!classes.count(type)) continue;
        all.push_back({frame, Obj{id, type, 0.5 * (l + r), 0.5 * (t + b), r - l, b - t}});
    }
    // frame count: the official sequence map when it is beside the labels, else the labels
    int frames = maxf + 1;
    std::ifstream map(dir + "/../evaluate_tracking.seqmap.training");
    std::string ms, dummy, f0, f1;
    while (map >> ms >> dummy >> f0 >> f1) {
        if (ms == name) frames = std::atoi(f1.c_str());
    }
    seq.frames = frames;
    seq.gt.assign(static_cast<size_t>(frames), {});
    for (auto &p : all) {
        if (p.first < frames) seq.gt[static_cast<size_t>(p.first)].push_back(p.second);
    }
    return true;
}

std::string load_seqs(const std::string &dir, const std::vector<std::string> &names,
                      const std::set<std::string> &classes, std::vector<Seq> &seqs)
{
    for (const auto &name : names) {
        Seq s;
        if (!load_seq(dir, name, classes, s)) return "cannot read " + dir + "/" + name + ".txt";
        seqs.push_back(std::move(s));
    }
    return seqs.empty() ? "--seqs names no sequence" : "";
}

std::vector<std::vector<Det>> corrupt(const Seq &seq, double noise, double miss, double clutter,
                                      unsigned seed)
{
    std::mt19937 rng(seed * 7919u + static_cast<unsigned>(std::atoi(seq.name.c_str())));
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    std::poisson_distribution<int> pois(clutter > 0.0 ? clutter : 1.0);
    std::vector<std::vector<Det>> out(seq.gt.size());
    for (size_t f = 0; f < seq.gt.size(); ++f) {
        for (const auto &o : seq.gt[f]) {
            if (uni(rng) < miss) continue;
            Det d{o.cx + noise * gauss(rng), o.cy + noise * gauss(rng), o.w, o.h, o.type};
            d.x = std::min(std::max(d.x, 0.0), seq.width - 0.01);
            d.y = std::min(std::max(d.y, 0.0), seq.height - 0.01);
            out[f].push_back(d);
        }
        const int nc = clutter > 0.0 ? pois(rng) : 0;
        for (int i = 0; i < nc; ++i) {
            Det d{uni(rng) * (seq.width - 0.01), uni(rng) * (seq.height - 0.01), 60.0, 45.0, "Car"};
            out[f].push_back(d);
        }
        std::shuffle(out[f].begin(), out[f].end(), rng);
    }
    return out;
}

Seq synthetic_seq(unsigned n, int frames, unsigned seed)
{
    Seq s;
    s.name = "synthetic";
    s.frames = frames;
    s.gt.assign(static_cast<size_t>(frames), {});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    const unsigned cols = 8, rows = (n + cols - 1) / cols;
    const double cw = s.width / cols, ch = s.height / rows;
    for (unsigned i = 0; i < n; ++i) {
        const double x0 = (i % cols + 0.5) * cw, y0 = (i / cols + 0.5) * ch;
        const double vx = u(rng), vy = u(rng) * ch / cw;
        for (int f = 0; f < frames; ++f) {
            // a triangle wave within +-0.3 of the cell around its centre
            auto tri = [](double t, double a) { const double p = std::fmod(std::fabs(t), 4 * a); return p < 2 * a ? p - a : 3 * a - p; };
            s.gt[static_cast<size_t>(f)].push_back(
                Obj{static_cast<int>(i), "Car", x0 + tri(vx * f + 0.3 * cw, 0.3 * cw), y0 + tri(vy * f + 0.3 * ch, 0.3 * ch), 40, 30});
        }
    }
    return s;
}

void write_kitti(const std::string &dir, const std::string &seq, const std::vector<std::vector<Hyp>> &per_frame)
{
    std::ofstream out(dir + "/" + seq + ".txt");
    for (size_t f = 0; f < per_frame.size(); ++f) {
        for (const Hyp &h : per_frame[f]) {
            char buf[256];
            std::snprintf(buf, sizeof buf,
                          "%zu %u %s -1 -1 -10 %.2f %.2f %.2f %.2f -1 -1 -1 -1000 -1000 -1000 -10 1\n", f, h.id,
                          h.type.c_str(), h.x - 0.5 * h.w, h.y - 0.5 * h.h, h.x + 0.5 * h.w, h.y + 0.5 * h.h);
            out << buf;
        }
    }
}

}  // namespace sbr_track_host
