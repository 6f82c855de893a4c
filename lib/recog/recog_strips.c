/* SPDX-License-Identifier: MIT */
/*
 * The strip configuration (include/sbr/recog.h, sbr_recog_detect_strips()): the frame in
 * bands of full rows that overlap, each band recognised as a region of interest, each
 * detection kept by the one band whose core holds its centre.
 */
#include "recog_internal.h"
#include "sbr/recog_strips.h"

#include <string.h>

/* The bands of a frame `height` rows tall: band k starts at row min(k step, height - rows),
   step = rows - overlap; a frame no taller than a band is one band. */
static uint32_t strip_count(uint32_t height, uint32_t rows, uint32_t overlap)
{
    const uint32_t step = rows - overlap;
    uint32_t n = 1u;
    if (height > rows) {
        n = ((((height - rows) + step) - 1u) / step) + 1u;
    }
    return n;
}

static uint32_t strip_top(uint32_t k, uint32_t height, uint32_t rows, uint32_t overlap)
{
    uint32_t y = 0u;
    if (height > rows) {
        y = k * (rows - overlap);
        if (y > (height - rows)) {
            y = height - rows;
        }
    }
    return y;
}

/* Band k's core: the rows whose detections it keeps. The first core starts at row 0, the
   last ends at the frame's bottom; in between a core ends half the overlap above its
   band's bottom and the next core starts there. A sign at most `overlap` tall whose
   centre lies in a core lies wholly inside that core's band. */
static uint32_t core_end(uint32_t k, uint32_t bands, uint32_t height, uint32_t rows,
                         uint32_t overlap)
{
    uint32_t e = height;
    if ((k + 1u) < bands) {
        e = (strip_top(k, height, rows, overlap) + rows) - (overlap / 2u);
    }
    return e;
}

/* Higher score first; equal scores in row, then column order (the same order on every
   target). */
static int det_before(const sbr_detection_t *a, const sbr_detection_t *b)
{
    int before = 0;
    if (a->score > b->score) {
        before = 1;
    } else if (a->score < b->score) {
        /* after */
    } else if (a->box.y < b->box.y) {
        before = 1;
    } else if ((a->box.y == b->box.y) && (a->box.x < b->box.x)) {
        before = 1;
    } else {
        /* after, or the same place */
    }
    return before;
}

/* One band's counters added to the frame's. */
static void stats_add(sbr_recog_stats_t *t, const sbr_recog_stats_t *s)
{
    uint32_t i;
    t->parts_stats.regions += s->parts_stats.regions;
    t->parts_stats.skipped_shape += s->parts_stats.skipped_shape;
    t->parts_stats.skipped_contour += s->parts_stats.skipped_contour;
    t->parts_stats.capacity_hit |= s->parts_stats.capacity_hit;
    t->parts += s->parts;
    t->matches += s->matches;
    t->votes += s->votes;
    t->hypotheses += s->hypotheses;
    t->verified += s->verified;
    t->rejected += s->rejected;
    t->classified += s->classified;
    t->refined += s->refined;
    t->views += s->views;
    t->extra_looks += s->extra_looks;
    t->rim_rejected += s->rim_rejected;
    t->gated += s->gated;
    t->outlines += s->outlines;
    t->capacity_hit |= s->capacity_hit;
    for (i = 0u; i < (uint32_t)SBR_RECOG_STAGES; i++) {
        t->stage_ticks[i] += s->stage_ticks[i];
    }
}

/* The band's detections kept (centre in its core) go into the frame's, dets[0 .. *n)
   sorted by det_before(), at most `capacity`: a better one takes the worst's place when
   full. Returns 1 when a detection was dropped (the new one or the worst). */
static int det_insert(sbr_detection_t *dets, uint32_t *n, uint32_t capacity, const sbr_detection_t *d)
{
    uint32_t pos = *n;
    int dropped = 0;
    if (*n < capacity) {
        (*n)++;
    } else if (det_before(d, &dets[capacity - 1u]) != 0) {
        pos = capacity - 1u;
        dropped = 1;
    } else {
        pos = capacity; /* not among the best `capacity` */
        dropped = 1;
    }
    if (pos < capacity) {
        while ((pos > 0u) && (det_before(d, &dets[pos - 1u]) != 0)) {
            dets[pos] = dets[pos - 1u];
            pos--;
        }
        dets[pos] = *d;
    }
    return dropped;
}

/* Bytes of one band's detections after the band's workspace. */
#define STRIP_DETS_BYTES SBR_WS_ALIGN8((size_t)SBR_RECOG_STRIP_BAND_DETECTIONS * sizeof(sbr_detection_t))

size_t sbr_recog_strip_workspace_size(const sbr_recog_config_t *cfg, uint32_t width,
                                      uint32_t height, uint32_t rows)
{
    uint32_t h = height;
    size_t need = 0u;
    if (rows < h) {
        h = rows;
    }
    if (rows != 0u) {
        need = sbr_recog_workspace_size(cfg, width, h);
    }
    return (need == 0u) ? 0u : (need + STRIP_DETS_BYTES);
}

sbr_status_t sbr_recog_detect_strips(sbr_recog_t *rec, const sbr_image_t *img, uint32_t rows,
                                     uint32_t overlap, sbr_detection_t *dets, uint32_t capacity,
                                     uint32_t *count, sbr_recog_stats_t *stats)
{
    sbr_recog_stats_t total;
    sbr_recog_stats_t band;
    sbr_detection_t *got_dets;
    size_t need;
    uint32_t bands;
    uint32_t band_rows;
    uint32_t k;
    uint32_t n = 0u;
    int full = 0;
    sbr_status_t st;

    st = sbr_recog_priv_begin(rec, img, dets, count, stats);
    if (st != SBR_OK) {
        return st;
    }
    st = sbr_image_check(img);
    if (st != SBR_OK) {
        return st;
    }
    if ((rows == 0u) || (overlap >= rows)) {
        return SBR_ERR_RANGE;
    }
    band_rows = (img->height < rows) ? img->height : rows;
    need = sbr_recog_workspace_size(&rec->cfg, img->width, band_rows);
    if ((need == 0u) || (capacity == 0u)) {
        return SBR_ERR_SIZE;
    }
    if (rec->workspace_size < (need + STRIP_DETS_BYTES)) {
        return SBR_ERR_WORKSPACE;
    }
    /* a band's detections: after what sbr_recog_detect() uses of the workspace */
    got_dets = (sbr_detection_t *)(void *)&((uint8_t *)rec->workspace)[need];
    (void)memset(&total, 0, sizeof total);
    bands = strip_count(img->height, rows, overlap);
    for (k = 0u; k < bands; k++) {
        const uint32_t lo = (k == 0u) ? 0u : core_end(k - 1u, bands, img->height, rows, overlap);
        const uint32_t hi = core_end(k, bands, img->height, rows, overlap);
        sbr_rect_t roi;
        uint32_t got = 0u;
        uint32_t i;
        roi.x = 0u;
        roi.y = strip_top(k, img->height, rows, overlap);
        roi.width = img->width;
        roi.height = band_rows;
        st = sbr_recog_detect(rec, img, &roi, got_dets, SBR_RECOG_STRIP_BAND_DETECTIONS, &got, &band);
        if (st == SBR_ERR_CAPACITY) {
            full = 1;
        } else if (st != SBR_OK) {
            *count = 0u;
            return st;
        } else {
            /* complete */
        }
        stats_add(&total, &band);
        /* keep the detections whose centre row lies in the band's core */
        for (i = 0u; i < got; i++) {
            const uint32_t cy = got_dets[i].box.y + (got_dets[i].box.height / 2u);
            if ((cy >= lo) && (cy < hi) && (det_insert(dets, &n, capacity, &got_dets[i]) != 0)) {
                full = 1;
            }
        }
    }
    *count = n;
    if (stats != NULL) {
        *stats = total;
    }
    return (full != 0) ? SBR_ERR_CAPACITY : SBR_OK;
}
