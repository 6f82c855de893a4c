// SPDX-License-Identifier: MIT
#include "gtsdb.hpp"

extern "C" {
#include "sbr/picto.h"
}

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <cctype>
#include <fstream>
#include <iterator>
#include <sstream>

namespace fs = std::filesystem;

namespace sbr_host {

PixBox gt_pixbox(const GtBox &g) {
    return from_inclusive(g.left, g.top, g.right, g.bottom);
}

PixBox rect_pixbox(const sbr_rect_t &r) {
    return {double(r.x), double(r.y), double(r.x) + r.width, double(r.y) + r.height};
}

std::map<int, std::vector<GtBox>> read_gt(const std::string &path) {
    std::map<int, std::vector<GtBox>> gt;
    std::ifstream f(path);
    for (std::string line; std::getline(f, line);) {
        std::replace(line.begin(), line.end(), ';', ' ');
        std::istringstream is(line);
        std::string name;
        GtBox b;
        if (is >> name >> b.left >> b.top >> b.right >> b.bottom >> b.class_id)
            gt[image_number(name)].push_back(b);
    }
    return gt;
}

std::string gtsdb_image_dir(const std::string &dir) {
    std::error_code ec;  // an unreadable folder is named by the listing, not thrown here
    if (fs::is_directory(fs::path(dir) / "FullIJCNN2013", ec)) return (fs::path(dir) / "FullIJCNN2013").string();
    return dir;
}

uint64_t fnv1a(uint64_t h, const void *p, size_t n) {
    const unsigned char *b = static_cast<const unsigned char *>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

std::vector<std::string> list_images(const std::string &dir, std::string *problem) {
    std::vector<std::string> out;
    std::error_code ec;
    fs::directory_iterator it(dir, ec), end;
    // a folder that cannot be listed, or whose entries cannot be looked at, is named with
    // the reason (not mistaken for a folder without images)
    for (; !ec && it != end; it.increment(ec)) {
        std::string ext = it->path().extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
        if (ext != ".jpg" && ext != ".jpeg" && ext != ".png" && ext != ".ppm") continue;
        std::error_code tec;
        const bool regular = fs::is_regular_file(it->path(), tec);  // follows symbolic links
        if (tec) {
            if (problem && problem->empty()) *problem = it->path().string() + ": " + tec.message();
            continue;
        }
        if (regular) out.push_back(it->path().string());
    }
    if (ec && problem && problem->empty()) *problem = dir + ": cannot list it: " + ec.message();
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::string> list_images(const std::string &dir, const ImageRanges &range, std::string *problem) {
    std::vector<std::string> out;
    for (auto &f : list_images(dir, problem))
        if (range.empty() || range.contains(image_number(f))) out.push_back(std::move(f));
    return out;
}

namespace {

// The byte count a binary PPM/PGM's header promises (header included), or 0 when the
// header cannot be read.
size_t ppm_expected_size(const std::vector<unsigned char> &b) {
    std::string head(b.begin(), b.begin() + std::min<size_t>(b.size(), 512));
    size_t pos = 2;
    long v[3] = {0, 0, 0};
    for (long &x : v) {
        while (pos < head.size() && (std::isspace(static_cast<unsigned char>(head[pos])) || head[pos] == '#')) {
            if (head[pos] == '#') pos = head.find('\n', pos);
            if (pos == std::string::npos) return 0;
            ++pos;
        }
        const size_t start = pos;
        while (pos < head.size() && std::isdigit(static_cast<unsigned char>(head[pos]))) ++pos;
        if (pos == start || pos - start > 9) return 0;
        x = std::atol(head.substr(start, pos - start).c_str());
    }
    if (pos >= head.size() || v[0] <= 0 || v[1] <= 0 || v[2] <= 0) return 0;
    const size_t channels = head[1] == '6' ? 3 : 1, bytes = v[2] > 255 ? 2 : 1;
    return pos + 1 + size_t(v[0]) * size_t(v[1]) * channels * bytes;
}

std::vector<unsigned char> file_bytes(const std::string &path, bool &ok) {
    std::ifstream f(path, std::ios::binary);
    ok = bool(f);
    return std::vector<unsigned char>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

// image_file_problem() of a file's bytes.
std::string bytes_problem(const std::vector<unsigned char> &b) {
    if (b.empty()) return "empty file";
    const size_t n = b.size();
    if (n >= 2 && b[0] == 0xFF && b[1] == 0xD8) {
        for (size_t i = n - 1; i >= 1 && i + 1024 >= n; --i)
            if (b[i - 1] == 0xFF && b[i] == 0xD9) return "";
        return "truncated JPEG (no end-of-image marker)";
    }
    if (n >= 8 && b[0] == 0x89 && b[1] == 'P' && b[2] == 'N' && b[3] == 'G')
        return n >= 12 && std::equal(b.end() - 8, b.end() - 4, "IEND") ? "" : "truncated PNG (no IEND chunk)";
    if (n >= 2 && b[0] == 'P' && (b[1] == '5' || b[1] == '6')) {
        const size_t want = ppm_expected_size(b);
        if (want == 0) return "unreadable PPM header";
        return n >= want ? "" : "truncated PPM (" + std::to_string(n) + " of " + std::to_string(want) + " bytes)";
    }
    return "";
}

}  // namespace

std::string image_file_problem(const std::string &path) {
    bool ok = false;
    const std::vector<unsigned char> b = file_bytes(path, ok);
    return ok ? bytes_problem(b) : "cannot open the file";
}

std::string read_image(const std::string &path, cv::Mat &img) {
    bool ok = false;
    const std::vector<unsigned char> b = file_bytes(path, ok);
    if (!ok) return "cannot open the file";
    std::string problem = bytes_problem(b);
    if (problem.empty()) {
        img = cv::imdecode(b, cv::IMREAD_COLOR);
        if (img.empty()) problem = "cannot decode it";
    }
    return problem;
}

int image_number(const std::string &path) {
    const std::string stem = fs::path(path).stem().string();
    if (stem.empty() || !std::all_of(stem.begin(), stem.end(), ::isdigit)) return -1;
    return std::atoi(stem.c_str());
}

bool ImageRanges::contains(int n) const {
    for (const auto &r : spans)
        if (n >= r.first && n <= r.second) return true;
    return false;
}

std::string ImageRanges::str(bool padded) const {
    if (spans.empty()) return "all";
    std::string s;
    char b[32];
    for (const auto &r : spans) {
        std::snprintf(b, sizeof b, padded ? "%s%05d-%05d" : "%s%d-%d", s.empty() ? "" : ",", r.first, r.second);
        s += b;
    }
    return s;
}

bool parse_image_ranges(const std::string &s, ImageRanges &out) {
    std::vector<std::pair<int, int>> v;
    std::stringstream ss(s);
    std::string part;
    // strict: digits only, at most kMaxImageNumber (no overflow, no sign, no trailing text)
    auto number = [](const std::string &t, int &out) {
        if (t.empty() || t.size() > 9 || t.find_first_not_of("0123456789") != std::string::npos) return false;
        const long n = std::stol(t);
        if (n > kMaxImageNumber) return false;
        out = int(n);
        return true;
    };
    while (std::getline(ss, part, ',')) {
        const size_t dash = part.find('-');
        int a = -1, b = -1;
        if (dash == std::string::npos || !number(part.substr(0, dash), a) ||
            !number(part.substr(dash + 1), b) || b < a)
            return false;
        v.emplace_back(a, b);
    }
    if (v.empty() || s.back() == ',') return false;
    std::sort(v.begin(), v.end());
    std::vector<std::pair<int, int>> m;
    for (const auto &r : v) {
        if (!m.empty() && r.first <= m.back().second + 1) m.back().second = std::max(m.back().second, r.second);
        else m.push_back(r);
    }
    out.spans = m;
    return true;
}

sbr_image_t bgr_view(const cv::Mat &m) {
    sbr_image_t v{};
    v.width = static_cast<uint32_t>(m.cols);
    v.height = static_cast<uint32_t>(m.rows);
    v.stride = static_cast<uint32_t>(m.step[0]);
    v.format = m.channels() == 1 ? SBR_PIXEL_GRAY8 : SBR_PIXEL_BGR888;
    v.data = m.data;
    return v;
}

}  // namespace sbr_host
