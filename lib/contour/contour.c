/* SPDX-License-Identifier: MIT */
/* Outer contours of a binary mask (include/sbr/contour.h): border following with a label
   map. */
#include "sbr/contour.h"

/* Label map values: background, unvisited foreground, visited border pixel, visited border
   pixel whose right neighbour is background (the "right bound" of Suzuki-Abe). */
#define LBL_BG 0
#define LBL_FG 1
#define LBL_BORDER 2
#define LBL_RIGHT (-2)

size_t sbr_contour_workspace_size(uint32_t width, uint32_t height)
{
    if ((width == 0u) || (height == 0u) || (width > SBR_IMAGE_MAX_DIM) ||
        (height > SBR_IMAGE_MAX_DIM)) {
        return 0u;
    }
    return SBR_CONTOUR_WORKSPACE_SIZE(width, height);
}

/* Neighbour offsets in the padded map and in image coordinates, counter-clockwise on the
   screen from east: E, NE, N, NW, W, SW, S, SE, repeated so that a search may run past 7. */
static void make_deltas(int32_t pitch, int32_t d[16], int16_t dx[8], int16_t dy[8])
{
    static const int16_t kx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
    static const int16_t ky[8] = {0, -1, -1, -1, 0, 1, 1, 1};
    uint32_t k;
    for (k = 0u; k < 8u; k++) {
        dx[k] = kx[k];
        dy[k] = ky[k];
        d[k] = ((int32_t)ky[k] * pitch) + (int32_t)kx[k];
        d[k + 8u] = d[k];
    }
}

typedef struct trace_out_s {
    sbr_point_t *points;
    uint32_t capacity;
    uint32_t used;    /* points already committed by earlier contours */
    uint32_t length;  /* points of the contour being traced */
    int overflow;     /* this contour did not fit */
    int16_t minx;
    int16_t miny;
    int16_t maxx;
    int16_t maxy;
} trace_out_t;

static void emit(trace_out_t *o, int16_t x, int16_t y)
{
    const uint32_t at = o->used + o->length;
    if (at < o->capacity) {
        o->points[at].x = x;
        o->points[at].y = y;
    } else {
        o->overflow = 1;
    }
    o->length++;
    if (x < o->minx) {
        o->minx = x;
    }
    if (x > o->maxx) {
        o->maxx = x;
    }
    if (y < o->miny) {
        o->miny = y;
    }
    if (y > o->maxy) {
        o->maxy = y;
    }
}

/* Follows the outer border that starts at map index i0 = pixel (x0, y0), whose west
   neighbour is background; labels the border in the map and emits its points. */
static void follow(int8_t *map, ptrdiff_t i0, int16_t x0, int16_t y0, const int32_t d[16],
                   const int16_t dx[8], const int16_t dy[8], size_t max_steps, trace_out_t *o)
{
    uint32_t s = 4u;
    uint32_t s_end = 4u;
    ptrdiff_t i1;
    ptrdiff_t i3;
    ptrdiff_t i4 = i0;
    size_t steps = 0u;
    int32_t x = x0;
    int32_t y = y0;

    /* Clockwise from the west neighbour: the first foreground pixel is the contour's
       last point. */
    do {
        s = (s + 7u) & 7u;
        i1 = i0 + d[s];
    } while ((map[i1] == LBL_BG) && (s != s_end));

    if (s == s_end) { /* isolated pixel */
        map[i0] = LBL_RIGHT;
        emit(o, x0, y0);
        return;
    }
    i3 = i0;
    while (steps < max_steps) {
        steps++;
        s_end = s;
        /* Counter-clockwise from the direction after the one we came from. */
        do {
            s++;
            i4 = i3 + d[s];
        } while ((map[i4] == LBL_BG) && (s < 15u));
        s &= 7u;
        /* The east neighbour was examined and is background: a right bound. */
        if ((s - 1u) < s_end) {
            map[i3] = LBL_RIGHT;
        } else if (map[i3] == LBL_FG) {
            map[i3] = LBL_BORDER;
        } else {
            /* already labelled by an earlier pass of this border */
        }
        {
            const int16_t xs = (int16_t)x; /* within the image: fits int16_t */
            const int16_t ys = (int16_t)y;
            emit(o, xs, ys);
        }
        x += dx[s];
        y += dy[s];
        if ((i4 == i0) && (i3 == i1)) {
            break;
        }
        i3 = i4;
        s = (s + 4u) & 7u;
    }
}

/* Eight bytes as one word (byte i in bits 8i..8i+7, whatever the CPU's byte order;
   compilers make it one load on little-endian targets). */
static inline uint64_t load8(const uint8_t *b)
{
    return ((uint64_t)b[0] | ((uint64_t)b[1] << 8u) | ((uint64_t)b[2] << 16u) |
            ((uint64_t)b[3] << 24u) | ((uint64_t)b[4] << 32u) | ((uint64_t)b[5] << 40u) |
            ((uint64_t)b[6] << 48u) | ((uint64_t)b[7] << 56u));
}

/* load8()'s inverse into a label map. */
static inline void store8(int8_t *b, uint64_t v)
{
    b[0] = (int8_t)(uint8_t)v;
    b[1] = (int8_t)(uint8_t)(v >> 8u);
    b[2] = (int8_t)(uint8_t)(v >> 16u);
    b[3] = (int8_t)(uint8_t)(v >> 24u);
    b[4] = (int8_t)(uint8_t)(v >> 32u);
    b[5] = (int8_t)(uint8_t)(v >> 40u);
    b[6] = (int8_t)(uint8_t)(v >> 48u);
    b[7] = (int8_t)(uint8_t)(v >> 56u);
}

/* The padded binary copy of the mask in map (pitch = width + 2): a frame of background
   around it. */
static void pad_mask(const sbr_image_t *mask, int8_t *map, size_t pitch)
{
    uint32_t x;
    uint32_t y;
    for (x = 0u; x < pitch; x++) {
        map[x] = LBL_BG;
        map[(((size_t)mask->height + 1u) * pitch) + x] = LBL_BG;
    }
    for (y = 0u; y < mask->height; y++) {
        const uint8_t *row = &mask->data[(size_t)y * mask->stride];
        int8_t *m = &map[((size_t)y + 1u) * pitch];
        const uint32_t w8 = mask->width - (mask->width % 8u);
        m[0] = LBL_BG;
        m[pitch - 1u] = LBL_BG;
        for (x = 0u; x < w8; x += 8u) {
            /* eight bytes at once: each byte's bits or-ed down into its lowest bit (the
               shifts move bits within a byte for that bit), so 1 (LBL_FG) where the mask
               byte is not 0 */
            uint64_t v = load8(&row[x]);
            v |= v >> 4u;
            v |= v >> 2u;
            v |= v >> 1u;
            v &= UINT64_C(0x0101010101010101);
            store8(&m[x + 1u], v);
        }
        for (x = w8; x < mask->width; x++) {
            m[x + 1u] = (row[x] != 0u) ? (int8_t)LBL_FG : (int8_t)LBL_BG;
        }
    }
}

/* The state of one scan: the padded map, the neighbour steps, and the outputs. */
typedef struct contour_scan_s {
    int8_t *map;
    int32_t d[16];
    int16_t dx[8];
    int16_t dy[8];
    size_t max_steps;
    sbr_point_t *points;
    uint32_t point_capacity;
    sbr_contour_t *contours;
    uint32_t contour_capacity;
    uint32_t n;
    uint32_t used;
    int overflow;
} contour_scan_t;

/* Trace the outer border that starts at map index `at` (mask pixel px, py) and keep it
   as the next contour if there is room. */
static void trace_border(contour_scan_t *sc, size_t at, uint32_t px, uint32_t py)
{
    trace_out_t o;
    o.points = sc->points;
    o.capacity = sc->point_capacity;
    o.used = sc->used;
    o.length = 0u;
    o.overflow = 0;
    o.minx = INT16_MAX;
    o.miny = INT16_MAX;
    o.maxx = INT16_MIN;
    o.maxy = INT16_MIN;
    follow(sc->map, (ptrdiff_t)at, (int16_t)px, (int16_t)py, sc->d, sc->dx, sc->dy,
           sc->max_steps, &o);
    if ((o.overflow != 0) || (sc->n >= sc->contour_capacity)) {
        sc->overflow = 1;
    } else {
        sbr_contour_t *c = &sc->contours[sc->n];
        const int32_t bw = (int32_t)o.maxx - (int32_t)o.minx;
        const int32_t bh = (int32_t)o.maxy - (int32_t)o.miny;
        c->first = sc->used;
        c->length = o.length;
        c->bbox.x = (uint32_t)o.minx;
        c->bbox.y = (uint32_t)o.miny;
        c->bbox.width = (uint32_t)bw + 1u;
        c->bbox.height = (uint32_t)bh + 1u;
        sc->used += o.length;
        sc->n++;
    }
}

sbr_status_t sbr_contour_find_external(const sbr_image_t *mask, void *workspace,
                                       size_t workspace_size, sbr_point_t *points,
                                       uint32_t point_capacity, sbr_contour_t *contours,
                                       uint32_t contour_capacity, uint32_t *contour_count)
{
    sbr_status_t st = sbr_image_check(mask);
    contour_scan_t sc;
    const uint8_t *bytes;
    size_t pitch;
    uint32_t y;

    if (contour_count != NULL) {
        *contour_count = 0u;
    }
    if (st != SBR_OK) {
        return st;
    }
    if ((workspace == NULL) || (points == NULL) || (contours == NULL) ||
        (contour_count == NULL)) {
        return SBR_ERR_NULL;
    }
    if (mask->format != SBR_PIXEL_GRAY8) {
        return SBR_ERR_RANGE;
    }
    if (workspace_size < SBR_CONTOUR_WORKSPACE_SIZE(mask->width, mask->height)) {
        return SBR_ERR_WORKSPACE;
    }
    sc.map = (int8_t *)workspace;
    pitch = (size_t)mask->width + 2u;
    pad_mask(mask, sc.map, pitch);
    make_deltas((int32_t)pitch, sc.d, sc.dx, sc.dy);
    sc.max_steps = 4u * pitch * ((size_t)mask->height + 2u);
    sc.points = points;
    sc.point_capacity = point_capacity;
    sc.contours = contours;
    sc.contour_capacity = contour_capacity;
    sc.n = 0u;
    sc.used = 0u;
    sc.overflow = 0;

    bytes = (const uint8_t *)sc.map; /* the labels' bytes, compared eight at a time */
    for (y = 1u; y <= mask->height; y++) {
        const size_t row = (size_t)y * pitch;
        int8_t prev = LBL_BG;
        int8_t lnbd = LBL_BG; /* label of the last border pixel passed on this row */
        uint32_t x = 1u;
        while (x <= mask->width) {
            const int8_t p = sc.map[row + x];
            if (p == prev) {
                /* nothing happens at a pixel equal to the one before: past it, and past
                   the next eight when they equal it too */
                if (((x + 8u) <= mask->width) &&
                    (load8(&bytes[row + x + 1u]) ==
                     ((uint64_t)(uint8_t)prev * UINT64_C(0x0101010101010101)))) {
                    x += 8u;
                }
            } else {
                /* An outer border starts at an unvisited pixel after background, unless
                   the last border passed is a left (non-right-bound) border: then we are
                   inside a blob's hole, which RETR_EXTERNAL skips. */
                if ((prev == LBL_BG) && (p == LBL_FG) && (lnbd <= 0)) {
                    trace_border(&sc, row + x, x - 1u, y - 1u);
                }
                prev = sc.map[row + x]; /* as the trace labelled it */
                if ((prev != LBL_BG) && (prev != LBL_FG)) {
                    lnbd = prev;
                }
            }
            x++;
        }
    }
    *contour_count = sc.n;
    return (sc.overflow != 0) ? SBR_ERR_CAPACITY : SBR_OK;
}

sbr_status_t sbr_contour_area2(const sbr_point_t *points, uint32_t count, int64_t *area2)
{
    int64_t sum = 0;
    uint32_t i;

    if ((points == NULL) || (area2 == NULL)) {
        return SBR_ERR_NULL;
    }
    if (count == 0u) {
        return SBR_ERR_SIZE;
    }
    for (i = 0u; i < count; i++) {
        const sbr_point_t a = points[i];
        const sbr_point_t b = points[(i + 1u) % count];
        sum += ((int64_t)a.x * (int64_t)b.y) - ((int64_t)b.x * (int64_t)a.y);
    }
    *area2 = sum;
    return SBR_OK;
}
