/* SPDX-License-Identifier: MIT */
/* The FFT instance set-up shared by every length: tables, stage count, integrity word. */
#include "fft_internal.h"
#include "../common/sbr_util.h"

sbr_status_t sbr_fft_priv_setup(sbr_fft_t *fft, uint32_t n, const uint16_t *bitrev,
                                const sbr_complex_t *tw0, const sbr_complex_t *tw1,
                                const sbr_complex_t *tw2, const sbr_complex_t *tw3)
{
    uint32_t log2n = 0u;
    uint32_t stages;
    uint32_t span;

    if (fft == NULL) {
        return SBR_ERR_NULL;
    }
    while ((1u << log2n) < n) {
        log2n++;
    }
    /* The first stage is radix-4 without twiddles for even log2(N), radix-8 for odd;
       every further stage is radix-4 with twiddles of span 4, 16, ... or 8, 32, ... */
    if ((log2n % 2u) == 0u) {
        span = 4u;
    } else {
        span = 8u;
    }
    stages = 0u;
    while (span < n) {
        stages++;
        span *= 4u;
    }
    fft->n = n;
    fft->log2n = log2n;
    fft->stages = stages;
    fft->bitrev = bitrev;
    fft->twiddle[0] = tw0;
    fft->twiddle[1] = tw1;
    fft->twiddle[2] = tw2;
    fft->twiddle[3] = tw3;
    fft->check = sbr_fft_priv_seal(fft);
    return SBR_OK;
}

uint32_t sbr_fft_priv_seal(const sbr_fft_t *fft)
{
    const uint32_t mul = 0x9E3779B1u; /* odd: every step is a bijection of the word */
    uint32_t h = SBR_FFT_CHECK_KEY ^ fft->n;
    uint32_t s;
    h = (h * mul) ^ fft->log2n;
    h = (h * mul) ^ fft->stages;
    h = (h * mul) ^ sbr_util_addr32(fft->bitrev);
    for (s = 0u; s < SBR_FFT_MAX_STAGES; s++) {
        h = (h * mul) ^ sbr_util_addr32(fft->twiddle[s]);
    }
    return h;
}
