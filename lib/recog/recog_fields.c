/* SPDX-License-Identifier: MIT */
/*
 * The recogniser's configuration as one table (recog.h, sbr_field_t): each field's
 * name, type, range, default and meaning, written here once. The defaults
 * (sbr_recog_config_default()), the check (sbr_recog_config_check_field()), the host
 * tools' options, the Python keywords and docs/usage/configuration.md all come from it;
 * tests/test_recog_fields.c, tests/python/test_cli.py and the Python package's tests fail
 * when one of them disagrees. Measurements behind the defaults: docs/results/.
 */
#include "recog_internal.h"

#include <stddef.h>
#include <string.h>

/* The table, once: X_U(name, member, lo, hi, default, flags, meaning) for a uint32_t,
   X_A(name, member, lo, hi, four defaults, flags, meaning) for one uint32_t per map kind
   (intensity, red, blue, yellow), X_F(...) for a float. Expanded twice below: the numbers
   (used by the defaults and the check) and the texts (names and meanings, used only by
   the field functions, so a target that calls only the check links no strings). Neither
   holds a pointer: the core keeps no relocated data. */
#define RECOG_FIELDS(X_U, X_A, X_F) \
    /* the part stage: maps, regions, contours, descriptors (parts.h, mser.h) */ \
    X_U(maps, parts.maps, 1u, MAPS_ALL, 0x7u, 0u, \
      "map kinds used: bit k = sbr_map_kind_t k (1 intensity, 2 red, 4 blue, 8 yellow)") \
    X_U(subsample, parts.subsample, 1u, SBR_MAP_MAX_SUBSAMPLE, 1u, LINKED, \
      "subsampling of every map (x map_subsample at most 8): 2 quarters time and memory") \
    X_A(map_subsample, parts.map_subsample, 1u, SBR_MAP_MAX_SUBSAMPLE, 1u, 1u, 2u, 1u, LINKED, \
      "further subsampling per map kind (subsample x this at most 8)") \
    X_A(map_min_area, parts.map_min_area, 0u, 100000000u, 0u, 0u, 20u, 0u, LINKED, \
      "smallest region per map kind, in its map's pixels (0: min_area; at most max_area)") \
    X_A(map_polarity, parts.map_polarity, 0u, 3u, 2u, 2u, 0u, 0u, 0u, \
      "regions flooded per map kind: 0 polarity's, 1 dark, 2 bright, 3 both") \
    X_A(map_bright_min, parts.map_bright_min, 0u, 255u, 0u, 136u, 0u, 0u, 0u, \
      "bright regions per map kind only from this level up (0: bright_min)") \
    X_A(map_dark_max, parts.map_dark_max, 0u, 255u, 0u, 0u, 120u, 0u, 0u, \
      "dark regions per map kind only up to this level (0: dark_max)") \
    X_U(delta, parts.mser.delta, 1u, SBR_MSER_MAX_DELTA, SBR_RECOG_DEFAULT_DELTA, 0u, \
      "MSER delta: levels a region's stability is measured over; smaller finds blurred signs") \
    X_U(min_area, parts.mser.min_area, 1u, 100000000u, 60u, LINKED, \
      "smallest MSER region, pixels (at most max_area)") \
    X_U(max_area, parts.mser.max_area, 1u, 100000000u, 14400u, LINKED, \
      "largest MSER region, pixels (at least min_area and every map_min_area)") \
    X_F(max_variation, parts.mser.max_variation, 1.0e-6f, 1.0e30f, 0.5f, 0u, \
      "MSER stability bound: larger gives more, less stable regions") \
    X_F(min_diversity, parts.mser.min_diversity, 0.0f, 0.999999f, 0.2f, 0u, \
      "nested regions less different than this are reported once") \
    X_U(polarity, parts.mser.polarity, 1u, 3u, 3u, 0u, \
      "MSER polarities where map_polarity gives 0: 1 dark, 2 bright, 3 both") \
    X_U(max_nodes, parts.mser.max_nodes, 0u, 100000000u, SBR_PARTS_DEFAULT_MAX_NODES, 0u, \
      "MSER tree nodes per map (0: the worst case); bounds the workspace") \
    X_U(dark_max, parts.mser.dark_max, 0u, 255u, 255u, 0u, \
      "dark regions only up to this level where map_dark_max gives 0") \
    X_U(bright_min, parts.mser.bright_min, 0u, 255u, 0u, 0u, \
      "bright regions only from this level up where map_bright_min gives 0") \
    X_U(max_heap, parts.mser.max_heap, 0u, 100000000u, SBR_PARTS_DEFAULT_MAX_HEAP, 0u, \
      "MSER pixels waiting in the boundary heap at once (0: every pixel); bounds the workspace") \
    X_U(max_regions, parts.max_regions, 1u, 1000000u, SBR_PARTS_DEFAULT_MAX_REGIONS, 0u, \
      "regions kept per map before the shape filters") \
    X_U(min_side, parts.min_side, 1u, 4096u, 6u, LINKED, \
      "smallest box side of a region, map pixels (at most max_side)") \
    X_U(max_side, parts.max_side, 1u, 4096u, SBR_PARTS_DEFAULT_MAX_SIDE, LINKED, \
      "largest box side of a region, map pixels (at least min_side)") \
    X_F(max_aspect, parts.max_aspect, 1.0f, 1.0e6f, 3.0f, 0u, \
      "largest long / short box side of a region") \
    X_F(min_fill, parts.min_fill, 0.0f, 1.0f, 0.2f, 0u, \
      "smallest region area / box area") \
    X_U(max_contour, parts.max_contour, 3u, 65536u, SBR_PARTS_DEFAULT_MAX_CONTOUR, 0u, \
      "longest contour traced, points") \
    X_U(fd_n, parts.fd_n, 16u, 1024u, SBR_PARTS_DEFAULT_FD_N, LINKED, \
      "descriptor resampling size N, a supported FFT size above 2 fd_m; must equal the model's") \
    X_U(fd_m, parts.fd_m, 1u, SBR_FD_MAX_M, SBR_PARTS_DEFAULT_FD_M, LINKED, \
      "descriptor coefficients M (2M < fd_n, 2M < match_p); must equal the model's") \
    X_U(grey_polarity, grey_polarity, 0u, 3u, 0u, 0u, \
      "the intensity map's polarities on a grey frame: 0 polarity's, 1 dark, 2 bright, 3 both") \
    /* matching and voting */ \
    X_U(match_p, match_p, 16u, 1024u, SBR_RECOG_DEFAULT_MATCH_P, LINKED, \
      "correlation size P, a supported FFT size of at least 2 fd_m + 1") \
    X_U(max_parts, max_parts, 1u, 1000000u, SBR_RECOG_DEFAULT_MAX_PARTS, 0u, \
      "parts kept per frame; bounds the workspace") \
    X_U(max_votes, max_votes, 1u, 4000000u, SBR_RECOG_DEFAULT_MAX_VOTES, 0u, \
      "votes kept per frame; bounds the workspace") \
    X_U(max_hypotheses, max_hypotheses, 1u, 1000000u, SBR_RECOG_DEFAULT_MAX_HYPOTHESES, 0u, \
      "hypotheses kept per frame; bounds the workspace") \
    X_U(max_model_protos, max_model_protos, 1u, 65535u, SBR_RECOG_DEFAULT_MAX_MODEL_PROTOS, 0u, \
      "largest prototype library the workspace serves") \
    X_F(vote_error, vote_error, 0.0f, 4.0f, 0.0f, 0u, \
      "largest descriptor error of a vote (0: the model's); larger: more recall, more clutter") \
    X_F(verify_error, verify_error, 1.0e-6f, 4.0f, 0.25f, 0u, \
      "largest descriptor error of a part found by the cascade") \
    X_F(max_rotation, max_rotation, 1.0e-6f, PI_F, 0.35f, 0u, \
      "largest rotation of a part against its prototype, radians") \
    X_F(min_size, min_size, 1.0f, 16384.0f, 12.0f, LINKED, \
      "smallest predicted sign size, pixels (at most max_size)") \
    X_F(max_size, max_size, 1.0f, 16384.0f, 200.0f, LINKED, \
      "largest predicted sign size, pixels (at least min_size)") \
    X_F(centre_tol, centre_tol, 1.0e-6f, 10.0f, 0.2f, 0u, \
      "votes of one hypothesis: centres within this fraction of the size") \
    X_F(size_tol, size_tol, 0.0f, 10.0f, 0.3f, 0u, \
      "votes of one hypothesis: sizes within a factor 1 + size_tol") \
    X_U(cascade_depth, cascade_depth, 0u, 65535u, 8u, 0u, \
      "cascade prototypes looked for per hypothesis (0: no verification)") \
    X_U(min_parts, min_parts, 0u, 65535u, 1u, 0u, \
      "distinct prototypes a hypothesis needs (2 without a class stage)") \
    X_F(candidate_score, candidate_score, 0.0f, 0.999999f, 0.0f, 0u, \
      "part-score floor of a class-stage candidate") \
    X_U(max_candidates, max_candidates, 0u, 1000000u, 256u, 0u, \
      "class-stage candidates per frame, best part score first; bounds its work") \
    /* the class stage (picto.h) */ \
    X_U(refine_steps, refine_steps, 0u, SBR_RECOG_MAX_REFINE, 2u, 0u, \
      "box refinements by the class stage's regression (0: boxes stay)") \
    X_U(views, views, 1u, SBR_RECOG_MAX_VIEWS, 5u, 0u, \
      "shifted views of the final box averaged by the class stage") \
    X_U(triangle_view, triangle_view, 0u, 1u, 1u, 0u, \
      "1: look at a danger candidate's inner triangle once more") \
    X_U(max_extra_looks, max_extra_looks, 0u, 1000000u, SBR_RECOG_DEFAULT_MAX_EXTRA_LOOKS, 0u, \
      "class-stage looks per frame beyond each candidate's first; bounds its work") \
    X_F(min_score, min_score, 0.0f, 0.999999f, 0.3f, 0u, \
      "score floor of a reported detection") \
    X_F(nms_iou, nms_iou, 1.0e-6f, 1.0f, 0.3f, 0u, \
      "non-maximum suppression IoU") \
    X_F(candidate_iou, candidate_iou, 1.0e-6f, 1.0f, 1.0f, 0u, \
      "suppression IoU among the candidates before the class stage (1: none)") \
    X_U(gate, gate, 0u, 1u, 1u, 0u, \
      "1: the class stage's gate screens candidates first (when it has one)") \
    X_U(outline_maps, outline_maps, 0u, MAPS_ALL, 0x6u, 0u, \
      "outline candidates: sign-shaped bright regions of these map kinds at their own box (0: none)") \
    X_U(max_outline_candidates, max_outline_candidates, 0u, 1000000u, SBR_RECOG_DEFAULT_MAX_OUTLINES, 0u, \
      "outline candidates per frame")

#define OFF(member) ((uint32_t)offsetof(sbr_recog_config_t, member))
#define U32 ((uint8_t)SBR_FIELD_U32)
#define F32 ((uint8_t)SBR_FIELD_F32)
#define LINKED SBR_FIELD_LINKED
#define MAPS_ALL ((1u << SBR_MAP_KINDS) - 1u)
#define PI_F 3.14159265f

/* The numbers of a field. */
typedef struct field_row_s {
    uint32_t offset;
    uint8_t kind;
    uint8_t count;
    uint8_t flags;
    uint32_t lo_u;
    uint32_t hi_u;
    uint32_t def_u[SBR_FIELD_MAX_VALUES];
    float lo_f;
    float hi_f;
    float def_f;
} field_row_t;

/* The texts of a field. */
typedef struct field_text_s {
    char name[SBR_FIELD_NAME_LEN];
    char help[SBR_FIELD_HELP_LEN];
} field_text_t;

#define ROW_U(name, member, lo, hi, def, flags, help) \
    {OFF(member), U32, 1u, (flags), (lo), (hi), {(def), 0u, 0u, 0u}, 0.0f, 0.0f, 0.0f},
#define ROW_A(name, member, lo, hi, d0, d1, d2, d3, flags, help) \
    {OFF(member), U32, (uint8_t)SBR_MAP_KINDS, (flags), (lo), (hi), {(d0), (d1), (d2), (d3)}, 0.0f, 0.0f, 0.0f},
#define ROW_F(name, member, lo, hi, def, flags, help) \
    {OFF(member), F32, 1u, (flags), 0u, 0u, {0u, 0u, 0u, 0u}, (lo), (hi), (def)},
#define TEXT_U(name, member, lo, hi, def, flags, help) {#name, help},
#define TEXT_A(name, member, lo, hi, d0, d1, d2, d3, flags, help) {#name, help},
#define TEXT_F(name, member, lo, hi, def, flags, help) {#name, help},

static const field_row_t fields[] = {RECOG_FIELDS(ROW_U, ROW_A, ROW_F)};
static const field_text_t texts[] = {RECOG_FIELDS(TEXT_U, TEXT_A, TEXT_F)};

#define FIELD_COUNT ((uint32_t)((sizeof fields) / (sizeof fields[0])))

uint32_t sbr_recog_field_count(void)
{
    return FIELD_COUNT;
}

sbr_status_t sbr_recog_field_at(uint32_t index, sbr_field_t *out)
{
    sbr_status_t st = SBR_ERR_NULL;
    if (out != NULL) {
        st = SBR_ERR_RANGE;
        if (index < FIELD_COUNT) {
            const field_row_t *r = &fields[index];
            out->name = texts[index].name;
            out->help = texts[index].help;
            out->offset = r->offset;
            out->kind = r->kind;
            out->count = r->count;
            out->flags = r->flags;
            out->lo_u = r->lo_u;
            out->hi_u = r->hi_u;
            (void)memcpy(out->def_u, r->def_u, sizeof out->def_u);
            out->lo_f = r->lo_f;
            out->hi_f = r->hi_f;
            out->def_f = r->def_f;
            st = SBR_OK;
        }
    }
    return st;
}

uint32_t sbr_recog_field_find(const char *name)
{
    uint32_t found = SBR_FIELD_NONE;
    if (name != NULL) {
        uint32_t i;
        for (i = 0u; (i < FIELD_COUNT) && (found == SBR_FIELD_NONE); i++) {
            if (strncmp(texts[i].name, name, SBR_FIELD_NAME_LEN) == 0) {
                found = i;
            }
        }
    }
    return found;
}

/* Value k of field f in cfg (bytes copied: the table gives the offset). */
static uint32_t get_u(const sbr_recog_config_t *cfg, const field_row_t *f, uint32_t k)
{
    uint32_t v;
    (void)memcpy((uint8_t *)&v, &((const uint8_t *)cfg)[f->offset + (k * 4u)], sizeof v);
    return v;
}

static float get_f(const sbr_recog_config_t *cfg, const field_row_t *f)
{
    float v;
    (void)memcpy((uint8_t *)&v, &((const uint8_t *)cfg)[f->offset], sizeof v);
    return v;
}

void sbr_recog_priv_fields_default(sbr_recog_config_t *cfg)
{
    uint32_t i;
    uint32_t k;
    for (i = 0u; i < FIELD_COUNT; i++) {
        const field_row_t *f = &fields[i];
        uint8_t *at = &((uint8_t *)cfg)[f->offset];
        if (f->kind == F32) {
            (void)memcpy(at, (const uint8_t *)&f->def_f, sizeof f->def_f);
        } else {
            for (k = 0u; k < f->count; k++) {
                (void)memcpy(&at[k * 4u], (const uint8_t *)&f->def_u[k], sizeof f->def_u[k]);
            }
        }
    }
}

/* Whether the field's values are within its range (false for NaN). */
static int in_table_range(const sbr_recog_config_t *cfg, const field_row_t *f)
{
    int ok = 1;
    if (f->kind == F32) {
        const float v = get_f(cfg, f);
        if (!((v >= f->lo_f) && (v <= f->hi_f))) {
            ok = 0;
        }
    } else {
        uint32_t k;
        for (k = 0u; k < f->count; k++) {
            const uint32_t v = get_u(cfg, f, k);
            if ((v < f->lo_u) || (v > f->hi_u)) {
                ok = 0;
            }
        }
    }
    return ok;
}

/* The rules between fields (SBR_FIELD_LINKED), each blamed on one field, found by its
   offset (the table's texts stay out of the check). */
static int links_ok(const sbr_recog_config_t *cfg, uint32_t offset)
{
    const sbr_parts_config_t *p = &cfg->parts;
    int ok = 1;
    uint32_t k;
    if (offset == OFF(parts.map_subsample)) {
        for (k = 0u; k < SBR_MAP_KINDS; k++) {
            if ((p->subsample * p->map_subsample[k]) > SBR_MAP_MAX_SUBSAMPLE) {
                ok = 0;
            }
        }
    } else if (offset == OFF(parts.map_min_area)) {
        for (k = 0u; k < SBR_MAP_KINDS; k++) {
            if (p->map_min_area[k] > p->mser.max_area) {
                ok = 0;
            }
        }
    } else if (offset == OFF(parts.mser.max_area)) {
        if (p->mser.max_area < p->mser.min_area) {
            ok = 0;
        }
    } else if (offset == OFF(parts.max_side)) {
        if (p->max_side < p->min_side) {
            ok = 0;
        }
    } else if (offset == OFF(parts.fd_n)) {
        if (sbr_fft_size_supported(p->fd_n) == 0) {
            ok = 0;
        }
    } else if (offset == OFF(parts.fd_m)) {
        if ((2u * p->fd_m) >= p->fd_n) {
            ok = 0;
        }
    } else if (offset == OFF(match_p)) {
        if ((sbr_fft_size_supported(cfg->match_p) == 0) || (cfg->match_p < ((2u * p->fd_m) + 1u))) {
            ok = 0;
        }
    } else if (offset == OFF(max_size)) {
        if (!(cfg->max_size >= cfg->min_size)) {
            ok = 0;
        }
    } else {
        /* the other linked fields are blamed through their partner */
    }
    return ok;
}

uint32_t sbr_recog_config_check_field(const sbr_recog_config_t *cfg)
{
    uint32_t bad = SBR_FIELD_NONE;
    if (cfg != NULL) {
        uint32_t i;
        /* every range first, so that the links compare values in range */
        for (i = 0u; (i < FIELD_COUNT) && (bad == SBR_FIELD_NONE); i++) {
            if (in_table_range(cfg, &fields[i]) == 0) {
                bad = i;
            }
        }
        for (i = 0u; (i < FIELD_COUNT) && (bad == SBR_FIELD_NONE); i++) {
            if (((fields[i].flags & LINKED) != 0u) && (links_ok(cfg, fields[i].offset) == 0)) {
                bad = i;
            }
        }
    }
    return bad;
}
