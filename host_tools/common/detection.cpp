// SPDX-License-Identifier: MIT
// The host's detection type and the detection file's line (detection.hpp).
#include "detection.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace sbr_host {

Detection from_core(const sbr_detection_t &d, int image) {
    Detection o;
    o.image = image;
    o.box = {double(d.box.x), double(d.box.y), double(d.box.x) + double(d.box.width),
             double(d.box.y) + double(d.box.height)};
    o.class_id = int(d.class_id);
    o.score = double(d.score);
    return o;
}

bool to_core(const Detection &d, sbr_detection_t &out) {
    const double lim = 16777216.0;
    const PixBox &b = d.box;
    const auto whole = [lim](double v) { return v >= 0.0 && v <= lim && v == std::floor(v); };
    if (!whole(b.x0) || !whole(b.y0) || !whole(b.x1) || !whole(b.y1) || b.x1 < b.x0 || b.y1 < b.y0 ||
        d.class_id < 0 || d.class_id > 65535)
        return false;
    out = sbr_detection_t{};
    out.box.x = uint32_t(b.x0);
    out.box.y = uint32_t(b.y0);
    out.box.width = uint32_t(b.x1 - b.x0);
    out.box.height = uint32_t(b.y1 - b.y0);
    out.class_id = uint16_t(d.class_id);
    out.score = float(d.score);
    return true;
}

namespace {

// The whole field as a number (no trailing text, finite); false otherwise.
bool field_number(const std::string &f, double &v) {
    if (f.empty()) return false;
    char *end = nullptr;
    v = std::strtod(f.c_str(), &end);
    return end == f.c_str() + f.size() && std::isfinite(v);
}

}  // namespace

bool parse_detection_line(std::string line, Detection &d) {
    if (!line.empty() && line.back() == '\r') line.pop_back();  // a file saved with CRLF
    std::stringstream ss(line);
    std::string f[8];
    int k = 0;
    while (k < 8 && std::getline(ss, f[k], ';')) ++k;
    if (k < 6 || k > 7) return false;
    // NNNNN.ext: the image number first
    if (f[0].empty() || !std::isdigit(static_cast<unsigned char>(f[0][0]))) return false;
    double v[6] = {0, 0, 0, 0, 0, 1.0};
    for (int i = 1; i < k; ++i)
        if (!field_number(f[i], v[i - 1])) return false;
    if (v[4] != std::floor(v[4]) || v[4] < 0 || v[4] > 1e6) return false;  // a class id
    d.image = std::atoi(f[0].c_str());
    d.box = from_inclusive(v[0], v[1], v[2], v[3]);
    d.class_id = static_cast<int>(v[4]);
    d.score = v[5];
    return true;
}

std::string detection_line(const std::string &name, const Detection &d) {
    const InclusiveBox b = to_inclusive(d.box);
    char line[192];
    std::snprintf(line, sizeof line, "%s;%.0f;%.0f;%.0f;%.0f;%d;%.4f\n", name.c_str(), b.left, b.top, b.right,
                  b.bottom, d.class_id, d.score);
    return line;
}

}  // namespace sbr_host
