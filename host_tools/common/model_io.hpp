// SPDX-License-Identifier: MIT
// Prototype libraries on the host: the file form (load/save) and the generated C table.
//
// File form (.sbrm), little-endian, host struct layout of the core's types:
//   "SBRM" | u32 version | u32 fd_n | u32 fd_m | u32 proto_count | u32 cascade_count |
//   u32 class_count (K) | f32 vote_error | f32 score_threshold | u16 group_first[9] |
//   u16 class_first[K + 1] | u8 class_outline[K] |
//   sbr_fd_t fds[proto_count] | sbr_model_proto_t protos[proto_count] |
//   u16 cascade[cascade_count] | u32 picto (0: no class stage, else hidden + 1) |
//   [f32 threshold | u32 flags | f32 looks[5] with bit 3 | the class stage's weights and tables as in .sbrp, for
//   K classes] |
//   u32 CRC-32 (IEEE) of every byte before it.
// A loaded model is checked with sbr_model_check() as well.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

extern "C" {
#include "sbr/picto.h"
#include "sbr/recog.h"
#include "sbr/models.h"
}

namespace sbr_host {

// The core's field tables as vectors: the recogniser's configuration (recog.h) and the
// class stage's looks (picto.h).
inline std::vector<sbr_field_t> recog_fields() {
    std::vector<sbr_field_t> v(sbr_recog_field_count());
    for (uint32_t i = 0; i < v.size(); ++i) sbr_recog_field_at(i, &v[i]);
    return v;
}
inline std::vector<sbr_field_t> look_fields() {
    std::vector<sbr_field_t> v(sbr_picto_look_field_count());
    for (uint32_t i = 0; i < v.size(); ++i) sbr_picto_look_field_at(i, &v[i]);
    return v;
}

inline sbr_picto_looks_t default_looks() {
    sbr_picto_looks_t l;
    sbr_picto_looks_default(&l);
    return l;
}

// Owns the weights a sbr_picto_model_t points into (the class stage, picto.h).
// File form (.sbrp), little-endian: "SBRP" | u32 version | u32 features | u32 hidden |
//   u32 classes (K) | f32 threshold | u32 flags (bit 0: box regression, bit 1: colour
//   check, bit 2: gate, bit 3: looks) |
//   f32 looks[5] (sbr_picto_looks_t's order) with bit 3 (format 3 files have none: read
//   with sbr_picto_looks_default()) |
//   f32 w1[hidden * (features + 1)] | f32 w2[(K + 1) * (hidden or features, + 1)] |
//   f32 w3[4 * (hidden or features, + 1)] with bit 0 |
//   u8 rim_shape[K] | f32 rim_floor[K] with bit 1 |
//   u32 gate_hidden | f32 gate_threshold | f32 gate[SBR_PICTO_GATE_WEIGHTS(gate_hidden)]
//   with bit 2 |
//   u32 CRC-32 (IEEE) of every byte before it. Checked with sbr_picto_check() as well.
struct Picto {
    uint32_t hidden = 0;
    uint32_t classes = 0;  // sign classes (outputs: classes + 1)
    float threshold = 0.5f;
    sbr_picto_looks_t looks = default_looks();  // the recogniser's looks with it (picto.h)
    std::vector<float> w1, w2, w3;  // w3 empty: no box regression
    std::vector<uint8_t> rim_shape;  // colour check (picto.h): empty or `classes` entries each
    std::vector<float> rim_floor;
    std::vector<float> gate;  // the class stage's gate (picto.h): empty or its weights
    uint32_t gate_hidden = 0;
    float gate_threshold = 0.0f;
    sbr_picto_model_t view{};  // pointers refreshed by bind()
    void bind();
};

// Owns the arrays a sbr_model_t points into.
struct Model {
    std::vector<sbr_fd_t> fds;
    std::vector<sbr_model_proto_t> protos;
    std::vector<uint16_t> cascade;
    bool has_picto = false;
    Picto picto;  // the class stage, when has_picto
    sbr_model_t view{};  // pointers refreshed by bind()
    void bind();
    // The class stage for sbr_recog_init(): nullptr without one.
    const sbr_picto_model_t *picto_view() const { return has_picto ? &picto.view : nullptr; }
};

// Copies of a model held elsewhere (e.g. the built-in tables), owning their arrays.
// `picto` (nullptr or version 0: none) becomes the model's class stage.
Model model_from_view(const sbr_model_t &v, const sbr_picto_model_t *picto);
Picto picto_from_view(const sbr_picto_model_t &v);

// CRC-32/IEEE (the file forms' checksum).
uint32_t crc32_ieee(const void *data, size_t n);

// Returns "" on success, else the reason (naming the check that failed: magic, version,
// crc, sizes, values).
std::string save_model(const Model &m, const std::string &path);
std::string model_bytes(const Model &m, std::string &bytes);
std::string load_model(const std::string &path, Model &m);
// The same from the file's bytes (`name` for messages).
std::string parse_model(const std::string &bytes, const std::string &name, Model &m);
// The generated C source (const tables and sbr_model_gtsdb(), which fills a caller's struct); `header` lines go into the
// file's leading comment.
std::string write_model_c(const Model &m, const std::string &path, const std::string &header);

std::string save_picto(const Picto &p, const std::string &path);
std::string picto_bytes(const Picto &p, std::string &bytes);
std::string load_picto(const std::string &path, Picto &p);
std::string parse_picto(const std::string &bytes, const std::string &name, Picto &p);
// The generated C source: const tables and sbr_picto_gtsdb().
std::string write_picto_c(const Picto &p, const std::string &path, const std::string &header);

// Reports the outcome of one of the writers above on stderr ("TOOL: wrote PATH" or
// "TOOL: ERROR"); returns false on error.
bool report_write(const char *tool, const std::string &path, const std::string &error);

// Every map of parts at full resolution with the MSER defaults' region bound: how the
// prototype library is learned (sbr_train) and how the class stage's training candidates
// are found (sbr_train_picto), whatever resolution the recogniser runs a map at
// (descriptors are scale-normalised; parts.h map_subsample, map_min_area, map_polarity, map_bright_min, map_dark_max).
void parts_at_full_resolution(sbr_parts_config_t &parts);

// The work bounds the trainers' recogniser runs with: at most 4096 parts, every pixel
// room in the MSER's boundary heap, no budget of extra class-stage looks (the table's
// largest). The runtime's defaults (docs/usage/configuration.md) bound an ECU's worst
// case; on the trainers' configurations (every map at full resolution, every candidate
// refined) they would cut training images' parts and candidates, and the shipped models
// were learned without them (./sbr.sh train reproduces lib/models byte for byte).
void training_bounds(sbr_recog_config_t &rc);

// Part-stage options a trainer learns with instead of full resolution (the options of
// sbr_detect of the same names): --map-subsample, --map-min-area, --map-polarity, --map-bright-min, --map-dark-max I[,R,B,Y].
// The per-map-kind fields of the configuration's table given on a command line (field name
// -> the first 1..4 values, in the order intensity, red, blue, yellow).
struct FrontEnd {
    std::map<std::string, std::vector<unsigned>> lists;
};
void apply_front_end(const FrontEnd &fe, sbr_parts_config_t &parts);

}  // namespace sbr_host
