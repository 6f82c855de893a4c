/* SPDX-License-Identifier: MIT */
/* sbr_fft_init_256(): the FFT instance of length 256 over its constant tables. */
#include "fft_internal.h"

/* One translation unit per length, so the linker keeps only the tables in use. */
sbr_status_t sbr_fft_init_256(sbr_fft_t *fft)
{
    return sbr_fft_priv_setup(fft, 256u, sbr_fft_bitrev_256, sbr_fft_tw_4, sbr_fft_tw_16, sbr_fft_tw_64, NULL);
}
