// SPDX-License-Identifier: MIT
#include "cli.hpp"

namespace sbr_host {

CLI::Option *add_range_option(CLI::App &app, ImageRanges &out, const std::string &what, const std::string &name) {
    return app
        .add_option_function<std::string>(
            name,
            [&out, name](const std::string &s) {
                if (!parse_image_ranges(s, out))
                    throw CLI::ValidationError(name, "wants A-B[,C-D...] with 0 <= A <= B <= " +
                                                              std::to_string(kMaxImageNumber) + ", got '" + s + "'");
            },
            what)
        ->type_name("A-B[,C-D]");
}

void add_recog_options(CLI::App &app, sbr_recog_config_t &cfg, RecogCli &r) {
    const std::string g = "Recogniser (include/sbr/recog.h; defaults of sbr_recog_config_default())";
    auto u = [&](const char *name, uint32_t &field, uint32_t lo, uint32_t hi, const char *what) {
        app.add_option(name, field, what)->check(CLI::Range(lo, hi))->capture_default_str()->group(g);
    };
    auto f = [&](const char *name, float &field, double lo, double hi, const char *what) {
        app.add_option(name, field, what)->check(finite_range(lo, hi))->capture_default_str()->group(g);
    };
    r.min_score = app.add_option("--min-score", cfg.min_score,
                                 "score floor of a detection (default: the operating point, or 0.05 "
                                 "with --all-detections)")
                      ->check(finite_range(0.0, 0.999999))
                      ->group(g);
    u("--min-parts", cfg.min_parts, 0u, 65535u, "parts a hypothesis needs");
    f("--vote-error", cfg.vote_error, 0.0, 4.0, "largest FD error of a vote (0: the model's)");
    f("--verify-error", cfg.verify_error, 1e-6, 4.0, "largest FD error in the cascade");
    u("--refine-steps", cfg.refine_steps, 0u, SBR_RECOG_MAX_REFINE, "class-stage box refinements");
    f("--refine-first-score", cfg.refine_first_score, 0.0, 1.0,
      "sign probability to start refining (colour frames)");
    f("--grey-refine-first-score", cfg.grey_refine_first_score, 0.0, 1.0,
      "sign probability to start refining on a grey frame");
    f("--refine-score", cfg.refine_score, 0.0, 1.0, "sign probability to go on refining");
    u("--views", cfg.views, 1u, SBR_RECOG_MAX_VIEWS, "views averaged by the class stage");
    f("--view-score", cfg.view_score, 0.0, 1.0, "sign probability for the extra views");
    u("--triangle-view", cfg.triangle_view, 0u, 1u, "1: classify the inner triangle of danger candidates");
    f("--triangle-score", cfg.triangle_score, 0.0, 1.0, "danger probability for the triangle view");
    f("--candidate-score", cfg.candidate_score, 0.0, 0.999999, "part-evidence floor of a class-stage candidate");
    f("--candidate-iou", cfg.candidate_iou, 1e-6, 1.0, "suppression before the class stage (1: none)");
    u("--max-candidates", cfg.max_candidates, 0u, 1000000u, "class-stage candidate bound");
    u("--max-extra-looks", cfg.max_extra_looks, 0u, 1000000u,
      "class-stage looks per frame beyond each candidate's first");
    u("--max-parts", cfg.max_parts, 1u, 1000000u, "part bound");
    u("--max-votes", cfg.max_votes, 1u, 4000000u, "vote bound");
    u("--max-hypotheses", cfg.max_hypotheses, 1u, 1000000u, "hypothesis bound");
    u("--gate", cfg.gate, 0u, 1u, "0: class stage's gate off (used when the class stage has one)");
    u("--outline-maps", cfg.outline_maps, 0u, (1u << SBR_MAP_KINDS) - 1u,
      "outline candidates: bright regions of these maps (bit k = map kind k) at their own box (0: none)");
    u("--max-outline-candidates", cfg.max_outline_candidates, 0u, 1000000u, "outline candidates per frame");
    u("--maps", cfg.parts.maps, 1u, (1u << SBR_MAP_KINDS) - 1u,
      "parts.maps: bit k = map kind k of include/sbr/map.h (0x1 intensity only)");
    u("--max-nodes", cfg.parts.mser.max_nodes, 0u, 100000000u, "MSER tree nodes (0: the worst case)");
    u("--max-heap", cfg.parts.mser.max_heap, 0u, 100000000u,
      "MSER pixels waiting in the boundary heap at once (0: the worst case, every pixel)");
    u("--subsample", cfg.parts.subsample, 1u, SBR_MAP_MAX_SUBSAMPLE, "parts.subsample of every map");
    u("--grey-polarity", cfg.grey_polarity, 0u, 3u,
      "the intensity map's polarities on a grey frame (0: parts.mser's, 1 dark, 2 bright, 3 both)");
    add_front_end_options(app, r.front_end, g);
}

void add_front_end_options(CLI::App &app, FrontEnd &fe, const std::string &group) {
    // one value per map kind, in the order intensity, red, blue, yellow
    auto per_kind = [&](const char *name, std::vector<unsigned> &values, unsigned lo, unsigned hi, const char *what) {
        app.add_option(name, values, what)
            ->delimiter(',')
            ->expected(1, int(SBR_MAP_KINDS))
            ->check(CLI::Range(lo, hi))
            ->type_name("I[,R[,B[,Y]]]")
            ->group(group);
    };
    per_kind("--map-subsample", fe.sub, 1u, SBR_MAP_MAX_SUBSAMPLE,
             "parts.map_subsample per kind, in the order intensity, red, blue, yellow");
    per_kind("--map-min-area", fe.area, 0u, 100000000u, "parts.map_min_area per kind (0: the MSER default), same order");
    per_kind("--map-polarity", fe.polarity, 0u, 3u,
             "parts.map_polarity per kind (0: parts.mser's, 1 dark, 2 bright, 3 both), same order");
    per_kind("--map-bright-min", fe.bright_min, 0u, 255u,
             "parts.map_bright_min per kind: bright regions from this level up (0: parts.mser's), same order");
    per_kind("--map-dark-max", fe.dark_max, 0u, 255u,
             "parts.map_dark_max per kind: dark regions up to this level (0: parts.mser's), same order");
}

void apply_recog_cli(const RecogCli &r, sbr_recog_config_t &cfg) { apply_front_end(r.front_end, cfg.parts); }

}  // namespace sbr_host
