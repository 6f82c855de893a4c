// SPDX-License-Identifier: MIT
#include "track_model_io.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "model_io.hpp"

namespace sbr_host {

namespace {

const char *kMagic = "sbr_track_model";
const unsigned kVersion = 2;

std::string body_of(const TrackModel &d)
{
    std::ostringstream out;
    out << kMagic << " " << kVersion << "\n";
    out << "order " << d.m.order << "\nperiod " << d.m.period << "\nextent " << d.m.extent[0] << " "
        << d.m.extent[1] << "\nregions " << d.m.regions[0] << " " << d.m.regions[1] << "\nvel_count "
        << d.m.vel_count << "\nvel_spacing " << d.m.vel_spacing << "\n";
    out.precision(9);
    out << "transition " << d.trans.size() << "\n";
    for (size_t i = 0; i < d.trans.size(); ++i) out << d.trans[i] << ((i + 1) % d.m.vel_count ? ' ' : '\n');
    out << "birth " << d.birth.size() << "\n";
    for (size_t i = 0; i < d.birth.size(); ++i) out << d.birth[i] << ((i + 1) % d.m.vel_count ? ' ' : '\n');
    return out.str();
}

bool read_table(std::istream &in, size_t max, std::vector<float> &v)
{
    size_t n = 0;
    if (!(in >> n) || n > max) return false;
    v.resize(n);
    for (auto &x : v)
        if (!(in >> x)) return false;
    return true;
}

}  // namespace

std::string track_model_bytes(const TrackModel &d, std::string &bytes)
{
    if (d.m.vel_count == 0) return "no model to write";
    bytes = body_of(d);
    char crc[32];
    std::snprintf(crc, sizeof crc, "crc32 %08x\n", crc32_ieee(bytes.data(), bytes.size()));
    bytes += crc;
    return "";
}

std::string save_track_model(const TrackModel &d, const std::string &path)
{
    std::string bytes;
    const std::string e = track_model_bytes(d, bytes);
    if (!e.empty()) return e;
    std::ofstream out(path, std::ios::binary);
    if (!out) return "cannot write " + path;
    out << bytes;
    return out ? "" : "write failed: " + path;
}

std::string parse_track_model(const std::string &s, const std::string &path, TrackModel &d)
{
    d = TrackModel{};
    // magic and version first, so a foreign file is named as such
    {
        std::istringstream head(s.substr(0, 64));
        std::string key;
        unsigned ver = 0;
        if (!(head >> key) || key != kMagic) return path + ": magic: not an sbr_track_model file";
        if (!(head >> ver) || ver != kVersion)
            return path + ": version: format " + std::to_string(ver) + ", this build reads " +
                   std::to_string(kVersion);
    }
    const size_t at = s.rfind("crc32 ");
    if (at == std::string::npos || (at > 0 && s[at - 1] != '\n')) return path + ": crc: no crc32 line (truncated?)";
    unsigned stored = 0;
    char tail = 0;
    if (std::sscanf(s.c_str() + at, "crc32 %8x%c", &stored, &tail) != 2 || tail != '\n' ||
        at + 15 != s.size())
        return path + ": crc: malformed crc32 line";
    if (crc32_ieee(s.data(), at) != stored) return path + ": crc: mismatch (corrupted file)";
    std::istringstream in(s.substr(0, at));
    std::string key;
    unsigned ver = 0;
    in >> key >> ver;
    bool seen_trans = false, seen_birth = false;
    while (in >> key) {
        if (key == "order") in >> d.m.order;
        else if (key == "period") in >> d.m.period;
        else if (key == "extent") in >> d.m.extent[0] >> d.m.extent[1];
        else if (key == "regions") in >> d.m.regions[0] >> d.m.regions[1];
        else if (key == "vel_count") in >> d.m.vel_count;
        else if (key == "vel_spacing") in >> d.m.vel_spacing;
        else if (key == "transition") {
            if (!read_table(in, 2000000, d.trans)) return path + ": sizes: transition table malformed or too large";
            seen_trans = true;
        } else if (key == "birth") {
            if (!read_table(in, 200000, d.birth)) return path + ": sizes: birth table malformed or too large";
            seen_birth = true;
        } else {
            return path + ": format: unknown key " + key;
        }
        if (!in) return path + ": format: bad value after " + key;
    }
    if (!seen_trans || !seen_birth) return path + ": format: a table is missing";
    if (d.m.regions[0] < 3u || d.m.regions[0] > SBR_TRACK_MAX_REGIONS || d.m.regions[1] < 3u ||
        d.m.regions[1] > SBR_TRACK_MAX_REGIONS || d.m.vel_count < 5u || d.m.vel_count > SBR_TRACK_MAX_VEL)
        return path + ": sizes: region or velocity channel count out of range";
    if (d.trans.size() != SBR_TRACK_MODEL_TRANSITION_LEN(d.m.regions[0], d.m.regions[1], d.m.vel_count) ||
        d.birth.size() != SBR_TRACK_MODEL_BIRTH_LEN(d.m.regions[0], d.m.regions[1], d.m.vel_count))
        return path + ": sizes: table sizes do not match the header";
    for (float v : d.trans)
        if (!std::isfinite(v)) return path + ": values: non-finite transition entry";
    for (float v : d.birth)
        if (!std::isfinite(v)) return path + ": values: non-finite birth entry";
    d.bind();
    const sbr_status_t st = sbr_track_model_check(&d.m);
    if (st != SBR_OK) return path + ": values: sbr_track_model_check: " + sbr_status_str(st);
    return "";
}

std::string load_track_model(const std::string &path, TrackModel &d)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) return "cannot read " + path;
    std::stringstream ss;
    ss << in.rdbuf();
    return parse_track_model(ss.str(), path, d);
}

}  // namespace sbr_host
