/* SPDX-License-Identifier: MIT */
#include <sbr/sbr.h>

/* Exit code 0 only if the installed library transforms correctly. */
int main(void)
{
    sbr_fft_t fft;
    sbr_complex_t x[16] = {{0.0f, 0.0f}};
    x[0].re = 1.0f;
    if (sbr_fft_init_16(&fft) != SBR_OK || sbr_fft_forward(&fft, x, x) != SBR_OK) {
        return 1;
    }
    return (x[7].re == 1.0f && x[7].im == 0.0f) ? 0 : 2;
}
