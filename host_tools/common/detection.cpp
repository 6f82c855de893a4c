// SPDX-License-Identifier: MIT
// The host's detection type and the detection file's line (detection.hpp).
#include "detection.hpp"

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

bool parse_detection_line(const std::string &line, Detection &d) {
    std::stringstream ss(line);
    std::string f[7];
    int k = 0;
    while (k < 7 && std::getline(ss, f[k], ';')) ++k;
    if (k < 6) return false;
    d.image = std::atoi(f[0].c_str());
    d.box = from_inclusive(std::atof(f[1].c_str()), std::atof(f[2].c_str()), std::atof(f[3].c_str()),
                           std::atof(f[4].c_str()));
    d.class_id = std::atoi(f[5].c_str());
    d.score = k >= 7 ? std::atof(f[6].c_str()) : 1.0;
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
