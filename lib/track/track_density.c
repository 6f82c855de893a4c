/* SPDX-License-Identifier: MIT */
/* Channel-based multi-target tracker (paper E), one target's density per axis: the
   channel grid, its prediction through the motion model, the measurement update, birth,
   and decoding a position from it. See include/sbr/track.h for the method. */
#include "sbr/track.h"

#include <math.h>
#include <string.h>

#include "sbr/channel.h"
#include "../common/sbr_util.h"
#include "track_internal.h"

/* ---- per-target density helpers ---------------------------------------------------- */

float *sbr_track_priv_dens(const sbr_track_t *trk, const trk_geo_t *g, uint32_t t, uint32_t axis)
{
    return &trk->dens[(((size_t)t * 2u) + axis) * (size_t)g->w * (size_t)g->v];
}

/* Position marginal of one axis' density into m[w]; returns the total. */
float sbr_track_priv_marginal(const float *d, const trk_geo_t *g, float *m)
{
    float total = 0.0f;
    uint32_t p;
    for (p = 0u; p < g->w; p++) {
        const float *row = &d[(size_t)p * g->v];
        float a = 0.0f;
        uint32_t k;
        for (k = 0u; k < g->v; k++) {
            a += row[k];
        }
        m[p] = a;
        total += a;
    }
    return total;
}

/* Mean and variance (in pixels) of a position marginal. */
void sbr_track_priv_moments(const float *m, const trk_geo_t *g, float origin, float *mean, float *var)
{
    float sw = 0.0f;
    float s1 = 0.0f;
    float s2 = 0.0f;
    uint32_t p;
    for (p = 0u; p < g->w; p++) {
        sw += m[p];
        s1 += m[p] * (float)p;
    }
    if (sw > TRK_TINY) {
        s1 /= sw;
        for (p = 0u; p < g->w; p++) {
            const float d = (float)p - s1;
            s2 += m[p] * d * d;
        }
        s2 /= sw;
    }
    *mean = origin + (s1 * g->s);
    /* a channel's own width: variance of the cos² kernel of support 3 s */
    *var = (s2 + 0.294f) * g->s * g->s;
}

static void trk_normalise(float *d, size_t n)
{
    float sum = 0.0f;
    size_t i;
    for (i = 0u; i < n; i++) {
        sum += d[i];
    }
    if (sum > TRK_TINY) {
        const float inv = 1.0f / sum;
        for (i = 0u; i < n; i++) {
            d[i] *= inv;
        }
    }
}

/* Velocity channel j's mass of every position channel p, times the transition t0 + t1
   to velocity channel k, added to out at positions p + sh (share t0) and p + sh + 1
   (share t1), inside the window. */
static void trk_shift_add(const trk_geo_t *g, const float *d, uint32_t j, uint32_t k, int32_t sh,
                          float t0, float t1, float *out)
{
    uint32_t p;
    for (p = 0u; p < g->w; p++) {
        const float c = d[((size_t)p * g->v) + j];
        if (c > 0.0f) {
            const int32_t q = (int32_t)p + sh;
            if ((q >= 0) && (q < (int32_t)g->w)) {
                out[((size_t)q * g->v) + k] += c * t0;
            }
            if (((q + 1) >= 0) && ((q + 1) < (int32_t)g->w)) {
                const int32_t q1 = q + 1;
                out[((size_t)q1 * g->v) + k] += c * t1;
            }
        }
    }
}

/* One prediction sub-step of one axis: ratio = sub-step / period. */
void sbr_track_priv_predict_axis(const sbr_track_t *trk, const trk_geo_t *g, uint32_t axis,
                             float *d, float *origin, float ratio)
{
    const sbr_track_model_t *m = trk->cfg.model;
    const float *tab = sbr_track_priv_table(m, axis, 0);
    const size_t vv = (size_t)g->v * (size_t)g->v;
    float *out = trk->scratch;
    uint32_t ridx[3];
    float rw[3];
    uint32_t nr;
    float mp = 0.0f;
    float mv = 0.0f;
    float tot = 0.0f;
    float shift_f;
    int32_t recentre;
    uint32_t p;
    uint32_t j;
    uint32_t k;
    uint32_t r;
    for (p = 0u; p < g->w; p++) {
        for (k = 0u; k < g->v; k++) {
            const float c = d[((size_t)p * g->v) + k];
            tot += c;
            mp += c * (float)p;
            mv += c * ((float)k - g->c0);
        }
    }
    if (tot > TRK_TINY) {
        mp /= tot;
        mv /= tot;
    }
    shift_f = (mp + (mv * ratio)) - g->half;
    recentre = (int32_t)floorf(shift_f + 0.5f);
    nr = sbr_track_priv_region_weights(m, axis, *origin + (g->half * g->s), ridx, rw);
    (void)memset(out, 0, (size_t)g->w * (size_t)g->v * sizeof(float));
    for (k = 0u; k < g->v; k++) {
        const float sk = (((float)k - g->c0) * ratio) - (float)recentre;
        const float fl = floorf(sk);
        const float f = sk - fl;
        const int32_t sh = (int32_t)fl;
        for (j = 0u; j < g->v; j++) {
            float t = 0.0f;
            for (r = 0u; r < nr; r++) {
                t += rw[r] * tab[((size_t)ridx[r] * vv) + ((size_t)j * g->v) + k];
            }
            if (t > 0.0f) {
                trk_shift_add(g, d, j, k, sh, t * (1.0f - f), t * f, out);
            }
        }
    }
    trk_normalise(out, (size_t)g->w * (size_t)g->v);
    (void)memcpy(d, out, (size_t)g->w * (size_t)g->v * sizeof(float));
    *origin += (float)recentre * g->s;
}

/* Detection likelihood of one axis at position channel p. */
static float trk_lik(const trk_geo_t *g, float origin, uint32_t p, float z, float w)
{
    const float x = origin + ((float)p * g->s);
    return (1.0f - w) + (w * sbr_track_priv_kernel(x - z, g->kw));
}

/* Update one axis with a detection. If the prediction gave the detection (next to) no
   probability, the position is taken from the detection alone and the velocity marginal
   is kept (the density would otherwise collapse to rounding noise). */
void sbr_track_priv_update_axis(const trk_geo_t *g, float *d, float origin, float z, float w,
                            float *vel_marg)
{
    float total = 0.0f;
    float before = 0.0f;
    uint32_t p;
    uint32_t k;
    for (k = 0u; k < g->v; k++) {
        vel_marg[k] = 0.0f;
    }
    for (p = 0u; p < g->w; p++) {
        const float l = trk_lik(g, origin, p, z, w);
        for (k = 0u; k < g->v; k++) {
            const size_t i = ((size_t)p * g->v) + k;
            before += d[i];
            vel_marg[k] += d[i];
            d[i] *= l;
            total += d[i];
        }
    }
    if (total <= (1e-6f * before)) {
        for (p = 0u; p < g->w; p++) {
            const float l = trk_lik(g, origin, p, z, 1.0f);
            for (k = 0u; k < g->v; k++) {
                d[((size_t)p * g->v) + k] = l * vel_marg[k];
            }
        }
    }
    trk_normalise(d, (size_t)g->w * (size_t)g->v);
}

/* A new density on one axis: the detection's kernel times the region's velocity prior. */
void sbr_track_priv_birth_axis(const sbr_track_t *trk, const trk_geo_t *g, uint32_t axis, float *d,
                           float *origin, float z)
{
    const sbr_track_model_t *m = trk->cfg.model;
    const float *tab = sbr_track_priv_table(m, axis, 1);
    uint32_t ridx[3];
    float rw[3];
    uint32_t nr;
    float prior[SBR_TRACK_MAX_VEL];
    uint32_t p;
    uint32_t k;
    uint32_t r;
    (void)memset(prior, 0, sizeof(prior));
    nr = sbr_track_priv_region_weights(m, axis, z, ridx, rw);
    for (k = 0u; k < g->v; k++) {
        for (r = 0u; r < nr; r++) {
            prior[k] += rw[r] * tab[((size_t)ridx[r] * g->v) + k];
        }
    }
    *origin = z - (g->half * g->s);
    for (p = 0u; p < g->w; p++) {
        const float l = trk_lik(g, *origin, p, z, 1.0f);
        for (k = 0u; k < g->v; k++) {
            d[((size_t)p * g->v) + k] = l * prior[k];
        }
    }
    trk_normalise(d, (size_t)g->w * (size_t)g->v);
}

/* Mean of channels [c - r, c + r] of a vector, as a channel index (the decoded mode's
   neighbourhood: unbiased for a symmetric blob, unlike a 3-channel window on a density
   that is not a single cos² encoding). */
static float trk_local_mean(const float *m, uint32_t len, float c, uint32_t r)
{
    const int32_t ci = (int32_t)floorf(c + 0.5f);
    int32_t lo = ci - (int32_t)r;
    int32_t hi = ci + (int32_t)r;
    int32_t i;
    float sw = 0.0f;
    float s1 = 0.0f;
    float res = c;
    if (lo < 0) {
        lo = 0;
    }
    if (hi > ((int32_t)len - 1)) {
        hi = (int32_t)len - 1;
    }
    for (i = lo; i <= hi; i++) {
        sw += m[i];
        s1 += m[i] * (float)i;
    }
    if (sw > TRK_TINY) {
        res = s1 / sw;
    }
    return res;
}

/* Decode one channel vector, in channel units: the strongest valid 3-channel window
   (sbr_channel_decode()) locates the mode, the mean of its neighbourhood (`radius`
   channels each side) refines it; without a valid window, the mean of the whole vector.
   `cert` gets the window's sum (clamped to 1; 0 without a window). */
static float trk_decode_vec(const float *vec, uint32_t len, uint32_t radius, float *cert)
{
    sbr_channel_config_t cc;
    sbr_channel_mode_t mode;
    uint32_t cnt = 0u;
    float res;
    cc.first_centre = 0.0f;
    cc.spacing = 1.0f;
    cc.count = len;
    cc.overlap = 3u;
    *cert = 0.0f;
    (void)sbr_channel_decode(&cc, vec, len, 0.0f, &mode, 1u, &cnt);
    if (cnt == 1u) {
        res = trk_local_mean(vec, len, mode.value, radius);
        *cert = mode.certainty;
        if (*cert > 1.0f) {
            *cert = 1.0f;
        }
    } else {
        const uint32_t mid = len / 2u;
        res = trk_local_mean(vec, len, (float)mid, len);
    }
    return res;
}

/* Decode position and velocity of one axis from its position and velocity marginals;
   the position's neighbourhood is the detection kernel's half width plus one channel. */
void sbr_track_priv_decode_axis(const trk_geo_t *g, const float *d, float origin, float *pos,
                            float *vel, float *cert)
{
    float m[SBR_TRACK_MAX_WINDOW];
    float mv[SBR_TRACK_MAX_VEL];
    const uint32_t r = (uint32_t)ceilf((0.5f * g->kw) / g->s) + 1u;
    float vcert = 0.0f;
    uint32_t p;
    uint32_t k;
    (void)sbr_track_priv_marginal(d, g, m);
    for (k = 0u; k < g->v; k++) {
        mv[k] = 0.0f;
    }
    for (p = 0u; p < g->w; p++) {
        for (k = 0u; k < g->v; k++) {
            mv[k] += d[((size_t)p * g->v) + k];
        }
    }
    *pos = origin + (trk_decode_vec(m, g->w, r, cert) * g->s);
    *vel = (trk_decode_vec(mv, g->v, 3u, &vcert) - g->c0) * g->s;
}
