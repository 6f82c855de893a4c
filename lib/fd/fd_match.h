/* SPDX-License-Identifier: MIT */
/* Private to lib/fd: what the pair matcher (fd_match.c) and the table matcher
   (fd_table.c) share. Not installed. */
#ifndef SBR_FD_MATCH_H
#define SBR_FD_MATCH_H

#include "sbr/fd.h"
#include "fd_fft_lanes.h"

/* Prototypes transformed side by side by the table matcher (fd_fft_lanes.h). */
#define FD_LANES SBR_FFT_LANES

/* The four-lane batch of match_table_lanes(): up to four prototypes and their indices. */
typedef struct lane_batch_s {
    const sbr_fd_t *lane[FD_LANES];
    uint32_t idx[FD_LANES];
    uint32_t valid;
} lane_batch_t;

/* How a table is matched: trusted (a prepared table, sbr_fd_table_init(): every entry checked once) or not,
   and its entries' coefficient magnitudes when the owner computed them (NULL: computed
   per pair by the screening). */
typedef struct fd_table_s {
    int trusted;
    const float *pmag; /* per entry 2M + 1 values, query_magnitudes() of it */
} fd_table_t;

/* |c[k]| of a descriptor's 2M + 1 coefficients, as the screening computes them. */
void sbr_fd_priv_magnitudes(const sbr_fd_t *fd, float *mag);
/* Everything a match needs except the prototype: SBR_OK or the status. */
sbr_status_t sbr_fd_priv_check_match_args(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                          const sbr_fd_t *query, const sbr_complex_t *work,
                                          uint32_t work_len, const void *result);
/* A prototype of a trusted table: only its M against the query's. */
sbr_status_t sbr_fd_priv_check_trusted(const sbr_fd_t *query, const sbr_fd_t *proto);
/* A prototype must be a valid descriptor with the query's M. */
sbr_status_t sbr_fd_priv_check_proto(const sbr_fd_t *query, const sbr_fd_t *proto);
/* One match (checked arguments, prototype included) after the screening. */
sbr_status_t sbr_fd_priv_match_screened(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                        const sbr_fd_t *query, const sbr_fd_t *proto,
                                        sbr_complex_t *work, sbr_fd_match_t *result);
/* Where conj(Q(n)) C(n), n = -M..M, goes in the re/im arrays (scale * place). */
void sbr_fd_priv_product_positions(uint32_t m, uint32_t size, const uint16_t *bitrev,
                                   uint32_t scale, uint32_t *pos);
/* conj(Q(n)) C(n) at the given positions. */
void sbr_fd_priv_write_products(const sbr_fd_t *query, const sbr_fd_t *proto, const uint32_t *pos,
                                float *re, float *im);
/* Whether a pair is refined and the refined lag's offset d from the grid peak. */
int sbr_fd_priv_refine_offset(const sbr_fd_match_config_t *cfg, int found,
                              const sbr_complex_t around[3], float *d);
/* Each lane's energy over `size` lags (re, im: lag l of lane b at l FD_LANES + b), summed
   in lag order (fd_lanes.c). */
void sbr_fd_priv_lanes_energy(uint32_t size, const float *re, const float *im,
                              float check[FD_LANES]);
/* r at a fractional lag of FD_LANES prototypes, each lane equal to the one-pair value. */
void sbr_fd_priv_corr_at_lanes(const sbr_fd_t *q, const sbr_fd_t *const p[FD_LANES],
                               const float lag[FD_LANES], uint32_t size, sbr_complex_t out[FD_LANES]);
/* Refinement and the result, given the grid peak, r at best - 1, best, best + 1 and r at
   the refined lag when the caller found it (at_d; NULL: found here). */
void sbr_fd_priv_finish_match(uint32_t size, const sbr_fd_match_config_t *cfg,
                              const sbr_fd_t *query, const sbr_fd_t *proto, int found,
                              uint32_t best, const sbr_complex_t around[3],
                              const sbr_complex_t *at_d, sbr_fd_match_t *result);
/* 1 for the rotation-invariant mode. */
int sbr_fd_priv_mode_invariant(const sbr_fd_match_config_t *cfg);
/* cos of the rotation bound, or -2 (no bound). */
float sbr_fd_priv_rotation_cos_bound(const sbr_fd_match_config_t *cfg);
/* The level the magnitude sum must reach, or a negative value (no screening). */
float sbr_fd_priv_screen_level(const sbr_fd_match_config_t *cfg);
/* The grid peak of each of FD_LANES transformed lanes and its overflow check value. */
void sbr_fd_priv_lanes_peaks(uint32_t size, int inv, float cb, const float *re, const float *im,
                             uint32_t best[FD_LANES], float check[FD_LANES]);
/* The next (up to) four prototypes that pass the header check and the screening. */
void sbr_fd_priv_lanes_gather(const sbr_fd_t *query, const sbr_fd_t *protos, uint32_t count,
                              const float *qmag, float level, const fd_table_t *tb, uint32_t *i,
                              lane_batch_t *bt, sbr_fd_match_t *results, sbr_status_t *header);
/* Was a lane's peak admissible (a value above the outside mark)? */
int sbr_fd_priv_found_any(int inv, float cb, sbr_complex_t at_best);

#endif /* SBR_FD_MATCH_H */
