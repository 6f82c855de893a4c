/* SPDX-License-Identifier: MIT */
/* Private to the core: the table matcher for a caller that has checked its prototype
   table already (the recogniser checks its model with sbr_model_check() before it
   matches, so each of a frame's thousands of queries need not check every prototype
   again). Not installed. */
#ifndef SBR_FD_INTERNAL_H
#define SBR_FD_INTERNAL_H

#include "sbr/fd.h"

/* sbr_fd_match_table() for a table whose every entry passed sbr_fd_check() and whose
   scales keep query scale / prototype scale finite and positive for the caller's queries
   (the recogniser: prototype scales within SBR_MODEL_MIN_SCALE .. SBR_MODEL_MAX_SCALE,
   sbr_model_check(); query scales of regions of its frames): the same results as
   sbr_fd_match_table() for such a table; per pair it checks only the M.
   proto_mag: NULL, or per prototype its 2M + 1 coefficient magnitudes from
   sbr_fd_priv_magnitudes() (the screening then reads them instead of computing them per
   pair; the same sums, bit for bit). */
sbr_status_t sbr_fd_priv_match_checked_table(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                             const sbr_fd_t *query, const sbr_fd_t *protos,
                                             const float *proto_mag, uint32_t count,
                                             sbr_complex_t *work, uint32_t work_len,
                                             sbr_fd_match_t *results, uint32_t *best);

/* |c[k]| of a descriptor's 2M + 1 coefficients, as the screening computes them. */
void sbr_fd_priv_magnitudes(const sbr_fd_t *fd, float *mag);

#endif /* SBR_FD_INTERNAL_H */
