// SPDX-License-Identifier: MIT
#include "model_io.hpp"

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace sbr_host {

uint32_t crc32_ieee(const void *data, size_t n) {
    const unsigned char *p = static_cast<const unsigned char *>(data);
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return ~c;
}

namespace {

uint32_t crc32(const unsigned char *p, size_t n) { return crc32_ieee(p, n); }

std::string read_all(const std::string &path, bool &ok) {
    std::ifstream f(path, std::ios::binary);
    ok = static_cast<bool>(f);
    std::stringstream ss;
    if (ok) ss << f.rdbuf();
    return ss.str();
}

// Writes `bytes` to `path`; "" or the reason.
std::string write_all(const std::string &path, const std::string &bytes) {
    std::ofstream f(path, std::ios::binary);
    if (!f) return "cannot write " + path;
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return f ? "" : "write failed: " + path;
}

// The file's trailing CRC over every byte before it.
bool crc_ok(const std::string &s) {
    uint32_t stored = 0;
    std::memcpy(&stored, s.data() + s.size() - 4, 4);
    return crc32(reinterpret_cast<const unsigned char *>(s.data()), s.size() - 4) == stored;
}

template <typename T>
void put(std::string &s, const T &v) {
    s.append(reinterpret_cast<const char *>(&v), sizeof v);
}

template <typename T>
bool get(const std::string &s, size_t &off, T &v) {
    if (off + sizeof v > s.size()) return false;
    std::memcpy(&v, s.data() + off, sizeof v);
    off += sizeof v;
    return true;
}

// A descriptor's record in the file: m, scale, cx, cy and room for 65 coefficients (M up
// to 32, zeros beyond 2m + 1), whatever SBR_FD_MAX_M this build has; a build's smaller
// SBR_FD_MAX_M reads a file's descriptors of m up to its own.
constexpr uint32_t kFileFdCoeffs = 65u;
constexpr size_t kFileFdBytes = 16u + size_t(kFileFdCoeffs) * sizeof(sbr_complex_t);
static_assert(2u * SBR_FD_MAX_M + 1u <= kFileFdCoeffs, "descriptor records hold M up to 32");

void put_fd(std::string &s, const sbr_fd_t &f) {
    put(s, f.m);
    put(s, f.scale);
    put(s, f.cx);
    put(s, f.cy);
    const sbr_complex_t zero{0.0f, 0.0f};
    for (uint32_t k = 0; k < kFileFdCoeffs; ++k) put(s, k < 2u * SBR_FD_MAX_M + 1u ? f.c[k] : zero);
}

// false for an m above this build's SBR_FD_MAX_M (or coefficients stored beyond 2m + 1)
bool get_fd(const std::string &s, size_t &off, sbr_fd_t &f) {
    f = sbr_fd_t{};
    bool ok = get(s, off, f.m) && get(s, off, f.scale) && get(s, off, f.cx) && get(s, off, f.cy);
    for (uint32_t k = 0; ok && k < kFileFdCoeffs; ++k) {
        sbr_complex_t c{};
        ok = get(s, off, c);
        if (k < 2u * SBR_FD_MAX_M + 1u)
            f.c[k] = c;
        else if (c.re != 0.0f || c.im != 0.0f)
            ok = false;
    }
    return ok && f.m >= 1u && f.m <= SBR_FD_MAX_M;
}

size_t picto_w1_len(uint32_t hidden) { return size_t(hidden) * (SBR_PICTO_FEATURES + 1u); }
size_t picto_w2_len(uint32_t hidden, uint32_t classes) {
    return size_t(classes + 1u) * ((hidden > 0 ? hidden : SBR_PICTO_FEATURES) + 1u);
}
size_t picto_w3_len(uint32_t hidden) {
    return size_t(SBR_PICTO_BOX_OUTPUTS) * ((hidden > 0 ? hidden : SBR_PICTO_FEATURES) + 1u);
}
bool picto_sizes_ok(const Picto &p) {
    return p.classes >= 1u && p.classes <= SBR_PICTO_MAX_CLASSES && p.w1.size() == picto_w1_len(p.hidden) &&
           p.w2.size() == picto_w2_len(p.hidden, p.classes) &&
           (p.w3.empty() || p.w3.size() == picto_w3_len(p.hidden)) &&
           p.rim_shape.size() == p.rim_floor.size() &&
           (p.rim_shape.empty() || p.rim_shape.size() == p.classes) &&
           (p.gate.empty() || (p.gate_hidden <= SBR_PICTO_GATE_HIDDEN_MAX &&
                                p.gate.size() == SBR_PICTO_GATE_WEIGHTS(p.gate_hidden)));
}
// The flags word after the class stage's threshold: bit 0 box regression, bit 1 colour
// check tables, bit 2 gate, bit 3 the looks' thresholds (always written; files without
// them are read with sbr_picto_looks_default()).
constexpr uint32_t kPictoLooks = 8u;
constexpr uint32_t kPictoFlagsAll = 15u;
uint32_t picto_flags(const Picto &p) {
    return (p.w3.empty() ? 0u : 1u) | (p.rim_shape.empty() ? 0u : 2u) | (p.gate.empty() ? 0u : 4u) | kPictoLooks;
}
// The looks' thresholds, in the order of sbr_picto_looks_t.
void put_looks(std::string &s, const sbr_picto_looks_t &l) {
    put(s, l.refine_first_score);
    put(s, l.grey_refine_first_score);
    put(s, l.refine_score);
    put(s, l.view_score);
    put(s, l.triangle_score);
}
bool get_looks(const std::string &s, size_t &off, uint32_t flags, sbr_picto_looks_t &l) {
    sbr_picto_looks_default(&l);
    if ((flags & kPictoLooks) == 0u) return true;
    return get(s, off, l.refine_first_score) && get(s, off, l.grey_refine_first_score) &&
           get(s, off, l.refine_score) && get(s, off, l.view_score) && get(s, off, l.triangle_score);
}
// The class stage's weights after its header (threshold and box flag written already).
void put_picto_weights(std::string &s, const Picto &p) {
    for (float w : p.w1) put(s, w);
    for (float w : p.w2) put(s, w);
    for (float w : p.w3) put(s, w);
    for (uint8_t c : p.rim_shape) put(s, c);
    for (float f : p.rim_floor) put(s, f);
    if (!p.gate.empty()) {
        put(s, p.gate_hidden);
        put(s, p.gate_threshold);
        for (float w : p.gate) put(s, w);
    }
}
// Sizes the weight arrays for `hidden`, p.classes (in range) and `flags` (picto_flags());
// reads them when they fit in s exactly (up to the trailing CRC). Returns false when the
// size does not match.
bool get_picto_weights(const std::string &s, size_t &off, uint32_t hidden, uint32_t flags, Picto &p) {
    p.hidden = hidden;
    p.w1.assign(picto_w1_len(hidden), 0.0f);
    p.w2.assign(picto_w2_len(hidden, p.classes), 0.0f);
    p.w3.assign((flags & 1u) != 0 ? picto_w3_len(hidden) : 0u, 0.0f);
    p.rim_shape.assign((flags & 2u) != 0 ? p.classes : 0u, 0u);
    p.rim_floor.assign(p.rim_shape.size(), 0.0f);
    const size_t before_gate = off + 4u * (p.w1.size() + p.w2.size() + p.w3.size() + p.rim_floor.size()) +
                               p.rim_shape.size();
    p.gate.clear();
    p.gate_hidden = 0;
    if ((flags & 4u) != 0) {
        size_t at = before_gate;
        if (!get(s, at, p.gate_hidden) || p.gate_hidden > SBR_PICTO_GATE_HIDDEN_MAX) return false;
        p.gate.assign(SBR_PICTO_GATE_WEIGHTS(p.gate_hidden), 0.0f);
    }
    const size_t gate_bytes = p.gate.empty() ? 0u : 4u * (p.gate.size() + 2u);
    if (before_gate + gate_bytes + 4u != s.size()) return false;
    for (auto &w : p.w1) get(s, off, w);
    for (auto &w : p.w2) get(s, off, w);
    for (auto &w : p.w3) get(s, off, w);
    for (auto &c : p.rim_shape) get(s, off, c);
    for (auto &f : p.rim_floor) get(s, off, f);
    if (!p.gate.empty()) {
        get(s, off, p.gate_hidden);
        get(s, off, p.gate_threshold);
        for (auto &w : p.gate) get(s, off, w);
    }
    return true;
}

// `header` as the generated file's leading C comment.
std::string comment_block(const std::string &header) {
    std::ostringstream o;
    o << "/* SPDX-License-Identifier: MIT */\n/*\n";
    std::istringstream hs(header);
    for (std::string line; std::getline(hs, line);) o << (line.empty() ? " *" : " * " + line) << "\n";
    o << " */\n";
    return o.str();
}

// A float as a C literal that reads back to the same value.
std::string flit(float v) {
    char b[48];
    std::snprintf(b, sizeof b, "%.9ef", static_cast<double>(v));
    return b;
}

}  // namespace

void Model::bind() {
    view.fds = fds.data();
    view.protos = protos.data();
    view.cascade = cascade.data();
    view.proto_count = static_cast<uint32_t>(protos.size());
    if (has_picto) picto.bind();
}

Picto picto_from_view(const sbr_picto_model_t &v) {
    Picto p;
    p.hidden = v.hidden;
    p.classes = v.classes;
    p.threshold = v.threshold;
    p.looks = v.looks;
    if (v.w1 != nullptr) p.w1.assign(v.w1, v.w1 + picto_w1_len(v.hidden));
    if (v.w2 != nullptr) p.w2.assign(v.w2, v.w2 + picto_w2_len(v.hidden, v.classes));
    if (v.w3 != nullptr) p.w3.assign(v.w3, v.w3 + picto_w3_len(v.hidden));
    if (v.rim_shape != nullptr && v.rim_floor != nullptr) {
        p.rim_shape.assign(v.rim_shape, v.rim_shape + v.classes);
        p.rim_floor.assign(v.rim_floor, v.rim_floor + v.classes);
    }
    if (v.gate != nullptr && v.gate_hidden <= SBR_PICTO_GATE_HIDDEN_MAX) {
        p.gate.assign(v.gate, v.gate + SBR_PICTO_GATE_WEIGHTS(v.gate_hidden));
        p.gate_hidden = v.gate_hidden;
        p.gate_threshold = v.gate_threshold;
    }
    p.bind();
    return p;
}

Model model_from_view(const sbr_model_t &v, const sbr_picto_model_t *picto) {
    Model m;
    m.fds.assign(v.fds, v.fds + v.proto_count);
    m.protos.assign(v.protos, v.protos + v.proto_count);
    m.cascade.assign(v.cascade, v.cascade + v.class_first[v.class_count]);
    m.has_picto = picto != nullptr && picto->version != 0;
    if (m.has_picto) m.picto = picto_from_view(*picto);
    m.view = v;
    m.bind();
    return m;
}

std::string model_bytes(const Model &m, std::string &s) {
    s = "SBRM";
    const sbr_model_t &v = m.view;
    put(s, v.version);
    put(s, v.fd_n);
    put(s, v.fd_m);
    put(s, static_cast<uint32_t>(m.protos.size()));
    put(s, static_cast<uint32_t>(m.cascade.size()));
    if (v.class_count == 0u || v.class_count > SBR_RECOG_MAX_CLASSES) return "class count out of range";
    put(s, v.class_count);
    put(s, v.vote_error);
    put(s, v.score_threshold);
    for (auto g : v.group_first) put(s, g);
    for (uint32_t c = 0; c <= v.class_count; ++c) put(s, v.class_first[c]);
    for (uint32_t c = 0; c < v.class_count; ++c) put(s, v.class_outline[c]);
    for (const auto &f : m.fds) put_fd(s, f);
    for (const auto &p : m.protos) put(s, p);
    for (auto c : m.cascade) put(s, c);
    put(s, m.has_picto ? m.picto.hidden + 1u : 0u);
    if (m.has_picto) {
        if (!picto_sizes_ok(m.picto)) return "classifier sizes do not match its hidden layer";
        put(s, m.picto.threshold);
        put(s, picto_flags(m.picto));
        put_looks(s, m.picto.looks);
        put_picto_weights(s, m.picto);
    }
    put(s, crc32(reinterpret_cast<const unsigned char *>(s.data()), s.size()));
    return "";
}

std::string save_model(const Model &m, const std::string &path) {
    std::string s;
    const std::string e = model_bytes(m, s);
    return e.empty() ? write_all(path, s) : e;
}

std::string load_model(const std::string &path, Model &m) {
    bool ok = false;
    const std::string s = read_all(path, ok);
    if (!ok) return "cannot read " + path;
    return parse_model(s, path, m);
}

std::string parse_model(const std::string &s, const std::string &path, Model &m) {
    m = Model{};
    if (s.size() < 8 || s.compare(0, 4, "SBRM") != 0) return path + ": magic: not an sbr model file";
    if (!crc_ok(s)) return path + ": crc: mismatch (corrupted or truncated file)";
    size_t off = 4;
    sbr_model_t v{};
    uint32_t np = 0, nc = 0;
    if (!get(s, off, v.version)) return path + ": sizes: truncated header";
    if (v.version != SBR_MODEL_VERSION)
        return path + ": version: format " + std::to_string(v.version) + ", this build reads " +
               std::to_string(SBR_MODEL_VERSION);
    bool ok = get(s, off, v.fd_n) && get(s, off, v.fd_m) && get(s, off, np) && get(s, off, nc) &&
              get(s, off, v.class_count);
    if (!ok) return path + ": sizes: truncated header";
    if (np == 0u || np > 65535u || v.class_count == 0u || v.class_count > SBR_RECOG_MAX_CLASSES ||
        nc > 65535u * v.class_count)
        return path + ": sizes: bad counts";
    ok = get(s, off, v.vote_error) && get(s, off, v.score_threshold);
    for (auto &g : v.group_first) ok = ok && get(s, off, g);
    for (uint32_t c = 0; c <= v.class_count; ++c) ok = ok && get(s, off, v.class_first[c]);
    for (uint32_t c = 0; c < v.class_count; ++c) ok = ok && get(s, off, v.class_outline[c]);
    if (!ok) return path + ": sizes: truncated header";
    const size_t need = off + size_t(np) * (kFileFdBytes + sizeof(sbr_model_proto_t)) + size_t(nc) * 2u + 8u;
    if (need > s.size()) return path + ": sizes: file shorter than its counts";
    m.fds.resize(np);
    m.protos.resize(np);
    m.cascade.resize(nc);
    for (auto &x : m.fds)
        if (!get_fd(s, off, x))
            return path + ": descriptors: an order M above " + std::to_string(SBR_FD_MAX_M) + " (this build's largest)";
    for (auto &x : m.protos) get(s, off, x);
    for (auto &x : m.cascade) get(s, off, x);
    uint32_t picto = 0;
    get(s, off, picto);
    m.has_picto = picto != 0;
    if (m.has_picto) {
        const uint32_t hidden = picto - 1u;
        uint32_t box = 0;
        if (hidden > SBR_PICTO_HIDDEN_MAX || !get(s, off, m.picto.threshold) || !get(s, off, box) ||
            box > kPictoFlagsAll || !get_looks(s, off, box, m.picto.looks))
            return path + ": sizes: bad class stage header";
        m.picto.classes = v.class_count;  // the class stage has the model's classes
        if (!get_picto_weights(s, off, hidden, box, m.picto)) return path + ": sizes: do not match the counts";
    } else if (off + 4u != s.size()) {
        return path + ": sizes: do not match the counts";
    }
    m.view = v;
    m.bind();
    const sbr_status_t st = sbr_model_check(&m.view);
    if (st != SBR_OK) return path + ": values: sbr_model_check: " + sbr_status_str(st);
    if (m.has_picto) {
        const sbr_status_t ps = sbr_picto_check(&m.picto.view);
        if (ps == SBR_OK && m.picto.view.classes != m.view.class_count)
            return path + ": values: the class stage's class count is not the library's";
        if (ps != SBR_OK) return path + ": values: sbr_picto_check: " + sbr_status_str(ps);
    }
    return "";
}

std::string write_model_c(const Model &m, const std::string &path, const std::string &header) {
    std::ostringstream o;
    const sbr_model_t &v = m.view;
    o << comment_block(header) << "#include \"sbr/models.h\"\n\n";
    // The tables are block-scope const objects of the one function that uses them
    // (MISRA C:2012 8.9); they live in flash, the caller's struct only points at them.
    o << "sbr_status_t sbr_model_gtsdb(sbr_model_t *out)\n{\n";
    o << "    static const sbr_fd_t model_fds[" << m.fds.size() << "] = {\n";
    for (const auto &f : m.fds) {
        o << "        {" << f.m << "u, " << flit(f.scale) << ", " << flit(f.cx) << ", " << flit(f.cy) << ", {";
        for (uint32_t k = 0; k < 2u * f.m + 1u; ++k)
            o << (k ? ", " : "") << "{" << flit(f.c[k].re) << ", " << flit(f.c[k].im) << "}";
        o << "}},\n";
    }
    o << "    };\n    static const sbr_model_proto_t model_protos[" << m.protos.size() << "] = {\n";
    for (const auto &p : m.protos) {
        o << "        {" << flit(p.dx) << ", " << flit(p.dy) << ", " << flit(p.w) << ", " << flit(p.h) << ", "
          << flit(p.weight) << ", " << p.support << "u, " << unsigned(p.map) << "u, " << unsigned(p.polarity)
          << "u, {";
        for (unsigned k = 0; k < SBR_MODEL_PROTO_CLASSES; ++k) o << (k ? ", " : "") << unsigned(p.class_id[k]) << "u";
        o << "}, {";
        for (unsigned k = 0; k < SBR_MODEL_PROTO_CLASSES; ++k) o << (k ? ", " : "") << flit(p.class_p[k]);
        o << "}},\n";
    }
    o << "    };\n    static const uint16_t model_cascade[" << m.cascade.size() << "] = {";
    for (size_t i = 0; i < m.cascade.size(); ++i) o << (i % 16 ? " " : "\n        ") << m.cascade[i] << "u,";
    o << "\n    };\n    static const uint16_t model_group_first[" << (SBR_MODEL_GROUPS + 1u) << "] = {";
    for (unsigned g = 0; g <= SBR_MODEL_GROUPS; ++g) o << (g ? ", " : "") << v.group_first[g] << "u";
    const unsigned nc = v.class_count;
    o << "};\n    static const uint16_t model_class_first[" << (nc + 1u) << "] = {";
    for (unsigned c = 0; c <= nc; ++c) o << (c % 12 ? " " : "\n        ") << v.class_first[c] << "u,";
    o << "\n    };\n    static const uint8_t model_class_outline[" << nc << "] = {";
    for (unsigned c = 0; c < nc; ++c) o << (c % 16 ? " " : "\n        ") << unsigned(v.class_outline[c]) << "u,";
    o << "\n    };\n    uint32_t i;\n"
      << "    if (out == NULL) {\n        return SBR_ERR_NULL;\n    }\n"
      << "    out->version = " << v.version << "u;\n    out->fd_n = " << v.fd_n << "u;\n    out->fd_m = " << v.fd_m
      << "u;\n    out->proto_count = " << m.protos.size() << "u;\n    out->fds = model_fds;\n"
      << "    out->protos = model_protos;\n"
      << "    for (i = 0u; i <= SBR_MODEL_GROUPS; i++) {\n        out->group_first[i] = model_group_first[i];\n    }\n"
      << "    out->class_count = " << nc << "u;\n"
      << "    for (i = 0u; i <= SBR_RECOG_MAX_CLASSES; i++) {\n        out->class_first[i] = model_class_first[" << nc
      << "]; /* past the last class: empty */\n    }\n"
      << "    for (i = 0u; i <= " << nc << "u; i++) {\n        out->class_first[i] = model_class_first[i];\n    }\n"
      << "    for (i = 0u; i < SBR_RECOG_MAX_CLASSES; i++) {\n        out->class_outline[i] = 0u;\n    }\n"
      << "    for (i = 0u; i < " << nc << "u; i++) {\n        out->class_outline[i] = model_class_outline[i];\n    }\n"
      << "    out->cascade = model_cascade;\n    out->vote_error = " << flit(v.vote_error)
      << ";\n    out->score_threshold = " << flit(v.score_threshold) << ";\n"
      << "    return SBR_OK;\n}\n";
    std::ofstream f(path);
    if (!f) return "cannot write " + path;
    f << o.str();
    return f ? "" : "write failed: " + path;
}

void Picto::bind() {
    view.version = SBR_PICTO_VERSION;
    view.features = SBR_PICTO_FEATURES;
    view.hidden = hidden;
    view.classes = classes;
    view.threshold = threshold;
    view.looks = looks;
    view.w1 = hidden > 0 ? w1.data() : nullptr;
    view.w2 = w2.data();
    view.w3 = w3.empty() ? nullptr : w3.data();
    view.rim_shape = rim_shape.empty() ? nullptr : rim_shape.data();
    view.rim_floor = rim_floor.empty() ? nullptr : rim_floor.data();
    view.gate = gate.empty() ? nullptr : gate.data();
    view.gate_hidden = gate.empty() ? 0u : gate_hidden;
    view.gate_threshold = gate.empty() ? 0.0f : gate_threshold;
}


std::string picto_bytes(const Picto &p, std::string &s) {
    if (!picto_sizes_ok(p)) return "classifier sizes do not match its hidden layer";
    s = "SBRP";
    put(s, uint32_t(SBR_PICTO_VERSION));
    put(s, uint32_t(SBR_PICTO_FEATURES));
    put(s, p.hidden);
    put(s, p.classes);
    put(s, p.threshold);
    put(s, picto_flags(p));
    put_looks(s, p.looks);
    put_picto_weights(s, p);
    put(s, crc32(reinterpret_cast<const unsigned char *>(s.data()), s.size()));
    return "";
}

std::string save_picto(const Picto &p, const std::string &path) {
    std::string s;
    const std::string e = picto_bytes(p, s);
    return e.empty() ? write_all(path, s) : e;
}

std::string load_picto(const std::string &path, Picto &p) {
    bool ok = false;
    const std::string s = read_all(path, ok);
    if (!ok) return "cannot read " + path;
    return parse_picto(s, path, p);
}

std::string parse_picto(const std::string &s, const std::string &path, Picto &p) {
    p = Picto{};
    if (s.size() < 8 || s.compare(0, 4, "SBRP") != 0) return path + ": magic: not an sbr classifier file";
    if (!crc_ok(s)) return path + ": crc: mismatch (corrupted or truncated file)";
    size_t off = 4;
    uint32_t version = 0, features = 0, hidden = 0, box = 0;
    if (!get(s, off, version)) return path + ": sizes: truncated header";
    // format 3 had no looks' thresholds (they were the recogniser's configuration then)
    if (version != SBR_PICTO_VERSION && version != 3u)
        return path + ": version: format " + std::to_string(version) + ", this build reads 3 and " +
               std::to_string(SBR_PICTO_VERSION);
    if (!get(s, off, features) || !get(s, off, hidden) || !get(s, off, p.classes) || !get(s, off, p.threshold) ||
        !get(s, off, box))
        return path + ": sizes: truncated header";
    if (features != SBR_PICTO_FEATURES || hidden > SBR_PICTO_HIDDEN_MAX || p.classes == 0u ||
        p.classes > SBR_PICTO_MAX_CLASSES || box > kPictoFlagsAll || (version == 3u && (box & kPictoLooks) != 0u))
        return path + ": sizes: features, hidden units, classes or flags out of range";
    if (!get_looks(s, off, box, p.looks)) return path + ": sizes: truncated header";
    if (!get_picto_weights(s, off, hidden, box, p)) return path + ": sizes: do not match the header";
    p.bind();
    const sbr_status_t st = sbr_picto_check(&p.view);
    if (st != SBR_OK) return path + ": values: sbr_picto_check: " + sbr_status_str(st);
    return "";
}

std::string write_picto_c(const Picto &p, const std::string &path, const std::string &header) {
    if (!picto_sizes_ok(p)) return "classifier sizes do not match its hidden layer";
    std::ostringstream o;
    o << comment_block(header) << "#include \"sbr/models.h\"\n\n";
    o << "sbr_status_t sbr_picto_gtsdb(sbr_picto_model_t *out)\n{\n";
    auto table = [&](const char *name, const std::vector<float> &w) {
        o << "    static const float " << name << "[" << w.size() << "] = {";
        for (size_t i = 0; i < w.size(); ++i) o << (i % 6 ? " " : "\n        ") << flit(w[i]) << ",";
        o << "\n    };\n";
    };
    if (p.hidden > 0) table("picto_w1", p.w1);
    table("picto_w2", p.w2);
    if (!p.w3.empty()) table("picto_w3", p.w3);
    const bool rim = !p.rim_shape.empty();
    if (rim) {
        o << "    static const uint8_t picto_rim_shape[" << p.rim_shape.size() << "] = {";
        for (size_t i = 0; i < p.rim_shape.size(); ++i) o << (i % 16 ? " " : "\n        ") << unsigned(p.rim_shape[i]) << "u,";
        o << "\n    };\n";
        table("picto_rim_floor", p.rim_floor);
    }
    if (!p.gate.empty()) table("picto_gate", p.gate);
    o << "    if (out == NULL) {\n        return SBR_ERR_NULL;\n    }\n"
      << "    out->version = SBR_PICTO_VERSION;\n    out->features = SBR_PICTO_FEATURES;\n"
      << "    out->hidden = " << p.hidden << "u;\n    out->classes = " << p.classes << "u;\n"
      << "    out->threshold = " << flit(p.threshold) << ";\n"
      << "    out->looks.refine_first_score = " << flit(p.looks.refine_first_score) << ";\n"
      << "    out->looks.grey_refine_first_score = " << flit(p.looks.grey_refine_first_score) << ";\n"
      << "    out->looks.refine_score = " << flit(p.looks.refine_score) << ";\n"
      << "    out->looks.view_score = " << flit(p.looks.view_score) << ";\n"
      << "    out->looks.triangle_score = " << flit(p.looks.triangle_score) << ";\n"
      << "    out->w1 = " << (p.hidden > 0 ? "picto_w1" : "NULL") << ";\n    out->w2 = picto_w2;\n"
      << "    out->w3 = " << (p.w3.empty() ? "NULL" : "picto_w3") << ";\n"
      << "    out->rim_shape = " << (rim ? "picto_rim_shape" : "NULL") << ";\n"
      << "    out->rim_floor = " << (rim ? "picto_rim_floor" : "NULL") << ";\n"
      << "    out->gate = " << (p.gate.empty() ? "NULL" : "picto_gate") << ";\n"
      << "    out->gate_hidden = " << (p.gate.empty() ? 0u : p.gate_hidden) << "u;\n"
      << "    out->gate_threshold = " << flit(p.gate.empty() ? 0.0f : p.gate_threshold) << ";\n"
      << "    return SBR_OK;\n}\n";
    std::ofstream f(path);
    if (!f) return "cannot write " + path;
    f << o.str();
    return f ? "" : "write failed: " + path;
}

bool report_write(const char *tool, const std::string &path, const std::string &error) {
    if (!error.empty()) {
        std::fprintf(stderr, "%s: %s\n", tool, error.c_str());
        return false;
    }
    std::fprintf(stderr, "%s: wrote %s\n", tool, path.c_str());
    return true;
}

void parts_at_full_resolution(sbr_parts_config_t &parts) {
    for (uint32_t k = 0; k < SBR_MAP_KINDS; ++k) {
        parts.map_subsample[k] = 1;
        parts.map_min_area[k] = 0;
        parts.map_polarity[k] = 0;
        parts.map_bright_min[k] = 0;
        parts.map_dark_max[k] = 0;
    }
}

void training_bounds(sbr_recog_config_t &rc) {
    rc.max_parts = 4096u;
    rc.parts.mser.max_heap = 0u;
    // no budget: the largest the table allows
    sbr_field_t looks;
    if (sbr_recog_field_at(sbr_recog_field_find("max_extra_looks"), &looks) == SBR_OK) rc.max_extra_looks = looks.hi_u;
}

void apply_front_end(const FrontEnd &fe, sbr_parts_config_t &parts) {
    // the table's offsets are into sbr_recog_config_t; the per-map lists are in its `parts`
    unsigned char *base = reinterpret_cast<unsigned char *>(&parts);
    for (const auto &kv : fe.lists) {
        sbr_field_t field;
        static_assert(offsetof(sbr_recog_config_t, parts) == 0, "parts opens the configuration");
        if (sbr_recog_field_at(sbr_recog_field_find(kv.first.c_str()), &field) != SBR_OK) continue;
        const sbr_field_t *f = &field;
        if (f->offset + 4u * f->count > sizeof parts) continue;
        const size_t at = f->offset;
        for (size_t k = 0; k < kv.second.size() && k < f->count; ++k) {
            const uint32_t v = kv.second[k];
            std::memcpy(base + at + 4u * k, &v, sizeof v);
        }
    }
}

}  // namespace sbr_host
