/* SPDX-License-Identifier: MIT */
/* Fourier-descriptor matching over a prototype table (sbr_fd_match_table() and the
   prepared table, sbr_fd_table_init()): four prototypes at a time through the four-lane transform
   (fd_fft_lanes.c), or pair by pair when the work buffer is too small for the
   lanes. Layout of `work` for the lanes (as floats): re[4P], im[4P], P / 2 complex
   twiddles, then P floats for the screening's query magnitudes (SBR_FD_TABLE_WORK_LEN =
   5P complex). */
#include "sbr/fd.h"
#include "fd_match.h"
#include "fd_fft_lanes.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "../common/sbr_util.h"

/* conj(Q(n)) C(n) of four consecutive prototypes (FD_LANES = 4): per coefficient, the
   four prototypes' values are loaded one by one (straight-line code, which compilers pack
   into one vector on SIMD hosts) and the products are stored as whole-lane groups,
   instead of 2 x 4 scattered single stores. */
static void lanes_products(const sbr_fd_t *query, const sbr_fd_t *const protos[FD_LANES],
                           const uint32_t *pos, float *re, float *im)
{
    const uint32_t n = (2u * query->m) + 1u;
    uint32_t k;
    for (k = 0u; k < n; k++) {
        const float qr = query->c[k].re;
        const float qi = query->c[k].im;
        const sbr_complex_t c0 = protos[0]->c[k];
        const sbr_complex_t c1 = protos[1]->c[k];
        const sbr_complex_t c2 = protos[2]->c[k];
        const sbr_complex_t c3 = protos[3]->c[k];
        const float cr[FD_LANES] = {c0.re, c1.re, c2.re, c3.re};
        const float ci[FD_LANES] = {c0.im, c1.im, c2.im, c3.im};
        float *r = &re[pos[k]];
        float *m = &im[pos[k]];
        uint32_t b;
        for (b = 0u; b < FD_LANES; b++) {
            r[b] = (qr * cr[b]) + (qi * ci[b]);
        }
        for (b = 0u; b < FD_LANES; b++) {
            m[b] = (qr * ci[b]) - (qi * cr[b]);
        }
    }
}

/* The lanes' inputs: the products of the query with each prototype at their bit-reversed
   positions, zero elsewhere (only the gap n = M+1 .. P-M-1 needs clearing after the
   products are placed; unused lanes get zero input, their results are discarded). */
static void lanes_fill(const sbr_fft_t *fft, const sbr_fd_t *query, const lane_batch_t *bt,
                       const uint32_t *pos, float *re, float *im)
{
    const uint32_t size = fft->n;
    uint32_t b;
    uint32_t k;
    for (k = query->m + 1u; k < (size - query->m); k++) {
        const uint32_t at = (uint32_t)fft->bitrev[k] * FD_LANES;
        for (b = 0u; b < FD_LANES; b++) {
            re[at + b] = 0.0f;
            im[at + b] = 0.0f;
        }
    }
    for (b = bt->valid; b < FD_LANES; b++) {
        for (k = 0u; k < size; k++) {
            re[(k * FD_LANES) + b] = 0.0f;
            im[(k * FD_LANES) + b] = 0.0f;
        }
    }
    if (bt->valid == FD_LANES) {
        lanes_products(query, bt->lane, pos, re, im);
    } else {
        for (b = 0u; b < bt->valid; b++) {
            sbr_fd_priv_write_products(query, bt->lane[b], pos, &re[b], &im[b]);
        }
    }
}

#if SBR_UTIL_SCALAR_CORE == 0
/* The results of a transformed batch from each lane's correlation peak and its two
   neighbours; the refined lags' correlations of the batch in one four-lane evaluation
   (lanes not refined evaluate lag 0 of the first prototype, unused). */
static void lanes_finish(uint32_t size, const sbr_fd_match_config_t *cfg, const sbr_fd_t *query,
                         const lane_batch_t *bt, int inv, float cb, const float *re,
                         const float *im, const uint32_t *best, sbr_fd_match_t *results)
{
    sbr_complex_t around[FD_LANES][3];
    int found[FD_LANES];
    int refined[FD_LANES];
    const sbr_fd_t *lane[FD_LANES];
    float lag[FD_LANES];
    sbr_complex_t at_d[FD_LANES];
    uint32_t any = 0u;
    uint32_t b;
    uint32_t k;
    for (b = 0u; b < FD_LANES; b++) {
        float d = 0.0f;
        lane[b] = bt->lane[0];
        lag[b] = 0.0f;
        refined[b] = 0;
        if (b < bt->valid) {
            /* size is a power of two (a valid FFT instance) */
            const uint32_t at[3] = {(best[b] + size - 1u) & (size - 1u), best[b],
                                    (best[b] + 1u) & (size - 1u)};
            for (k = 0u; k < 3u; k++) {
                around[b][k].re = re[(at[k] * FD_LANES) + b];
                around[b][k].im = im[(at[k] * FD_LANES) + b];
            }
            found[b] = sbr_fd_priv_found_any(inv, cb, around[b][1]);
            refined[b] = sbr_fd_priv_refine_offset(cfg, found[b], around[b], &d);
            if (refined[b] != 0) {
                lane[b] = bt->lane[b];
                lag[b] = (float)best[b] + d;
                any++;
            }
        }
    }
    if (any > 0u) {
        sbr_fd_priv_corr_at_lanes(query, lane, lag, size, at_d);
    }
    for (b = 0u; b < bt->valid; b++) {
        sbr_fd_priv_finish_match(size, cfg, query, bt->lane[b], found[b], best[b], around[b],
                                 (refined[b] != 0) ? &at_d[b] : NULL, &results[bt->idx[b]]);
    }
}
#else
/* The results of a transformed batch from each lane's correlation peak and its two
   neighbours, each pair refined on its own (a core without a vector unit, where four
   lanes side by side cost more). */
static void lanes_finish(uint32_t size, const sbr_fd_match_config_t *cfg, const sbr_fd_t *query,
                         const lane_batch_t *bt, int inv, float cb, const float *re,
                         const float *im, const uint32_t *best, sbr_fd_match_t *results)
{
    uint32_t b;
    uint32_t k;
    for (b = 0u; b < bt->valid; b++) {
        sbr_complex_t around[3];
        /* size is a power of two (a valid FFT instance) */
        const uint32_t at[3] = {(best[b] + size - 1u) & (size - 1u), best[b],
                                (best[b] + 1u) & (size - 1u)};
        for (k = 0u; k < 3u; k++) {
            around[k].re = re[(at[k] * FD_LANES) + b];
            around[k].im = im[(at[k] * FD_LANES) + b];
        }
        sbr_fd_priv_finish_match(size, cfg, query, bt->lane[b],
                                 sbr_fd_priv_found_any(inv, cb, around[1]), best[b], around, NULL,
                                 &results[bt->idx[b]]);
    }
}
#endif

static sbr_status_t match_table_lanes(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                      const sbr_fd_t *query, const sbr_fd_t *protos,
                                      uint32_t count, const fd_table_t *tb, sbr_complex_t *work,
                                      sbr_fd_match_t *results)
{
    const uint32_t size = fft->n;
    /* lane buffers: the first 4P complex values of `work` seen as 8P floats */
    float *re = (float *)(void *)work;
    float *im = &re[size * FD_LANES];
    sbr_complex_t *tw = &work[size * FD_LANES];       /* P / 2 twiddles after re, im */
    /* the query's magnitudes in the last P floats (2M + 1 <= P) */
    float *qmag = (float *)(void *)&work[(size * FD_LANES) + (size / 2u)];
    const int inv = sbr_fd_priv_mode_invariant(cfg);
    const float cb = sbr_fd_priv_rotation_cos_bound(cfg);
    const float level = sbr_fd_priv_screen_level(cfg);
    uint32_t best[FD_LANES];
    float check[FD_LANES];
    uint32_t pos[(2u * SBR_FD_MAX_M) + 1u];
    uint32_t j;
    uint32_t i = 0u;
    sbr_status_t header = SBR_OK;

    sbr_fd_priv_product_positions(query->m, size, fft->bitrev, FD_LANES, pos);
    for (j = 0u; j < (size / 2u); j++) {
        const float a = (SBR_TWO_PI_F * (float)j) / (float)size;
        tw[j].re = cosf(a);
        tw[j].im = sinf(a);
    }
    if (level > 0.0f) {
        sbr_fd_priv_magnitudes(query, qmag);
    }
    while ((i < count) && (header == SBR_OK)) {
        /* each prototype is checked as sbr_fd_check() does when it is gathered; a bad
           one's status is returned after the batch gathered before it is transformed
           (whose correlations are checked for overflow), so the first bad prototype in
           table order decides the status */
        lane_batch_t bt;
        sbr_fd_priv_lanes_gather(query, protos, count, qmag, level, tb, &i, &bt, results, &header);
        if (bt.valid > 0u) {
            uint32_t b;
            lanes_fill(fft, query, &bt, pos, re, im);
            sbr_fd_priv_lanes_inverse(size, tw, re, im);
            sbr_fd_priv_lanes_peaks(size, inv, cb, re, im, best, check);
            for (b = 0u; b < bt.valid; b++) {
                if ((isfinite(check[b]) == 0) || (check[b] < 0.0f)) {
                    return SBR_ERR_RANGE;
                }
            }
            lanes_finish(size, cfg, query, &bt, inv, cb, re, im, best, results);
        }
    }
    return header;
}

/* sbr_fd_match_table(); trusted: the prototypes were checked by sbr_fd_check() before
   (fd_internal.h), so only the per-pair conditions are checked here. */
static sbr_status_t match_table(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                const sbr_fd_t *query, const sbr_fd_t *protos, uint32_t count,
                                const fd_table_t *tb, sbr_complex_t *work, uint32_t work_len,
                                sbr_fd_match_t *results, uint32_t *best)
{
    const int trusted = tb->trusted;
    sbr_status_t st = sbr_fd_priv_check_match_args(fft, cfg, query, work, work_len, results);
    uint32_t i;
    uint32_t b = 0u;

    if (st != SBR_OK) {
        return st;
    }
    if ((protos == NULL) || (best == NULL)) {
        return SBR_ERR_NULL;
    }
    if (count == 0u) {
        return SBR_ERR_SIZE;
    }
    if (work_len >= SBR_FD_TABLE_WORK_LEN(fft->n)) {
        st = match_table_lanes(fft, cfg, query, protos, count, tb, work, results);
        if (st != SBR_OK) {
            return st;
        }
    } else {
        for (i = 0u; i < count; i++) {
            st = (trusted != 0) ? sbr_fd_priv_check_trusted(query, &protos[i]) : sbr_fd_priv_check_proto(query, &protos[i]);
            if (st != SBR_OK) {
                return st;
            }
            st = sbr_fd_priv_match_screened(fft, cfg, query, &protos[i], work, &results[i]);
            if (st != SBR_OK) {
                return st;
            }
        }
    }
    for (i = 1u; i < count; i++) {
        if (results[i].error < results[b].error) {
            b = i;
        }
    }
    *best = b;
    return SBR_OK;
}

sbr_status_t sbr_fd_match_table(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                const sbr_fd_t *query, const sbr_fd_t *protos, uint32_t count,
                                sbr_complex_t *work, uint32_t work_len, sbr_fd_match_t *results,
                                uint32_t *best)
{
    const fd_table_t tb = {0, NULL};
    return match_table(fft, cfg, query, protos, count, &tb, work, work_len, results, best);
}

/* "FDTB": a prepared table. */
#define FD_TABLE_MAGIC 0x46445442u

/* The integrity word over the bytes before it. */
static uint32_t table_checksum(const sbr_fd_table_t *t)
{
    return sbr_util_fnv1a(t, offsetof(sbr_fd_table_t, check));
}

static int scale_ok(float s)
{
    return ((s >= SBR_FD_TABLE_MIN_SCALE) && (s <= SBR_FD_TABLE_MAX_SCALE)) ? 1 : 0;
}

sbr_status_t sbr_fd_table_init(sbr_fd_table_t *table, const sbr_fd_t *protos, uint32_t count,
                               float *mags, size_t mags_len)
{
    uint32_t i;
    uint32_t m;
    if (table == NULL) {
        return SBR_ERR_NULL;
    }
    (void)memset(table, 0, sizeof *table);
    if ((protos == NULL) || (mags == NULL)) {
        return SBR_ERR_NULL;
    }
    if (count == 0u) {
        return SBR_ERR_SIZE;
    }
    m = protos[0].m;
    for (i = 0u; i < count; i++) {
        float e;
        if ((sbr_fd_check(&protos[i], &e) != SBR_OK) || (protos[i].m != m) ||
            (scale_ok(protos[i].scale) == 0)) {
            return SBR_ERR_RANGE;
        }
    }
    if (mags_len < SBR_FD_TABLE_MAGS_LEN(count, m)) {
        return SBR_ERR_SIZE;
    }
    for (i = 0u; i < count; i++) {
        sbr_fd_priv_magnitudes(&protos[i], &mags[(size_t)i * ((2u * (size_t)m) + 1u)]);
    }
    table->protos = protos;
    table->mags = mags;
    table->count = count;
    table->m = m;
    table->magic = FD_TABLE_MAGIC;
    table->check = table_checksum(table);
    return SBR_OK;
}

sbr_status_t sbr_fd_match_prepared(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                   const sbr_fd_table_t *table, uint32_t first, uint32_t count,
                                   const sbr_fd_t *query, sbr_complex_t *work, uint32_t work_len,
                                   sbr_fd_match_t *results, uint32_t *best)
{
    fd_table_t tb;
    if ((table == NULL) || (query == NULL)) {
        return SBR_ERR_NULL;
    }
    if ((table->magic != FD_TABLE_MAGIC) || (table->check != table_checksum(table))) {
        return SBR_ERR_STATE;
    }
    if ((count == 0u) || (first >= table->count) || (count > (table->count - first))) {
        return SBR_ERR_SIZE;
    }
    if (scale_ok(query->scale) == 0) {
        return SBR_ERR_RANGE;
    }
    tb.trusted = 1;
    tb.pmag = &table->mags[(size_t)first * ((2u * (size_t)table->m) + 1u)];
    return match_table(fft, cfg, query, &table->protos[first], count, &tb, work, work_len, results,
                       best);
}
