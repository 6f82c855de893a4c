// Shared by the binding files: statuses as exceptions.
#pragma once
#include <nanobind/nanobind.h>

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

void bind_tracker(nanobind::module_ &m);
void bind_shapes(nanobind::module_ &m);
void bind_can(nanobind::module_ &m);

}  // namespace sbr_py
