// SPDX-License-Identifier: MIT
// Command-line options of the host tools, through CLI11 (Debian libcli11-dev): one parser
// for every tool, so each accepts --help (exit 0, every option described) and refuses a
// malformed or out-of-range value with the option's name (exit 2).
#pragma once

#include "cli_core.hpp"

#include <string>

#include "gtsdb.hpp"
#include "model_io.hpp"

extern "C" {
#include "sbr/recog.h"
}

namespace sbr_host {

// --range A-B[,C-D...]: image numbers (strict: digits only, A <= B, no overflow).
CLI::Option *add_range_option(CLI::App &app, ImageRanges &out, const std::string &what,
                              const std::string &name = "--range");

// The recogniser's options that the tools let a user override, bound to the fields of
// `cfg` (which holds the defaults, shown by --help), in an option group "Recogniser".
struct RecogCli {
    CLI::Option *min_score = nullptr;  // given explicitly? (tools lower the floor otherwise)
    FrontEnd front_end;                // --map-subsample, --map-min-area, --map-polarity
};
void add_recog_options(CLI::App &app, sbr_recog_config_t &cfg, RecogCli &r);
// --map-subsample, --map-min-area and --map-polarity (per map kind) into fe, in option group `group`.
void add_front_end_options(CLI::App &app, FrontEnd &fe, const std::string &group = "");
// What add_recog_options() cannot bind directly (the per-map lists).
void apply_recog_cli(const RecogCli &r, sbr_recog_config_t &cfg);

}  // namespace sbr_host
