/* SPDX-License-Identifier: MIT */
/* sbr_fft_init_64(): the FFT instance of length 64 over its constant tables. */
#include "fft_internal.h"

/* One translation unit per length, so the linker keeps only the tables in use. */
sbr_status_t sbr_fft_init_64(sbr_fft_t *fft)
{
    return sbr_fft_priv_setup(fft, 64u, sbr_fft_bitrev_64, sbr_fft_tw_4, sbr_fft_tw_16, NULL, NULL);
}
