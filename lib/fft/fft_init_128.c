/* SPDX-License-Identifier: MIT */
/* sbr_fft_init_128(): the FFT instance of length 128 over its constant tables. */
#include "fft_internal.h"

/* One translation unit per length, so the linker keeps only the tables in use. */
sbr_status_t sbr_fft_init_128(sbr_fft_t *fft)
{
    return sbr_fft_priv_setup(fft, 128u, sbr_fft_bitrev_128, sbr_fft_tw_8, sbr_fft_tw_32, NULL, NULL);
}
