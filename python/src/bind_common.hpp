// SPDX-License-Identifier: MIT
// Shared by the binding files: statuses as exceptions.
#pragma once
#include <nanobind/nanobind.h>

#include <cstring>
#include <stdexcept>
#include <string>

extern "C" {
#include "sbr/status.h"
}

namespace sbr_py {

// ValueError for bad input (NULL never reaches the core from Python; sizes, ranges,
// degenerate data), RuntimeError for corrupted state.
[[noreturn]] inline void raise_status(const char *what, sbr_status_t st) {
    const std::string m = std::string(what) + ": " + sbr_status_str(st);
    if (st == SBR_ERR_CORRUPT || st == SBR_ERR_STATE) throw std::runtime_error(m);
    throw nanobind::value_error(m.c_str());
}

inline void check(const char *what, sbr_status_t st) {
    if (st != SBR_OK) raise_status(what, st);
}

// A configuration the core refused with `st`: ValueError naming the first given field
// that the core also refuses alone on the defaults (`defaults(cfg)` fills them,
// `set(cfg, name, value)` writes one field, `check(cfg)` is the core's check), or naming
// the combination when each alone is accepted. `who`: "the recogniser"; `header`: where
// the ranges are documented.
template <typename Cfg, typename Defaults, typename Set, typename Check>
[[noreturn]] void refuse_config(nanobind::dict given, sbr_status_t st, const std::string &who,
                                const std::string &header, Defaults defaults, Set set, Check check) {
    for (auto kv : given) {
        Cfg one;
        defaults(one);
        const std::string name = nanobind::cast<std::string>(kv.first);
        set(one, name, kv.second);
        if (check(one) != SBR_OK)
            throw nanobind::value_error(
                (name + ": refused by " + who + " (" + sbr_status_str(st) + "; " + header + " gives its range)").c_str());
    }
    throw nanobind::value_error(
        ("configuration: refused by " + who + " (" + sbr_status_str(st) + "): these fields together").c_str());
}

// A configuration struct's field by name: float or uint32_t at `offset` (the tracker's and
// the sign tracking's keyword arguments).
struct ConfigField {
    const char *name;
    bool is_float;
    size_t offset;
};

// Sets field `name` of the struct at `cfg` from `value` (a non-negative whole number for a
// uint32_t field); ValueError for an unknown name (`what`: "tracker") or a bad value.
template <size_t N>
void set_config_field(void *cfg, const ConfigField (&fields)[N], const std::string &name, double value,
                      const char *what) {
    for (const ConfigField &f : fields) {
        if (name != f.name) continue;
        unsigned char *base = static_cast<unsigned char *>(cfg) + f.offset;
        if (f.is_float) {
            const float v = static_cast<float>(value);
            std::memcpy(base, &v, sizeof v);
        } else {
            if (!(value >= 0.0 && value <= 4294967295.0) || value != double(uint32_t(value)))
                throw nanobind::value_error((name + ": a non-negative integer is needed").c_str());
            const uint32_t u = uint32_t(value);
            std::memcpy(base, &u, sizeof u);
        }
        return;
    }
    throw nanobind::value_error((std::string("unknown ") + what + " field: " + name).c_str());
}

// The fields of the struct at `cfg` as a dict.
template <size_t N>
nanobind::dict config_dict(const void *cfg, const ConfigField (&fields)[N]) {
    nanobind::dict d;
    for (const ConfigField &f : fields) {
        const unsigned char *base = static_cast<const unsigned char *>(cfg) + f.offset;
        if (f.is_float) {
            float v;
            std::memcpy(&v, base, sizeof v);
            d[f.name] = double(v);
        } else {
            uint32_t u;
            std::memcpy(&u, base, sizeof u);
            d[f.name] = u;
        }
    }
    return d;
}

void bind_tracker(nanobind::module_ &m);
void bind_shapes(nanobind::module_ &m);
void bind_can(nanobind::module_ &m);
void bind_signs(nanobind::module_ &m);
void bind_eval(nanobind::module_ &m);

}  // namespace sbr_py
