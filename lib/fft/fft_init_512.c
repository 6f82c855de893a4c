/* SPDX-License-Identifier: MIT */
/* sbr_fft_init_512(): the FFT instance of length 512 over its constant tables. */
#include "fft_internal.h"

/* One translation unit per length, so the linker keeps only the tables in use. */
sbr_status_t sbr_fft_init_512(sbr_fft_t *fft)
{
    return sbr_fft_priv_setup(fft, 512u, sbr_fft_bitrev_512, sbr_fft_tw_8, sbr_fft_tw_32, sbr_fft_tw_128, NULL);
}
