// SPDX-License-Identifier: MIT
// The model file forms (--model .sbrm, --picto .sbrp, sbr_track --model text) against
// damaged files: the built-in models are written, then truncated at many lengths, bit-flipped
// at many positions, changed with the CRC fixed up (counts, a weight made NaN, a table row
// made invalid), version-bumped and given a foreign magic. Every damaged file must be
// refused, and the refusal must name the check that caught it (magic, version, crc, sizes,
// values, format); the intact files load and save back byte for byte.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

#include "model_io.hpp"
#include "track_model_io.hpp"

extern "C" {
#include "sbr/picto.h"
#include "sbr/recog.h"
#include "sbr/track.h"
#include "sbr/models.h"

#include "test_help.hpp"
}

namespace {

int failures = 0;
int checks = 0;

void expect(bool ok, const std::string &what)
{
    ++checks;
    if (!ok) {
        ++failures;
        std::printf("FAIL: %s\n", what.c_str());
    }
}

// the refusal names `check` (": magic:", ": crc:", ...)
void expect_refused(const std::string &err, const char *check, const std::string &what)
{
    expect(!err.empty() && err.find(std::string(": ") + check + ":") != std::string::npos,
           what + " -> '" + err + "' (wanted a " + check + " refusal)");
}

void fix_crc(std::string &s)
{
    const uint32_t c = sbr_host::crc32_ieee(s.data(), s.size() - 4u);
    std::memcpy(&s[s.size() - 4u], &c, 4u);
}

template <typename Parse>
void binary_damage(const std::string &good, const char *name, Parse parse)
{
    // truncated: every length of the header, then every 997th byte
    int n = 0;
    for (size_t len = 0; len < good.size(); len += (len < 256u ? 1u : 997u), ++n) {
        const std::string e = parse(good.substr(0, len));
        expect(!e.empty(), std::string(name) + " truncated to " + std::to_string(len) + " bytes accepted");
        if (len >= 8u) expect_refused(e, "crc", std::string(name) + " truncated to " + std::to_string(len));
    }
    // one bit flipped anywhere: the CRC catches it
    for (size_t pos = 0; pos < good.size(); pos += 1 + good.size() / 300u) {
        std::string s = good;
        s[pos] = static_cast<char>(s[pos] ^ (1 << (pos % 8u)));
        const std::string e = parse(s);
        if (pos < 4u)
            expect_refused(e, "magic", std::string(name) + " bit flip in the magic");
        else
            expect_refused(e, "crc", std::string(name) + " bit flip at " + std::to_string(pos));
    }
    // truncated with the CRC fixed up: the sizes no longer match the counts
    {
        std::string s = good.substr(0, good.size() - 100u);
        fix_crc(s);
        expect_refused(parse(s), "sizes", std::string(name) + " truncated, CRC fixed up");
    }
    // version bumped, CRC fixed up
    {
        std::string s = good;
        uint32_t v = 0;
        std::memcpy(&v, &s[4], 4u);
        ++v;
        std::memcpy(&s[4], &v, 4u);
        fix_crc(s);
        expect_refused(parse(s), "version", std::string(name) + " version bumped");
    }
    // a foreign file
    {
        std::string s = good;
        s[0] = 'X';
        expect_refused(parse(s), "magic", std::string(name) + " foreign magic");
    }
    std::printf("%s: %zu bytes, %d truncations, bit flips and fixed-up changes refused\n", name, good.size(), n);
}

}  // namespace

int main(int argc, char **argv)
{
    const int h = test_help(argc, argv, "test_model_files: the model file forms (.sbrm, .sbrp, .stm) intact and damaged",
                            "test_model_files");
    if (h >= 0) return h;
    sbr_model_t mv{};
    sbr_picto_model_t pv{};
    sbr_track_model_t tv{};
    if (sbr_model_gtsdb(&mv) != SBR_OK || sbr_picto_gtsdb(&pv) != SBR_OK || sbr_track_model_kitti(&tv) != SBR_OK) {
        std::printf("FAIL: built-in models\n");
        return 1;
    }

    // ---- the class stage (.sbrp)
    std::string picto;
    expect(sbr_host::picto_bytes(sbr_host::picto_from_view(pv), picto).empty(), "write .sbrp");
    {
        sbr_host::Picto p;
        expect(sbr_host::parse_picto(picto, "builtin.sbrp", p).empty(), "the intact .sbrp loads");
        std::string again;
        expect(sbr_host::picto_bytes(p, again).empty() && again == picto, "the .sbrp saves back byte for byte");
    }
    auto parse_picto = [](const std::string &s) {
        sbr_host::Picto p;
        return sbr_host::parse_picto(s, "f.sbrp", p);
    };
    binary_damage(picto, ".sbrp", parse_picto);
    {
        // a weight made NaN, CRC fixed up: values
        std::string s = picto;
        const float nan = NAN;
        std::memcpy(&s[s.size() - 8u], &nan, 4u);
        fix_crc(s);
        expect_refused(parse_picto(s), "values", ".sbrp NaN weight, CRC fixed up");
        // hidden units above the maximum: sizes
        s = picto;
        const uint32_t hidden = SBR_PICTO_HIDDEN_MAX + 1u;
        std::memcpy(&s[12], &hidden, 4u);
        fix_crc(s);
        expect_refused(parse_picto(s), "sizes", ".sbrp hidden units out of range, CRC fixed up");
        // a class count of 0 or above SBR_PICTO_MAX_CLASSES: sizes
        for (uint32_t k : {0u, SBR_PICTO_MAX_CLASSES + 1u}) {
            s = picto;
            std::memcpy(&s[16], &k, 4u);
            fix_crc(s);
            expect_refused(parse_picto(s), "sizes", ".sbrp class count " + std::to_string(k) + ", CRC fixed up");
        }
    }

    {
        // the looks' thresholds (flags bit 3, five floats after the flags): they load and
        // save back; a format-3 file (no looks, from before they were the model's) loads
        // with sbr_picto_looks_default(); out of [0, 1] is refused; format 3 with the bit
        // set is refused
        sbr_host::Picto p = sbr_host::picto_from_view(pv);
        p.looks.refine_score = 0.5f;
        p.looks.triangle_score = 0.0f;
        p.bind();
        std::string a;
        expect(sbr_host::picto_bytes(p, a).empty(), "write with looks");
        sbr_host::Picto back;
        expect(sbr_host::parse_picto(a, "looks.sbrp", back).empty() && back.looks.refine_score == 0.5f &&
                   back.looks.triangle_score == 0.0f && back.view.looks.refine_score == 0.5f,
               "the looks load");
        std::string old = picto.substr(0, 28) + picto.substr(48);
        uint32_t v = 3u, flags = 0u;
        std::memcpy(&old[4], &v, 4u);
        std::memcpy(&flags, &old[24], 4u);
        expect((flags & 8u) != 0u, "the built-in class stage's file has the looks' bit");
        flags &= ~8u;
        std::memcpy(&old[24], &flags, 4u);
        fix_crc(old);
        sbr_picto_looks_t def;
        sbr_picto_looks_default(&def);
        expect(sbr_host::parse_picto(old, "format3.sbrp", back).empty() &&
                   std::memcmp(&back.looks, &def, sizeof def) == 0,
               "a format-3 .sbrp loads with the default looks");
        std::string bad = old;
        flags |= 8u;
        std::memcpy(&bad[24], &flags, 4u);
        fix_crc(bad);
        expect_refused(parse_picto(bad), "sizes", ".sbrp format 3 with the looks' bit, CRC fixed up");
        bad = a;
        const float out = 1.5f;
        std::memcpy(&bad[28 + 8], &out, 4u);  // refine_score
        fix_crc(bad);
        expect_refused(parse_picto(bad), "values", ".sbrp refine_score 1.5, CRC fixed up");
        std::printf(".sbrp looks: round trip, format 3 read with the defaults, out of range refused\n");
    }

    {
        // the colour check's tables (picto.h rim_shape, rim_floor; flags bit 1): they
        // load and save back; without them the file is the same minus the tables (older
        // files load); damaged tables are refused. Without a gate (the built-in class
        // stage has one), so that the tables end the file.
        sbr_host::Picto with = sbr_host::picto_from_view(pv);
        with.gate.clear();
        with.gate_hidden = 0u;
        with.gate_threshold = 0.0f;
        sbr_host::Picto without = with;
        const uint32_t K = pv.classes;
        with.rim_shape.assign(K, uint8_t(SBR_PICTO_RIM_NONE));
        with.rim_floor.assign(K, -2.0f);
        with.rim_shape[13] = uint8_t(SBR_PICTO_RIM_TRIANGLE_DOWN);
        with.rim_floor[13] = 0.0125f;
        without.rim_shape.clear();
        without.rim_floor.clear();
        with.bind();
        without.bind();
        std::string a, b;
        expect(sbr_host::picto_bytes(with, a).empty() && sbr_host::picto_bytes(without, b).empty(), "write both");
        expect(a.size() == b.size() + 5u * K, ".sbrp with the tables is K bytes + K floats longer");
        sbr_host::Picto back;
        expect(sbr_host::parse_picto(a, "rim.sbrp", back).empty() && back.rim_shape == with.rim_shape &&
                   back.rim_floor == with.rim_floor && back.view.rim_shape != nullptr,
               "the tables load");
        expect(sbr_host::parse_picto(b, "plain.sbrp", back).empty() && back.rim_shape.empty() &&
                   back.view.rim_shape == nullptr && back.view.rim_floor == nullptr,
               "a file without them loads without a colour check");
        const size_t shapes_at = a.size() - 4u - 4u * K - K;
        std::string d = a;
        d[shapes_at + 13u] = 9;  // no such outline
        fix_crc(d);
        expect_refused(parse_picto(d), "values", ".sbrp rim outline 9, CRC fixed up");
        d = a;
        const float big = 3.0f;
        std::memcpy(&d[a.size() - 8u], &big, 4u);  // class 42's floor beyond 2
        fix_crc(d);
        expect_refused(parse_picto(d), "values", ".sbrp rim floor 3, CRC fixed up");
        d = a;
        const uint32_t flags = 7u;
        std::memcpy(&d[24], &flags, 4u);
        fix_crc(d);
        expect_refused(parse_picto(d), "sizes", ".sbrp flags 7, CRC fixed up");
        d = b;
        const uint32_t rim_flag = 3u;  // says tables follow, none do
        std::memcpy(&d[24], &rim_flag, 4u);
        fix_crc(d);
        expect_refused(parse_picto(d), "sizes", ".sbrp flag without tables, CRC fixed up");
        binary_damage(a, ".sbrp with colour check", parse_picto);
    }

    {
        // the gate (picto.h gate, gate_hidden, gate_threshold; flags bit 2): it loads
        // and saves back; a hidden layer above the maximum, a non-finite weight or a
        // truncated gate are refused
        sbr_host::Picto with = sbr_host::picto_from_view(pv);
        with.gate_hidden = 4u;
        with.gate.assign(SBR_PICTO_GATE_WEIGHTS(4u), 0.0f);
        for (size_t i = 0; i < with.gate.size(); ++i) with.gate[i] = 0.001f * float(i % 11u) - 0.005f;
        with.gate_threshold = -0.75f;
        with.bind();
        std::string a;
        expect(sbr_host::picto_bytes(with, a).empty(), "write with a gate");
        sbr_host::Picto back;
        expect(sbr_host::parse_picto(a, "gate.sbrp", back).empty() && back.gate == with.gate &&
                   back.gate_hidden == 4u && back.gate_threshold == -0.75f && back.view.gate != nullptr &&
                   back.view.gate_hidden == 4u,
               "the gate loads");
        std::string again;
        expect(sbr_host::picto_bytes(back, again).empty() && again == a, "the gate saves back byte for byte");
        const size_t hidden_at = a.size() - 4u - 4u * with.gate.size() - 8u;
        std::string d = a;
        const uint32_t too_many = SBR_PICTO_GATE_HIDDEN_MAX + 1u;
        std::memcpy(&d[hidden_at], &too_many, 4u);
        fix_crc(d);
        expect_refused(parse_picto(d), "sizes", ".sbrp gate with 33 hidden units, CRC fixed up");
        d = a;
        const float nan = std::numeric_limits<float>::quiet_NaN();
        std::memcpy(&d[a.size() - 8u], &nan, 4u);
        fix_crc(d);
        expect_refused(parse_picto(d), "values", ".sbrp gate weight NaN, CRC fixed up");
        d = a.substr(0, a.size() - 8u) + a.substr(a.size() - 4u);
        fix_crc(d);
        expect_refused(parse_picto(d), "sizes", ".sbrp gate one weight short, CRC fixed up");
        binary_damage(a, ".sbrp with a gate", parse_picto);
    }

    // ---- the part model with its class stage (.sbrm)
    std::string model;
    expect(sbr_host::model_bytes(sbr_host::model_from_view(mv, &pv), model).empty(), "write .sbrm");
    {
        sbr_host::Model m;
        expect(sbr_host::parse_model(model, "builtin.sbrm", m).empty(), "the intact .sbrm loads");
        std::string again;
        expect(sbr_host::model_bytes(m, again).empty() && again == model, "the .sbrm saves back byte for byte");
    }
    auto parse_model = [](const std::string &s) {
        sbr_host::Model m;
        return sbr_host::parse_model(s, "f.sbrm", m);
    };
    binary_damage(model, ".sbrm", parse_model);
    {
        // prototype count 0 and far too many, CRC fixed up: sizes
        for (uint32_t np : {0u, 70000u}) {
            std::string s = model;
            std::memcpy(&s[16], &np, 4u);
            fix_crc(s);
            expect_refused(parse_model(s), "sizes", ".sbrm prototype count " + std::to_string(np));
        }
        // class count 0 and above SBR_RECOG_MAX_CLASSES: sizes
        for (uint32_t k : {0u, SBR_RECOG_MAX_CLASSES + 1u}) {
            std::string s = model;
            std::memcpy(&s[24], &k, 4u);
            fix_crc(s);
            expect_refused(parse_model(s), "sizes", ".sbrm class count " + std::to_string(k));
        }
        // the vote error made NaN: the model check (values)
        std::string s = model;
        const float nan = NAN;
        std::memcpy(&s[28], &nan, 4u);
        fix_crc(s);
        expect_refused(parse_model(s), "values", ".sbrm NaN vote error, CRC fixed up");
        // the first class's outline out of range (after vote error, score threshold, the
        // group and class ranges): values
        s = model;
        s[36u + 2u * (SBR_MODEL_GROUPS + 1u) + 2u * (mv.class_count + 1u)] = 9;
        fix_crc(s);
        expect_refused(parse_model(s), "values", ".sbrm class outline 9, CRC fixed up");
        // the first descriptor (after the outlines): m, scale, cx, cy and 65 coefficients
        // whatever this build's SBR_FD_MAX_M, so files of any build have one layout; an
        // order above this build's SBR_FD_MAX_M, or a coefficient beyond it, is refused
        const size_t fd0 = 36u + 2u * (SBR_MODEL_GROUPS + 1u) + 2u * (mv.class_count + 1u) + mv.class_count;
        uint32_t m0 = 0u;
        std::memcpy(&m0, &model[fd0], 4u);
        expect(m0 == mv.fds[0].m, ".sbrm first descriptor record where the format puts it");
        expect(model.size() > fd0 + 16u + 65u * 8u, ".sbrm descriptor records of 65 coefficients");
        s = model;
        const uint32_t big = SBR_FD_MAX_M + 1u;
        std::memcpy(&s[fd0], &big, 4u);
        fix_crc(s);
        expect_refused(parse_model(s), "descriptors", ".sbrm descriptor order above SBR_FD_MAX_M");
        s = model;
        const float one = 1.0f;
        std::memcpy(&s[fd0 + 16u + 8u * (2u * SBR_FD_MAX_M + 1u)], &one, 4u);
        fix_crc(s);
        expect_refused(parse_model(s), "descriptors", ".sbrm coefficient beyond SBR_FD_MAX_M");
    }

    // ---- the tracker's text form
    sbr_host::TrackModel tm;
    tm.m = tv;
    tm.trans.assign(tv.transition, tv.transition + SBR_TRACK_MODEL_TRANSITION_LEN(tv.regions[0], tv.regions[1], tv.vel_count));
    tm.birth.assign(tv.birth, tv.birth + SBR_TRACK_MODEL_BIRTH_LEN(tv.regions[0], tv.regions[1], tv.vel_count));
    tm.bind();
    std::string text;
    expect(sbr_host::track_model_bytes(tm, text).empty(), "write the tracker model");
    auto parse_track = [](const std::string &s) {
        sbr_host::TrackModel t;
        return sbr_host::parse_track_model(s, "f.stm", t);
    };
    expect(parse_track(text).empty(), "the intact tracker model loads");
    auto with_crc = [](std::string body) {
        const size_t at = body.rfind("crc32 ");
        body.resize(at);
        char line[32];
        std::snprintf(line, sizeof line, "crc32 %08x\n", sbr_host::crc32_ieee(body.data(), body.size()));
        return body + line;
    };
    int tn = 0;
    for (size_t len = 0; len < text.size(); len += 1 + text.size() / 200u, ++tn) {
        const std::string e = parse_track(text.substr(0, len));
        expect(!e.empty(), "tracker model truncated to " + std::to_string(len) + " accepted");
        if (len > 40u) expect_refused(e, "crc", "tracker model truncated to " + std::to_string(len));
    }
    for (size_t pos = 40; pos + 16u < text.size(); pos += 1 + text.size() / 150u, ++tn) {
        std::string s = text;
        if (s[pos] == '\n') continue;
        s[pos] = (s[pos] == '7') ? '8' : '7';
        expect_refused(parse_track(s), "crc", "tracker model edited at " + std::to_string(pos));
    }
    {
        std::string s = text;
        s.replace(s.find(" 2\n"), 3, " 3\n");
        expect_refused(parse_track(with_crc(s)), "version", "tracker model version bumped");
        s = text;
        s.replace(0, 3, "xbr");
        expect_refused(parse_track(s), "magic", "tracker model foreign magic");
        // a transition entry made 5 (its row no longer a distribution), CRC fixed up
        s = text;
        const size_t row = s.find('\n', s.find("transition ")) + 1u;
        s.insert(row, "5");
        expect_refused(parse_track(with_crc(s)), "values", "tracker model row not a distribution");
        // the header's region count changed: the tables no longer match it
        s = text;
        const size_t rg = s.find("regions ");
        s.replace(rg, s.find('\n', rg) - rg, "regions 10 6");
        expect_refused(parse_track(with_crc(s)), "sizes", "tracker model header with other region counts");
        // a table count that swallows the next key: a malformed file
        s = text;
        const size_t b = s.find("birth ");
        s.replace(b, s.find('\n', b) - b, "birth 3");
        expect_refused(parse_track(with_crc(s)), "format", "tracker model birth table of 3");
        // a NaN entry, CRC fixed up
        s = text;
        s.insert(row, "nan ");
        const std::string e = parse_track(with_crc(s));
        expect(!e.empty(), "tracker model with a NaN entry accepted");
    }
    std::printf("tracker model: %zu bytes, %d truncations and edits refused\n", text.size(), tn);

    std::printf("model files: %d checks, %d failed\n", checks, failures);
    std::printf("%d passed, %d failed\n", checks - failures, failures);
    return failures == 0 ? 0 : 1;
}
