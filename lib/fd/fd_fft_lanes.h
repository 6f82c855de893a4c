/* SPDX-License-Identifier: MIT */
/* Private to the core: the inverse FFT of SBR_FFT_LANES transforms side by side, for the
   Fourier-descriptor table matcher (lib/fd/fd_table.c). Not installed.

   A radix-2 transform whose butterflies work on SBR_FFT_LANES independent transforms side
   by side (lane-interleaved arrays: element k of lane b at [k * SBR_FFT_LANES + b]): the
   innermost loop has a fixed trip count over contiguous floats, which compilers map to
   SIMD registers on hosts that have them; on a scalar ECU core it costs the same as one
   transform after another. */
#ifndef SBR_FD_FFT_LANES_H
#define SBR_FD_FFT_LANES_H

#include "sbr/fft.h"

/* Transforms side by side. */
#define SBR_FFT_LANES 4u

/* In-place inverse transform (unscaled) of SBR_FFT_LANES bit-reversed inputs of `size`
   points (a power of two >= 4): re and im hold size * SBR_FFT_LANES floats each; tw the
   size / 2 twiddles e^{+2 pi i j / size}. */
void sbr_fd_priv_lanes_inverse(uint32_t size, const sbr_complex_t *tw, float *re, float *im);

#endif /* SBR_FD_FFT_LANES_H */
