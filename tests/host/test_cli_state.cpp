// SPDX-License-Identifier: MIT
// test_cli_state: what the host tools' recogniser options record survives the parse. The
// tools parse their command line in a function whose CLI::App is gone afterwards; which
// options were given (the --min-score default of sbr_detect follows the operating point
// unless it was) and the class stage's looks must be answered from what the parse
// recorded, not from the App's options (an earlier version read a destroyed option: with
// --picto, --all-detections lost its 0.05 floor on some runs).
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cli.hpp"
#include "test_help.hpp"

using namespace sbr_host;

namespace {

int failures = 0;

void expect(bool ok, const char *what)
{
    std::printf("%s: %s\n", ok ? "ok" : "FAIL", what);
    failures += ok ? 0 : 1;
}

}  // namespace

int main(int argc, char **argv)
{
    const int h = test_help(argc, argv, "test_cli_state: the recogniser's options after the parse", "test_cli_state");
    if (h >= 0) return h;
    sbr_recog_config_t cfg;
    sbr_recog_config_default(&cfg);
    RecogCli r;
    LooksCli l;
    {
        CLI::App app{"test"};
        add_recog_options(app, cfg, r);
        add_look_options(app, l);
        std::vector<std::string> args = {"--views", "3",           "--nms-iou",      "0.4",
                                         "--map-polarity", "3,3", "--refine-score", "0.5"};
        std::vector<const char *> av = {"test"};
        for (const auto &a : args) av.push_back(a.c_str());
        app.parse(int(av.size()), const_cast<char **>(av.data()));
        apply_recog_cli(r, cfg);
        // the App, its options and their results end here
    }
    r.options.clear();
    expect(r.given("views") && r.given("nms_iou") && r.given("map_polarity"), "the given fields are recorded");
    expect(!r.given("min_score") && !r.given("max_parts") && !r.given("map_subsample"),
           "the others are not (min_score then follows the operating point)");
    expect(cfg.views == 3u && cfg.nms_iou == 0.4f, "the fields hold the values");
    expect(cfg.parts.map_polarity[0] == 3u && cfg.parts.map_polarity[1] == 3u && cfg.parts.map_polarity[2] == 0u,
           "a per-map list sets its first values");
    sbr_picto_model_t stage{};
    sbr_picto_looks_default(&stage.looks);
    apply_looks(l, stage);
    expect(stage.looks.refine_score == 0.5f && stage.looks.view_score == 0.1f && l.given.size() == 1u,
           "the given look, and only it, is applied");
    std::printf("test_cli_state: %s\n", failures == 0 ? "OK" : "FAILED");
    return failures == 0 ? 0 : 1;
}
