/* SPDX-License-Identifier: MIT */
/*
 * Parts of a frame: maps -> MSER -> region masks -> outer contours -> Fourier descriptors.
 * All buffers come from the caller's workspace; see include/sbr/parts.h.
 */
#include "sbr/parts.h"

#include "sbr/contour.h"

#include "../common/sbr_util.h"

#include <string.h>

void sbr_parts_config_default(sbr_parts_config_t *cfg)
{
    if (cfg != NULL) {
        uint32_t k;
        cfg->maps = 0x7u;
        cfg->subsample = 1u;
        for (k = 0u; k < SBR_MAP_KINDS; k++) {
            cfg->map_subsample[k] = 1u;
            cfg->map_min_area[k] = 0u;
            cfg->map_polarity[k] = 0u;
            cfg->map_bright_min[k] = 0u;
            cfg->map_dark_max[k] = 0u;
        }
        sbr_mser_config_default(&cfg->mser);
        cfg->mser.max_nodes = SBR_PARTS_DEFAULT_MAX_NODES;
        cfg->mser.max_heap = SBR_PARTS_DEFAULT_MAX_HEAP;
        cfg->max_regions = SBR_PARTS_DEFAULT_MAX_REGIONS;
        cfg->min_side = 6u;
        cfg->max_side = SBR_PARTS_DEFAULT_MAX_SIDE;
        cfg->max_aspect = 3.0f;
        cfg->min_fill = 0.2f;
        cfg->max_contour = SBR_PARTS_DEFAULT_MAX_CONTOUR;
        cfg->fd_n = SBR_PARTS_DEFAULT_FD_N;
        cfg->fd_m = SBR_PARTS_DEFAULT_FD_M;
    }
}

sbr_status_t sbr_parts_config_check(const sbr_parts_config_t *cfg)
{
    sbr_status_t st;
    uint32_t k;
    if (cfg == NULL) {
        return SBR_ERR_NULL;
    }
    st = sbr_mser_config_check(&cfg->mser);
    if (st != SBR_OK) {
        return st;
    }
    if ((cfg->maps == 0u) || (cfg->maps > 0xFu) || (cfg->subsample == 0u) ||
        (cfg->subsample > SBR_MAP_MAX_SUBSAMPLE) || (cfg->max_regions == 0u) ||
        (cfg->min_side == 0u) || (cfg->max_side < cfg->min_side) || (cfg->max_side > 4096u) ||
        (cfg->max_contour < 3u) || (cfg->max_contour > 65536u) ||
        (sbr_fft_size_supported(cfg->fd_n) == 0) || (cfg->fd_m == 0u) ||
        (cfg->fd_m > SBR_FD_MAX_M) || ((2u * cfg->fd_m) >= cfg->fd_n)) {
        return SBR_ERR_RANGE;
    }
    for (k = 0u; k < SBR_MAP_KINDS; k++) {
        /* the product stays within the map's range (no overflow: both are checked first) */
        if ((cfg->map_subsample[k] == 0u) || (cfg->map_subsample[k] > SBR_MAP_MAX_SUBSAMPLE) ||
            ((cfg->subsample * cfg->map_subsample[k]) > SBR_MAP_MAX_SUBSAMPLE) ||
            (cfg->map_min_area[k] > cfg->mser.max_area) ||
            (cfg->map_polarity[k] > (uint32_t)SBR_MSER_BOTH) || (cfg->map_bright_min[k] > 255u) ||
            (cfg->map_dark_max[k] > 255u)) {
            return SBR_ERR_RANGE;
        }
    }
    if (!((cfg->max_aspect >= 1.0f) && (cfg->max_aspect <= 1.0e6f)) ||
        !((cfg->min_fill >= 0.0f) && (cfg->min_fill <= 1.0f))) {
        return SBR_ERR_RANGE;
    }
    return SBR_OK;
}

/* Workspace layout (each piece 8-byte aligned). */
typedef struct parts_layout_s {
    size_t mser;     /* MSER workspace (it holds each map too) */
    size_t regions;  /* region array */
    size_t mask;     /* region mask */
    size_t fill;     /* mask flood-fill stack */
    size_t trace;    /* contour label map */
    size_t points;   /* traced points (int16 pairs) */
    size_t pointsf;  /* float points */
    size_t fdwork;   /* FFT scratch */
    size_t total;
} parts_layout_t;

/* The subsampling of the finest selected map (it sizes the map and MSER buffers). */
static uint32_t finest_subsample(const sbr_parts_config_t *cfg)
{
    uint32_t finest = SBR_MAP_MAX_SUBSAMPLE;
    uint32_t k;
    for (k = 0u; k < SBR_MAP_KINDS; k++) {
        const uint32_t s = cfg->subsample * cfg->map_subsample[k];
        if (((cfg->maps & (1u << k)) != 0u) && (s < finest)) {
            finest = s;
        }
    }
    return finest;
}

static int parts_layout(uint32_t width, uint32_t height, const sbr_parts_config_t *cfg,
                        parts_layout_t *l)
{
    const uint32_t fs = finest_subsample(cfg);
    const uint32_t mw = width / fs;
    const uint32_t mh = height / fs;
    const size_t side = (size_t)cfg->max_side;
    size_t ms;
    uint32_t k;
    if (((width / cfg->subsample) < 3u) || ((height / cfg->subsample) < 3u)) {
        return 0;
    }
    for (k = 0u; k < SBR_MAP_KINDS; k++) {
        const uint32_t s = cfg->subsample * cfg->map_subsample[k];
        if (((cfg->maps & (1u << k)) != 0u) && (((width / s) < 3u) || ((height / s) < 3u))) {
            return 0;
        }
    }
    ms = sbr_mser_workspace_size(&cfg->mser, mw, mh);
    if (ms == 0u) {
        return 0;
    }
    l->mser = SBR_WS_ALIGN8(ms);
    l->regions = SBR_WS_ALIGN8((size_t)cfg->max_regions * sizeof(sbr_mser_region_t));
    l->mask = SBR_WS_ALIGN8(side * side);
    l->fill = SBR_WS_ALIGN8(SBR_MSER_MASK_WORKSPACE_SIZE(side, side));
    l->trace = SBR_WS_ALIGN8(SBR_CONTOUR_WORKSPACE_SIZE(side, side));
    l->points = SBR_WS_ALIGN8((size_t)cfg->max_contour * sizeof(sbr_point_t));
    l->pointsf = SBR_WS_ALIGN8((size_t)cfg->max_contour * sizeof(sbr_pointf_t));
    l->fdwork = SBR_WS_ALIGN8((size_t)cfg->fd_n * sizeof(sbr_complex_t));
    l->total = l->mser + l->regions + l->mask + l->fill + l->trace + l->points +
               l->pointsf + l->fdwork;
    return 1;
}

size_t sbr_parts_workspace_size(const sbr_parts_config_t *cfg, uint32_t width, uint32_t height)
{
    parts_layout_t l;
    if ((sbr_parts_config_check(cfg) != SBR_OK) || (width > SBR_IMAGE_MAX_DIM) ||
        (height > SBR_IMAGE_MAX_DIM) || (parts_layout(width, height, cfg, &l) == 0)) {
        return 0u;
    }
    return l.total;
}

/* Does a region pass the cheap shape filters? */
static int region_ok(const sbr_mser_region_t *r, const sbr_parts_config_t *cfg)
{
    const uint32_t w = r->bbox.width;
    const uint32_t h = r->bbox.height;
    uint32_t lo = w;
    uint32_t hi = h;
    int ok = 1;
    if (h < w) {
        lo = h;
        hi = w;
    }
    if ((lo < cfg->min_side) || (hi > cfg->max_side) ||
        ((float)hi > (cfg->max_aspect * (float)lo)) ||
        ((float)r->area < (cfg->min_fill * ((float)w * (float)h)))) {
        ok = 0;
    }
    return ok;
}

/* Scratch buffers of one call. */
typedef struct parts_bufs_s {
    uint8_t *mser;
    sbr_mser_region_t *regions;
    uint8_t *mask;
    uint8_t *fill;
    uint8_t *trace;
    sbr_point_t *points;
    sbr_pointf_t *pointsf;
    sbr_complex_t *fdwork;
    size_t mser_size;
    size_t fill_size;
    size_t trace_size;
} parts_bufs_t;

/* One region to a part; returns 1 if a part was written. */
static int region_to_part(const sbr_image_t *map, const sbr_mser_region_t *r,
                          const sbr_parts_config_t *cfg, const sbr_fft_t *fft,
                          parts_bufs_t *b, uint8_t kind, sbr_part_t *out)
{
    const uint32_t s = cfg->subsample * cfg->map_subsample[kind];
    const float half = 0.5f * ((float)s - 1.0f);
    sbr_image_t mv;
    sbr_contour_t ct;
    uint32_t n = 0u;
    uint32_t i;
    sbr_status_t st;

    st = sbr_mser_region_mask(map, r, b->fill, b->fill_size, b->mask, r->bbox.width,
                              (size_t)r->bbox.width * (size_t)r->bbox.height);
    if (st != SBR_OK) {
        return 0;
    }
    mv.width = r->bbox.width;
    mv.height = r->bbox.height;
    mv.stride = r->bbox.width;
    mv.format = SBR_PIXEL_GRAY8;
    mv.data = b->mask;
    /* a region is one 4-connected blob: its outer boundary is the only external contour */
    st = sbr_contour_find_external(&mv, b->trace, b->trace_size, b->points, cfg->max_contour,
                                   &ct, 1u, &n);
    if ((st != SBR_OK) || (n != 1u)) {
        return 0;
    }
    for (i = 0u; i < ct.length; i++) {
        const sbr_point_t p = b->points[ct.first + i];
        const uint32_t mx = (uint32_t)(int32_t)p.x + r->bbox.x; /* map pixel */
        const uint32_t my = (uint32_t)(int32_t)p.y + r->bbox.y;
        b->pointsf[i].x = ((float)mx * (float)s) + half;
        b->pointsf[i].y = ((float)my * (float)s) + half;
    }
    st = sbr_fd_from_pointsf(fft, b->pointsf, ct.length, cfg->fd_m, b->fdwork, cfg->fd_n,
                             &out->fd);
    if (st != SBR_OK) {
        return 0;
    }
    out->bbox.x = r->bbox.x * s;
    out->bbox.y = r->bbox.y * s;
    out->bbox.width = r->bbox.width * s;
    out->bbox.height = r->bbox.height * s;
    out->area = r->area;
    out->map = kind;
    out->polarity = r->polarity;
    out->level = r->level;
    out->pad = 0u;
    return 1;
}

/* The buffers of layout l in the workspace. */
static void parts_bufs(void *workspace, const parts_layout_t *l, parts_bufs_t *b)
{
    uint8_t *base = (uint8_t *)workspace;
    b->mser = base;
    b->mser_size = l->mser;
    base = &base[l->mser];
    b->regions = (sbr_mser_region_t *)(void *)base;
    base = &base[l->regions];
    b->mask = base;
    base = &base[l->mask];
    b->fill = base;
    b->fill_size = l->fill;
    base = &base[l->fill];
    b->trace = base;
    b->trace_size = l->trace;
    base = &base[l->trace];
    b->points = (sbr_point_t *)(void *)base;
    base = &base[l->points];
    b->pointsf = (sbr_pointf_t *)(void *)base;
    base = &base[l->pointsf];
    b->fdwork = (sbr_complex_t *)(void *)base;
}

/* Where the parts go: the caller's array, its capacity and count, and the statistics. */
typedef struct parts_out_s {
    sbr_part_t *parts;
    uint32_t capacity;
    uint32_t *count;
    sbr_parts_stats_t sx;
    int full;
} parts_out_t;

/* The parts of one map: the map at its resolution (made where the MSER workspace keeps
   it, so it needs no buffer of its own), its regions, and each region that passes the
   shape tests as a part while the output has room. */
static sbr_status_t parts_of_map(const sbr_image_t *img, const sbr_parts_config_t *cfg,
                                 uint32_t kind, const sbr_fft_t *fft, parts_bufs_t *b,
                                 parts_out_t *o)
{
    sbr_image_t map;
    sbr_mser_config_t mc = cfg->mser;
    const uint32_t sub = cfg->subsample * cfg->map_subsample[kind];
    uint32_t nreg = 0u;
    uint32_t i;
    sbr_status_t st;
    if (cfg->map_min_area[kind] != 0u) {
        mc.min_area = cfg->map_min_area[kind];
    }
    if (cfg->map_polarity[kind] != 0u) {
        mc.polarity = cfg->map_polarity[kind];
    }
    if (cfg->map_bright_min[kind] != 0u) {
        mc.bright_min = cfg->map_bright_min[kind];
    }
    if (cfg->map_dark_max[kind] != 0u) {
        mc.dark_max = cfg->map_dark_max[kind];
    }
    {
        const uint32_t mw = img->width / sub;
        const uint32_t mh = img->height / sub;
        uint8_t *slot = sbr_mser_map_slot(&mc, mw, mh, b->mser, b->mser_size);
        if (slot == NULL) {
            /* the MSER refuses the size or the workspace: its status */
            st = sbr_mser_detect_in_place(mw, mh, &mc, b->mser, b->mser_size, b->regions,
                                          cfg->max_regions, &nreg, &map);
        } else if ((mc.polarity == (uint32_t)SBR_MSER_BRIGHT) && (mc.bright_min > 128u)) {
            /* only values above 128 are flooded: the others need not be exact */
            st = sbr_map_make_bright(img, (sbr_map_kind_t)kind, sub, slot, mw, (size_t)mw * mh,
                                     &map);
        } else {
            st = sbr_map_make(img, (sbr_map_kind_t)kind, sub, slot, mw, (size_t)mw * mh, &map);
        }
        if (st != SBR_OK) {
            return st;
        }
        if (slot != NULL) {
            st = sbr_mser_detect_in_place(mw, mh, &mc, b->mser, b->mser_size, b->regions,
                                          cfg->max_regions, &nreg, &map);
        }
    }
    if (st == SBR_ERR_CAPACITY) {
        o->sx.capacity_hit = 1u;
    } else if (st != SBR_OK) {
        return st;
    } else {
        /* complete */
    }
    o->sx.regions += nreg;
    for (i = 0u; i < nreg; i++) {
        const sbr_mser_region_t *r = &b->regions[i];
        if (region_ok(r, cfg) == 0) {
            o->sx.skipped_shape++;
        } else if (*o->count >= o->capacity) {
            o->full = 1;
        } else if (region_to_part(&map, r, cfg, fft, b, (uint8_t)kind, &o->parts[*o->count]) !=
                   0) {
            (*o->count)++;
        } else {
            o->sx.skipped_contour++;
        }
    }
    return SBR_OK;
}

sbr_status_t sbr_parts_extract(const sbr_image_t *img, const sbr_parts_config_t *cfg,
                               const sbr_fft_t *fft, void *workspace, size_t workspace_size,
                               sbr_part_t *parts, uint32_t capacity, uint32_t *count,
                               sbr_parts_stats_t *stats)
{
    sbr_status_t st;
    parts_layout_t l;
    parts_bufs_t b;
    parts_out_t o;
    uint32_t kind;

    if ((img == NULL) || (cfg == NULL) || (fft == NULL) || (parts == NULL) || (count == NULL)) {
        return SBR_ERR_NULL;
    }
    *count = 0u;
    st = sbr_image_check(img);
    if (st != SBR_OK) {
        return st;
    }
    st = sbr_parts_config_check(cfg);
    if (st != SBR_OK) {
        return st;
    }
    if ((img->format == SBR_PIXEL_GRAY8) && (cfg->maps != 1u)) {
        return SBR_ERR_RANGE;
    }
    if ((sbr_fft_check(fft) != SBR_OK) || (fft->n != cfg->fd_n)) {
        return SBR_ERR_STATE;
    }
    if ((parts_layout(img->width, img->height, cfg, &l) == 0) || (capacity == 0u)) {
        return SBR_ERR_SIZE;
    }
    if ((workspace == NULL) || (workspace_size < l.total) ||
        (sbr_util_aligned(workspace, 8u) == 0)) {
        return SBR_ERR_WORKSPACE;
    }
    parts_bufs(workspace, &l, &b);
    (void)memset(&o, 0, sizeof o);
    o.parts = parts;
    o.capacity = capacity;
    o.count = count;
    for (kind = 0u; (kind < SBR_MAP_KINDS) && (o.full == 0); kind++) {
        if ((cfg->maps & (1u << kind)) != 0u) {
            st = parts_of_map(img, cfg, kind, fft, &b, &o);
            if (st != SBR_OK) {
                return st;
            }
        }
    }
    if (stats != NULL) {
        *stats = o.sx;
    }
    if (o.full != 0) {
        return SBR_ERR_CAPACITY;
    }
    return SBR_OK;
}
