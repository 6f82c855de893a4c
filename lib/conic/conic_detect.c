/* SPDX-License-Identifier: MIT */
/* Conics: ellipse detection (regions -> contours -> fits). See include/sbr/conic.h. */
#include "conic_internal.h"

#include <math.h>

#define DET_MAX_CONTOURS 4u

void sbr_ellipse_detect_config_default(sbr_ellipse_detect_config_t *cfg)
{
    if (cfg != NULL) {
        sbr_mser_config_default(&cfg->mser);
        cfg->mser.delta = 5u;
        cfg->mser.min_area = 40u;
        cfg->mser.max_area = 200000u;
        cfg->mser.max_variation = 0.5f;
        cfg->mser.min_diversity = 0.2f;
        cfg->mser.polarity = (uint32_t)SBR_MSER_BOTH;
        cfg->max_residual = 1.0f;
        cfg->min_coverage = 0.9f;
        cfg->min_semi_minor = 4.0f;
        cfg->min_axis_ratio = 0.1f;
        cfg->edge_offset = 0.5f;
        cfg->max_regions = 1024u;
        cfg->max_contour_points = 4096u;
    }
}

sbr_status_t sbr_ellipse_detect_config_check(const sbr_ellipse_detect_config_t *cfg)
{
    sbr_status_t st = SBR_OK;
    if (cfg == NULL) {
        st = SBR_ERR_NULL;
    } else if (sbr_mser_config_check(&cfg->mser) != SBR_OK) {
        st = SBR_ERR_RANGE;
    } else if ((isfinite(cfg->max_residual) == 0) || (cfg->max_residual <= 0.0f) ||
               (isfinite(cfg->min_coverage) == 0) || (cfg->min_coverage <= 0.0f) ||
               (cfg->min_coverage > 1.0f) || (isfinite(cfg->min_semi_minor) == 0) ||
               (cfg->min_semi_minor <= 0.0f) || (isfinite(cfg->min_axis_ratio) == 0) ||
               (cfg->min_axis_ratio <= 0.0f) || (cfg->min_axis_ratio > 1.0f) ||
               (isfinite(cfg->edge_offset) == 0) || (cfg->edge_offset < 0.0f) ||
               (cfg->edge_offset > 1.0f) || (cfg->max_regions == 0u) ||
               (cfg->max_regions > 1000000u) || (cfg->max_contour_points < 5u) ||
               (cfg->max_contour_points > 1000000u)) {
        st = SBR_ERR_RANGE;
    } else {
        /* valid */
    }
    return st;
}


/* Bytes of the per-region stage (mask workspace, mask, contour workspace, points). */
static size_t region_stage_size(uint32_t width, uint32_t height, uint32_t max_points)
{
    const size_t wh = (size_t)width * (size_t)height;
    return SBR_WS_ALIGN8(SBR_MSER_MASK_WORKSPACE_SIZE(width, height)) + SBR_WS_ALIGN8(wh) +
           SBR_WS_ALIGN8(SBR_CONTOUR_WORKSPACE_SIZE(width, height)) +
           SBR_WS_ALIGN8((size_t)max_points * sizeof(sbr_point_t)) +
           SBR_WS_ALIGN8((size_t)DET_MAX_CONTOURS * sizeof(sbr_contour_t)) +
           SBR_WS_ALIGN8((size_t)max_points * sizeof(sbr_pointf_t));
}

size_t sbr_ellipse_detect_workspace_size(const sbr_ellipse_detect_config_t *cfg, uint32_t width,
                                         uint32_t height)
{
    size_t total = 0u;
    if ((sbr_ellipse_detect_config_check(cfg) == SBR_OK) && (width >= 3u) && (height >= 3u) &&
        (width <= SBR_IMAGE_MAX_DIM) && (height <= SBR_IMAGE_MAX_DIM)) {
        const size_t mser = sbr_mser_workspace_size(&cfg->mser, width, height);
        const size_t stage = region_stage_size(width, height, cfg->max_contour_points);
        if (mser > 0u) {
            total = SBR_WS_ALIGN8((size_t)cfg->max_regions * sizeof(sbr_mser_region_t)) +
                    ((mser > stage) ? SBR_WS_ALIGN8(mser) : stage);
        }
    }
    return total;
}

/* Contour points as floats, moved `offset` pixels along the outward normal. The outward
   side follows from the contour's orientation (the sign of its shoelace area). */
static void edge_points(const sbr_point_t *pts, uint32_t n, float offset, sbr_pointf_t *out)
{
    int64_t area2 = 0;
    float side = 1.0f; /* normal (ty, -tx) * side points outward */
    uint32_t i;
    if ((sbr_contour_area2(pts, n, &area2) == SBR_OK) && (area2 < 0)) {
        side = -1.0f;
    }
    for (i = 0u; i < n; ++i) {
        const sbr_point_t *pa = &pts[(i + n - 2u) % n];
        const sbr_point_t *pb = &pts[(i + 2u) % n];
        const float tx = (float)pb->x - (float)pa->x;
        const float ty = (float)pb->y - (float)pa->y;
        const float len = sqrtf((tx * tx) + (ty * ty));
        out[i].x = (float)pts[i].x;
        out[i].y = (float)pts[i].y;
        if (len > 0.0f) {
            out[i].x += (offset * side * ty) / len;
            out[i].y -= (offset * side * tx) / len;
        }
    }
}

/* Index of a detection that is the same ellipse as `el` (a nested level set of the same
   edge: centres within 1 px, axes within 1.5 px or 3 %), or count when there is none. */
static uint32_t same_ellipse(const sbr_ellipse_det_t *dets, uint32_t count, const sbr_ellipse_t *el)
{
    uint32_t i;
    uint32_t found = count;
    for (i = 0u; (i < count) && (found == count); ++i) {
        const sbr_ellipse_t *o = &dets[i].ellipse;
        const float dx = o->cx - el->cx;
        const float dy = o->cy - el->cy;
        const float ta = fmaxf(1.5f, 0.03f * o->semi_major);
        const float tb = fmaxf(1.5f, 0.03f * o->semi_minor);
        if ((((dx * dx) + (dy * dy)) <= 1.0f) && (fabsf(o->semi_major - el->semi_major) <= ta) &&
            (fabsf(o->semi_minor - el->semi_minor) <= tb)) {
            found = i;
        }
    }
    return found;
}

/* Scale a conic to a + c = 1 (positive for an ellipse). */
static void unit_trace(sbr_conic_t *q)
{
    const float tr = q->a + q->c;
    if (tr != 0.0f) {
        *q = sbr_conic_priv_div(q, tr);
    }
}

/* Merge `det` into `into`: the running mean of their conics (each scaled to a + c = 1;
   nested level sets of one edge have nearly equal conics, so the mean is well defined
   even for near-circles, whose angles are not), the geometry recomputed from it. */
static void merge_into(sbr_ellipse_det_t *into, const sbr_ellipse_det_t *det)
{
    const float w = 1.0f / ((float)into->merged + 1.0f);
    sbr_conic_t *o = &into->conic;
    sbr_ellipse_t el;
    o->a += w * (det->conic.a - o->a);
    o->b += w * (det->conic.b - o->b);
    o->c += w * (det->conic.c - o->c);
    o->d += w * (det->conic.d - o->d);
    o->e += w * (det->conic.e - o->e);
    o->f += w * (det->conic.f - o->f);
    if (sbr_conic_priv_ellipse_of(o, &el) != 0) {
        into->ellipse = el;
    }
    into->residual += w * (det->residual - into->residual);
    into->coverage += w * (det->coverage - into->coverage);
    into->merged += 1u;
}

/* The region stage's buffers in the shared workspace, for a bw x bh region. */
typedef struct det_bufs_s {
    uint8_t *mws;
    uint8_t *mask;
    uint8_t *cws;
    sbr_point_t *pts;
    sbr_contour_t *cons;
    sbr_pointf_t *fp;
} det_bufs_t;

static void region_bufs(uint8_t *shared, uint32_t bw, uint32_t bh, uint32_t max_points,
                        det_bufs_t *b)
{
    const size_t off_mask = SBR_WS_ALIGN8(SBR_MSER_MASK_WORKSPACE_SIZE(bw, bh));
    const size_t off_cws = off_mask + SBR_WS_ALIGN8((size_t)bw * bh);
    const size_t off_pts = off_cws + SBR_WS_ALIGN8(SBR_CONTOUR_WORKSPACE_SIZE(bw, bh));
    const size_t off_cons = off_pts + SBR_WS_ALIGN8((size_t)max_points * sizeof(sbr_point_t));
    const size_t off_fp = off_cons + SBR_WS_ALIGN8((size_t)DET_MAX_CONTOURS * sizeof(sbr_contour_t));
    b->mws = shared;
    b->mask = &shared[off_mask];
    b->cws = &shared[off_cws];
    b->pts = (sbr_point_t *)(void *)&shared[off_pts];
    b->cons = (sbr_contour_t *)(void *)&shared[off_cons];
    b->fp = (sbr_pointf_t *)(void *)&shared[off_fp];
}

/* The longest outer contour of a region's mask: its point count (0 when the region is
   too small for the axis test or has no contour) and *first its first point in b->pts;
   *hit set when the contour tracer ran out of capacity. */
static uint32_t region_outline(const sbr_image_t *image, const sbr_ellipse_detect_config_t *cfg,
                               const sbr_mser_region_t *reg, det_bufs_t *b,
                               uint32_t *first, int *hit)
{
    const uint32_t bw = reg->bbox.width;
    const uint32_t bh = reg->bbox.height;
    const sbr_image_t mview = {bw, bh, bw, SBR_PIXEL_GRAY8, b->mask};
    uint32_t ncon = 0u;
    uint32_t np = 0u;
    sbr_status_t cs;
    if (((2.0f * cfg->min_semi_minor) > (float)((bw < bh) ? bw : bh)) ||
        (sbr_mser_region_mask(image, reg, b->mws, SBR_MSER_MASK_WORKSPACE_SIZE(bw, bh), b->mask,
                              bw, (size_t)bw * bh) != SBR_OK)) {
        return 0u; /* too small to pass the axis test, or no mask */
    }
    cs = sbr_contour_find_external(&mview, b->cws, SBR_CONTOUR_WORKSPACE_SIZE(bw, bh), b->pts,
                                   cfg->max_contour_points, b->cons, DET_MAX_CONTOURS, &ncon);
    if (cs == SBR_ERR_CAPACITY) {
        *hit = 1;
    } else if (cs != SBR_OK) {
        ncon = 0u;
    } else {
        /* traced */
    }
    if (ncon > 0u) {
        uint32_t best = 0u;
        uint32_t k;
        for (k = 1u; k < ncon; ++k) {
            if (b->cons[k].length > b->cons[best].length) {
                best = k;
            }
        }
        np = b->cons[best].length;
        *first = b->cons[best].first;
    }
    return np;
}

/* The ellipse of a region's outline pts[0..np) (np >= 8), moved by the edge offset into
   image coordinates in fp: 1 and *det when the fit passes every test. */
static int region_ellipse(const sbr_ellipse_detect_config_t *cfg, const sbr_mser_region_t *reg,
                          const sbr_point_t *pts, uint32_t np, sbr_pointf_t *fp,
                          sbr_ellipse_det_t *det)
{
    uint32_t i;
    int ok = 0;
    edge_points(pts, np, cfg->edge_offset, fp);
    for (i = 0u; i < np; ++i) {
        fp[i].x += (float)reg->bbox.x;
        fp[i].y += (float)reg->bbox.y;
    }
    if ((sbr_ellipse_fit(fp, np, &det->conic, &det->ellipse) == SBR_OK) &&
        (sbr_conic_residual(&det->conic, fp, np, &det->residual, NULL) == SBR_OK) &&
        (det->residual <= cfg->max_residual) &&
        (det->ellipse.semi_minor >= cfg->min_semi_minor) &&
        (det->ellipse.semi_minor >= (cfg->min_axis_ratio * det->ellipse.semi_major)) &&
        (sbr_ellipse_coverage(&det->conic, fp, np, 2.0f * cfg->max_residual, &det->coverage) ==
         SBR_OK) &&
        (det->coverage >= cfg->min_coverage)) {
        det->area = reg->area;
        det->polarity = reg->polarity;
        det->merged = 1u;
        unit_trace(&det->conic);
        ok = 1;
    }
    return ok;
}

/* A new detection merged into the same ellipse found before, or added; returns 1 when
   there was no room for it. */
static int add_ellipse(sbr_ellipse_det_t *out, uint32_t capacity, uint32_t *count,
                       const sbr_ellipse_det_t *det)
{
    const uint32_t same = same_ellipse(out, *count, &det->ellipse);
    int full = 0;
    if (same < *count) {
        merge_into(&out[same], det);
    } else if (*count < capacity) {
        out[*count] = *det;
        *count += 1u;
    } else {
        full = 1;
    }
    return full;
}

/* The arguments of sbr_ellipse_detect(), checked in the documented order. */
static sbr_status_t detect_args(const sbr_image_t *image, const sbr_ellipse_detect_config_t *cfg,
                                const void *workspace, size_t workspace_size, uint32_t capacity)
{
    sbr_status_t st = sbr_image_check(image);
    if ((st == SBR_OK) && ((image->format != SBR_PIXEL_GRAY8) ||
                           (sbr_ellipse_detect_config_check(cfg) != SBR_OK))) {
        st = SBR_ERR_RANGE;
    }
    if ((st == SBR_OK) && ((image->width < 3u) || (image->height < 3u))) {
        st = SBR_ERR_SIZE;
    }
    if (st == SBR_OK) {
        const size_t need = sbr_ellipse_detect_workspace_size(cfg, image->width, image->height);
        if ((workspace == NULL) || (need == 0u) || (workspace_size < need) ||
            (sbr_util_aligned(workspace, 8u) == 0)) {
            st = SBR_ERR_WORKSPACE;
        } else if (capacity == 0u) {
            st = SBR_ERR_CAPACITY;
        } else {
            /* valid */
        }
    }
    return st;
}

sbr_status_t sbr_ellipse_detect(const sbr_image_t *image, const sbr_ellipse_detect_config_t *cfg,
                                void *workspace, size_t workspace_size, sbr_ellipse_det_t *out,
                                uint32_t capacity, uint32_t *count)
{
    sbr_status_t st;
    uint8_t *base = (uint8_t *)workspace;
    sbr_mser_region_t *regions = (sbr_mser_region_t *)workspace;
    size_t region_bytes;
    uint32_t nreg = 0u;
    uint32_t r;
    int capacity_hit = 0;
    if ((image == NULL) || (cfg == NULL) || (out == NULL) || (count == NULL)) {
        return SBR_ERR_NULL;
    }
    *count = 0u;
    st = detect_args(image, cfg, workspace, workspace_size, capacity);
    if (st != SBR_OK) {
        return st;
    }
    region_bytes = SBR_WS_ALIGN8((size_t)cfg->max_regions * sizeof(sbr_mser_region_t));
    st = sbr_mser_detect(image, &cfg->mser, &base[region_bytes], workspace_size - region_bytes,
                         regions, cfg->max_regions, &nreg);
    if (st == SBR_ERR_CAPACITY) {
        capacity_hit = 1;
    } else if (st != SBR_OK) {
        return st;
    } else {
        /* all regions */
    }
    for (r = 0u; r < nreg; ++r) {
        const sbr_mser_region_t *reg = &regions[r];
        det_bufs_t b;
        uint32_t first = 0u;
        uint32_t np;
        sbr_ellipse_det_t det;
        region_bufs(&base[region_bytes], reg->bbox.width, reg->bbox.height,
                    cfg->max_contour_points, &b);
        np = region_outline(image, cfg, reg, &b, &first, &capacity_hit);
        if ((np >= 8u) && (region_ellipse(cfg, reg, &b.pts[first], np, b.fp, &det) != 0) &&
            (add_ellipse(out, capacity, count, &det) != 0)) {
            capacity_hit = 1;
        }
    }
    return (capacity_hit != 0) ? SBR_ERR_CAPACITY : SBR_OK;
}
