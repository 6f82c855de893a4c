// SPDX-License-Identifier: MIT
// Command-line options of the host tools, through CLI11 (Debian libcli11-dev): one parser
// for every tool, so each accepts --help (exit 0, every option described) and refuses a
// malformed or out-of-range value with the option's name (exit 2).
#pragma once

#include "cli_core.hpp"

#include <map>
#include <set>
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

// The recogniser's options: one per field of the configuration's table (recog.h,
// sbr_recog_field_at(): --name with '-' for '_', its range, its one-line meaning), bound to
// the fields of `cfg` (which holds the defaults, shown by --help), in an option group
// "Recogniser". Nothing here repeats a range or a default.
struct RecogCli {
    std::map<std::string, CLI::Option *> options;  // by field name, valid while the App lives
    std::set<std::string> given_fields;            // the fields given on the command line
    FrontEnd front_end;                            // the per-map-kind lists (--map-*)
    bool given(const std::string &field) const {
        if (given_fields.count(field) != 0) return true;
        const auto l = front_end.lists.find(field);
        return l != front_end.lists.end() && !l->second.empty();
    }
};
void add_recog_options(CLI::App &app, sbr_recog_config_t &cfg, RecogCli &r);
// The table's per-map-kind fields (--map-subsample, --map-min-area, ...) into fe, in option
// group `group` (the training tools: the part stage they learn with).
void add_front_end_options(CLI::App &app, FrontEnd &fe, const std::string &group = "");
// What add_recog_options() cannot bind directly (the per-map lists).
void apply_recog_cli(const RecogCli &r, sbr_recog_config_t &cfg);
// The class stage's looks (picto.h, sbr_picto_look_field_at()): options that override the
// values of the class stage in use (its model's, by default; --help says so).
struct LooksCli {
    std::map<std::string, float> given;  // the looks given on the command line, by name
};
// `written`: the trainer's options (the looks it writes into the model, default the
// table's) instead of a tool's overrides of the class stage in use.
void add_look_options(CLI::App &app, LooksCli &l, bool written = false);
// The given looks into a copy of the class stage (its tables stay borrowed).
void apply_looks(const LooksCli &l, sbr_picto_model_t &stage);
// A field's range as the table gives it ("0 .. 255").
std::string field_range(const sbr_field_t &f);
// "" for a configuration the core accepts; otherwise the option to blame, its value, its
// range and its meaning (sbr_recog_config_check_field()).
std::string config_problem(const sbr_recog_config_t &cfg);

}  // namespace sbr_host
