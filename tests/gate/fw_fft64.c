/* SPDX-License-Identifier: MIT */
/* A bare-metal image that uses only the 64-point FFT: the linker must drop the tables
   of the larger lengths (gate_fft_tables_dropped_by_linker). It also runs on the emulated
   Cortex-M4 and checks one transform (a DC input gives N at bin 0). */
#include "sbr/fft.h"

int main(void)
{
    sbr_fft_t fft;
    sbr_complex_t x[64];
    unsigned i;
    for (i = 0; i < 64u; i++) {
        x[i].re = 1.0f;
        x[i].im = 0.0f;
    }
    if (sbr_fft_init_64(&fft) != SBR_OK) {
        return 1;
    }
    if (sbr_fft_forward(&fft, x, x) != SBR_OK) {
        return 2;
    }
    if ((x[0].re != 64.0f) || (x[1].re != 0.0f) || (x[63].im != 0.0f)) {
        return 3;
    }
    return 0;
}
