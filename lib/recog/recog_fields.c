/* SPDX-License-Identifier: MIT */
/*
 * The recogniser's configuration as one table (recog.h, sbr_recog_field_t): each field's
 * name, type, range, default and meaning, written here once. The defaults
 * (sbr_recog_config_default()), the check (sbr_recog_config_check_field()), the host
 * tools' options, the Python keywords and docs/usage/configuration.md all come from it;
 * tests/test_recog_fields.c, tests/python/test_cli.py and the Python package's tests fail
 * when one of them disagrees. Measurements behind the defaults: docs/results/.
 */
#include "recog_internal.h"

#include <stddef.h>
#include <string.h>

#define OFF(member) ((uint32_t)offsetof(sbr_recog_config_t, member))
#define NOTE_NONE 0u
#define U32 ((uint8_t)SBR_RECOG_FIELD_U32)
#define F32 ((uint8_t)SBR_RECOG_FIELD_F32)

/* A uint32_t field: name, member, range, default, flags, meaning. */
#define U(name, member, lo, hi, def, flags, help) \
    {#name, help, OFF(member), U32, 1u, (flags), (lo), (hi), {(def), 0u, 0u, 0u}, 0.0f, 0.0f, 0.0f}
/* One uint32_t per map kind (intensity, red, blue, yellow). */
#define A(name, member, lo, hi, d0, d1, d2, d3, flags, help) \
    {#name, help, OFF(member), U32, (uint8_t)SBR_MAP_KINDS, (flags), (lo), (hi), {(d0), (d1), (d2), (d3)}, \
     0.0f, 0.0f, 0.0f}
/* A float field. */
#define F(name, member, lo, hi, def, flags, help) \
    {#name, help, OFF(member), F32, 1u, (flags), 0u, 0u, {0u, 0u, 0u, 0u}, (lo), (hi), (def)}

#define LINKED SBR_RECOG_FIELD_LINKED
#define MAPS_ALL ((1u << SBR_MAP_KINDS) - 1u)
#define PI_F 3.14159265f

static const sbr_recog_field_t fields[] = {
    /* the part stage: maps, regions, contours, descriptors (parts.h, mser.h) */
    U(maps, parts.maps, 1u, MAPS_ALL, 0x7u, 0u,
      "map kinds used: bit k = sbr_map_kind_t k (1 intensity, 2 red, 4 blue, 8 yellow)"),
    U(subsample, parts.subsample, 1u, SBR_MAP_MAX_SUBSAMPLE, 1u, LINKED,
      "subsampling of every map (x map_subsample at most 8): 2 quarters time and memory"),
    A(map_subsample, parts.map_subsample, 1u, SBR_MAP_MAX_SUBSAMPLE, 1u, 1u, 2u, 1u, LINKED,
      "further subsampling per map kind (subsample x this at most 8)"),
    A(map_min_area, parts.map_min_area, 0u, 100000000u, 0u, 0u, 20u, 0u, LINKED,
      "smallest region per map kind, in its map's pixels (0: min_area; at most max_area)"),
    A(map_polarity, parts.map_polarity, 0u, 3u, 2u, 2u, 0u, 0u, 0u,
      "regions flooded per map kind: 0 polarity's, 1 dark, 2 bright, 3 both"),
    A(map_bright_min, parts.map_bright_min, 0u, 255u, 0u, 136u, 0u, 0u, 0u,
      "bright regions per map kind only from this level up (0: bright_min)"),
    A(map_dark_max, parts.map_dark_max, 0u, 255u, 0u, 0u, 120u, 0u, 0u,
      "dark regions per map kind only up to this level (0: dark_max)"),
    U(delta, parts.mser.delta, 1u, SBR_MSER_MAX_DELTA, SBR_RECOG_DEFAULT_DELTA, 0u,
      "MSER delta: levels a region's stability is measured over; smaller finds blurred signs"),
    U(min_area, parts.mser.min_area, 1u, 100000000u, 60u, LINKED,
      "smallest MSER region, pixels (at most max_area)"),
    U(max_area, parts.mser.max_area, 1u, 100000000u, 14400u, LINKED,
      "largest MSER region, pixels (at least min_area and every map_min_area)"),
    F(max_variation, parts.mser.max_variation, 1.0e-6f, 1.0e30f, 0.5f, 0u,
      "MSER stability bound: larger gives more, less stable regions"),
    F(min_diversity, parts.mser.min_diversity, 0.0f, 0.999999f, 0.2f, 0u,
      "nested regions less different than this are reported once"),
    U(polarity, parts.mser.polarity, 1u, 3u, 3u, 0u,
      "MSER polarities where map_polarity gives 0: 1 dark, 2 bright, 3 both"),
    U(max_nodes, parts.mser.max_nodes, 0u, 100000000u, SBR_PARTS_DEFAULT_MAX_NODES, 0u,
      "MSER tree nodes per map (0: the worst case); bounds the workspace"),
    U(dark_max, parts.mser.dark_max, 0u, 255u, 255u, 0u,
      "dark regions only up to this level where map_dark_max gives 0"),
    U(bright_min, parts.mser.bright_min, 0u, 255u, 0u, 0u,
      "bright regions only from this level up where map_bright_min gives 0"),
    U(max_heap, parts.mser.max_heap, 0u, 100000000u, SBR_PARTS_DEFAULT_MAX_HEAP, 0u,
      "MSER pixels waiting in the boundary heap at once (0: every pixel); bounds the workspace"),
    U(max_regions, parts.max_regions, 1u, 1000000u, SBR_PARTS_DEFAULT_MAX_REGIONS, 0u,
      "regions kept per map before the shape filters"),
    U(min_side, parts.min_side, 1u, 4096u, 6u, LINKED,
      "smallest box side of a region, map pixels (at most max_side)"),
    U(max_side, parts.max_side, 1u, 4096u, SBR_PARTS_DEFAULT_MAX_SIDE, LINKED,
      "largest box side of a region, map pixels (at least min_side)"),
    F(max_aspect, parts.max_aspect, 1.0f, 1.0e6f, 3.0f, 0u,
      "largest long / short box side of a region"),
    F(min_fill, parts.min_fill, 0.0f, 1.0f, 0.2f, 0u,
      "smallest region area / box area"),
    U(max_contour, parts.max_contour, 3u, 65536u, SBR_PARTS_DEFAULT_MAX_CONTOUR, 0u,
      "longest contour traced, points"),
    U(fd_n, parts.fd_n, 16u, 1024u, SBR_PARTS_DEFAULT_FD_N, LINKED,
      "descriptor resampling size N, a supported FFT size above 2 fd_m; must equal the model's"),
    U(fd_m, parts.fd_m, 1u, SBR_FD_MAX_M, SBR_PARTS_DEFAULT_FD_M, LINKED,
      "descriptor coefficients M (2M < fd_n, 2M < match_p); must equal the model's"),
    U(grey_polarity, grey_polarity, 0u, 3u, 0u, 0u,
      "the intensity map's polarities on a grey frame: 0 polarity's, 1 dark, 2 bright, 3 both"),
    /* matching and voting */
    U(match_p, match_p, 16u, 1024u, SBR_RECOG_DEFAULT_MATCH_P, LINKED,
      "correlation size P, a supported FFT size of at least 2 fd_m + 1"),
    U(max_parts, max_parts, 1u, 1000000u, SBR_RECOG_DEFAULT_MAX_PARTS, 0u,
      "parts kept per frame; bounds the workspace"),
    U(max_votes, max_votes, 1u, 4000000u, SBR_RECOG_DEFAULT_MAX_VOTES, 0u,
      "votes kept per frame; bounds the workspace"),
    U(max_hypotheses, max_hypotheses, 1u, 1000000u, SBR_RECOG_DEFAULT_MAX_HYPOTHESES, 0u,
      "hypotheses kept per frame; bounds the workspace"),
    U(max_model_protos, max_model_protos, 1u, 65535u, SBR_RECOG_DEFAULT_MAX_MODEL_PROTOS, 0u,
      "largest prototype library the workspace serves"),
    F(vote_error, vote_error, 0.0f, 4.0f, 0.0f, 0u,
      "largest descriptor error of a vote (0: the model's); larger: more recall, more clutter"),
    F(verify_error, verify_error, 1.0e-6f, 4.0f, 0.25f, 0u,
      "largest descriptor error of a part found by the cascade"),
    F(max_rotation, max_rotation, 1.0e-6f, PI_F, 0.35f, 0u,
      "largest rotation of a part against its prototype, radians"),
    F(min_size, min_size, 1.0f, 16384.0f, 12.0f, LINKED,
      "smallest predicted sign size, pixels (at most max_size)"),
    F(max_size, max_size, 1.0f, 16384.0f, 200.0f, LINKED,
      "largest predicted sign size, pixels (at least min_size)"),
    F(centre_tol, centre_tol, 1.0e-6f, 10.0f, 0.2f, 0u,
      "votes of one hypothesis: centres within this fraction of the size"),
    F(size_tol, size_tol, 0.0f, 10.0f, 0.3f, 0u,
      "votes of one hypothesis: sizes within a factor 1 + size_tol"),
    U(cascade_depth, cascade_depth, 0u, 65535u, 8u, 0u,
      "cascade prototypes looked for per hypothesis (0: no verification)"),
    U(min_parts, min_parts, 0u, 65535u, 1u, 0u,
      "distinct prototypes a hypothesis needs (2 without a class stage)"),
    F(candidate_score, candidate_score, 0.0f, 0.999999f, 0.0f, 0u,
      "part-score floor of a class-stage candidate"),
    U(max_candidates, max_candidates, 0u, 1000000u, 256u, 0u,
      "class-stage candidates per frame, best part score first; bounds its work"),
    /* the class stage (picto.h) */
    U(refine_steps, refine_steps, 0u, SBR_RECOG_MAX_REFINE, 2u, 0u,
      "box refinements by the class stage's regression (0: boxes stay)"),
    F(refine_first_score, refine_first_score, 0.0f, 1.0f, 0.01f, 0u,
      "sign probability at which the first refinement starts (colour frames)"),
    F(grey_refine_first_score, grey_refine_first_score, 0.0f, 1.0f, 0.0003f, 0u,
      "refine_first_score on a grey frame"),
    F(refine_score, refine_score, 0.0f, 1.0f, 0.001f, 0u,
      "sign probability to go on refining"),
    U(views, views, 1u, SBR_RECOG_MAX_VIEWS, 5u, 0u,
      "shifted views of the final box averaged by the class stage"),
    F(view_score, view_score, 0.0f, 1.0f, 0.1f, 0u,
      "sign probability for the extra views"),
    U(triangle_view, triangle_view, 0u, 1u, 1u, 0u,
      "1: look at a danger candidate's inner triangle once more"),
    F(triangle_score, triangle_score, 0.0f, 1.0f, 0.001f, 0u,
      "danger probability for the triangle view"),
    U(max_extra_looks, max_extra_looks, 0u, 1000000u, SBR_RECOG_DEFAULT_MAX_EXTRA_LOOKS, 0u,
      "class-stage looks per frame beyond each candidate's first; bounds its work"),
    F(min_score, min_score, 0.0f, 0.999999f, 0.3f, 0u,
      "score floor of a reported detection"),
    F(nms_iou, nms_iou, 1.0e-6f, 1.0f, 0.3f, 0u,
      "non-maximum suppression IoU"),
    F(candidate_iou, candidate_iou, 1.0e-6f, 1.0f, 1.0f, 0u,
      "suppression IoU among the candidates before the class stage (1: none)"),
    U(gate, gate, 0u, 1u, 1u, 0u,
      "1: the class stage's gate screens candidates first (when it has one)"),
    U(outline_maps, outline_maps, 0u, MAPS_ALL, 0x6u, 0u,
      "outline candidates: sign-shaped bright regions of these map kinds at their own box (0: none)"),
    U(max_outline_candidates, max_outline_candidates, 0u, 1000000u, SBR_RECOG_DEFAULT_MAX_OUTLINES, 0u,
      "outline candidates per frame"),
};

#define FIELD_COUNT ((uint32_t)(sizeof fields / sizeof fields[0]))

uint32_t sbr_recog_field_count(void)
{
    return FIELD_COUNT;
}

const sbr_recog_field_t *sbr_recog_field_at(uint32_t index)
{
    return (index < FIELD_COUNT) ? &fields[index] : NULL;
}

uint32_t sbr_recog_field_find(const char *name)
{
    uint32_t i;
    uint32_t found = SBR_RECOG_FIELD_NONE;
    if (name != NULL) {
        for (i = 0u; (i < FIELD_COUNT) && (found == SBR_RECOG_FIELD_NONE); i++) {
            if (strcmp(fields[i].name, name) == 0) {
                found = i;
            }
        }
    }
    return found;
}

/* Value k of field f in cfg (bytes copied: the table gives the offset). */
static uint32_t get_u(const sbr_recog_config_t *cfg, const sbr_recog_field_t *f, uint32_t k)
{
    uint32_t v;
    (void)memcpy(&v, &((const uint8_t *)cfg)[f->offset + (k * 4u)], sizeof v);
    return v;
}

static float get_f(const sbr_recog_config_t *cfg, const sbr_recog_field_t *f)
{
    float v;
    (void)memcpy(&v, &((const uint8_t *)cfg)[f->offset], sizeof v);
    return v;
}

void sbr_recog_priv_fields_default(sbr_recog_config_t *cfg)
{
    uint32_t i;
    uint32_t k;
    for (i = 0u; i < FIELD_COUNT; i++) {
        const sbr_recog_field_t *f = &fields[i];
        uint8_t *at = &((uint8_t *)cfg)[f->offset];
        if (f->kind == F32) {
            (void)memcpy(at, &f->def_f, sizeof f->def_f);
        } else {
            for (k = 0u; k < f->count; k++) {
                (void)memcpy(&at[k * 4u], &f->def_u[k], sizeof f->def_u[k]);
            }
        }
    }
}

/* Whether the field's values are within its range (false for NaN). */
static int in_table_range(const sbr_recog_config_t *cfg, const sbr_recog_field_t *f)
{
    int ok = 1;
    uint32_t k;
    if (f->kind == F32) {
        const float v = get_f(cfg, f);
        ok = ((v >= f->lo_f) && (v <= f->hi_f)) ? 1 : 0;
    } else {
        for (k = 0u; k < f->count; k++) {
            const uint32_t v = get_u(cfg, f, k);
            if ((v < f->lo_u) || (v > f->hi_u)) {
                ok = 0;
            }
        }
    }
    return ok;
}

/* The rules between fields (SBR_RECOG_FIELD_LINKED), each blamed on one field by name. */
static int links_ok(const sbr_recog_config_t *cfg, const char *name)
{
    const sbr_parts_config_t *p = &cfg->parts;
    int ok = 1;
    uint32_t k;
    if (strcmp(name, "map_subsample") == 0) {
        for (k = 0u; k < SBR_MAP_KINDS; k++) {
            if ((p->subsample * p->map_subsample[k]) > SBR_MAP_MAX_SUBSAMPLE) {
                ok = 0;
            }
        }
    } else if (strcmp(name, "map_min_area") == 0) {
        for (k = 0u; k < SBR_MAP_KINDS; k++) {
            if (p->map_min_area[k] > p->mser.max_area) {
                ok = 0;
            }
        }
    } else if (strcmp(name, "max_area") == 0) {
        ok = (p->mser.max_area >= p->mser.min_area) ? 1 : 0;
    } else if (strcmp(name, "max_side") == 0) {
        ok = (p->max_side >= p->min_side) ? 1 : 0;
    } else if (strcmp(name, "fd_n") == 0) {
        ok = (sbr_fft_size_supported(p->fd_n) != 0) ? 1 : 0;
    } else if (strcmp(name, "fd_m") == 0) {
        ok = ((2u * p->fd_m) < p->fd_n) ? 1 : 0;
    } else if (strcmp(name, "match_p") == 0) {
        ok = ((sbr_fft_size_supported(cfg->match_p) != 0) && (cfg->match_p >= ((2u * p->fd_m) + 1u)))
                 ? 1
                 : 0;
    } else if (strcmp(name, "max_size") == 0) {
        ok = (cfg->max_size >= cfg->min_size) ? 1 : 0;
    } else {
        /* the other linked fields are blamed through their partner */
    }
    return ok;
}

uint32_t sbr_recog_config_check_field(const sbr_recog_config_t *cfg)
{
    uint32_t i;
    uint32_t bad = SBR_RECOG_FIELD_NONE;
    if (cfg != NULL) {
        /* every range first, so that the links compare values in range */
        for (i = 0u; (i < FIELD_COUNT) && (bad == SBR_RECOG_FIELD_NONE); i++) {
            if (in_table_range(cfg, &fields[i]) == 0) {
                bad = i;
            }
        }
        for (i = 0u; (i < FIELD_COUNT) && (bad == SBR_RECOG_FIELD_NONE); i++) {
            if (((fields[i].flags & LINKED) != 0u) && (links_ok(cfg, fields[i].name) == 0)) {
                bad = i;
            }
        }
    }
    return bad;
}
