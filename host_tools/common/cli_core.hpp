// SPDX-License-Identifier: MIT
// The CLI11 helpers every host tool uses (header only; common/cli.hpp adds the
// recogniser's options and image ranges for the tools that link sbr_host_common).
#pragma once

#include <CLI/CLI.hpp>

#include <cmath>
#include <string>

namespace sbr_host {

// Parse argv: -1 to go on; otherwise the exit status (0 after --help, 2 after a usage
// error, whose message CLI11 has printed with the option's name).
inline int parse_cli(CLI::App &app, int argc, char **argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        const int rc = app.exit(e);
        return rc == 0 ? 0 : 2;
    }
    return -1;
}

// A finite value in [lo, hi] (CLI::Range lets NaN through).
inline CLI::Validator finite_range(double lo, double hi) {
    const std::string range = "[" + CLI::detail::to_string(lo) + ", " + CLI::detail::to_string(hi) + "]";
    return CLI::Validator(
        [range, lo, hi](std::string &s) -> std::string {
            double v = 0.0;
            if (!CLI::detail::lexical_cast(s, v) || !std::isfinite(v) || v < lo || v > hi)
                return "value " + s + " is not a finite number in " + range;
            return std::string();
        },
        "in " + range);
}

}  // namespace sbr_host
