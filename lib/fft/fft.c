/* SPDX-License-Identifier: MIT */
/* The fixed-size complex FFT (include/sbr/fft.h): forward and inverse transforms of an
   initialised instance. */
#include "fft_internal.h"
#include "../common/sbr_util.h"

#define SBR_FFT_INV 0
#define SBR_FFT_NAME(x) fwd_##x
#include "fft_kernel.inc"
#undef SBR_FFT_INV
#undef SBR_FFT_NAME

#define SBR_FFT_INV 1
#define SBR_FFT_NAME(x) inv_##x
#include "fft_kernel.inc"
#undef SBR_FFT_INV
#undef SBR_FFT_NAME

int sbr_fft_size_supported(uint32_t n)
{
    return ((n >= SBR_FFT_MIN_SIZE) && (n <= SBR_FFT_MAX_SIZE) && ((n & (n - 1u)) == 0u))
               ? 1
               : 0;
}

/* Cheap consistency checks of an instance; catches never-initialised and overwritten
   instances without touching more than a few words. */
sbr_status_t sbr_fft_check(const sbr_fft_t *fft)
{
    uint32_t s;
    uint32_t span;

    if (fft == NULL) {
        return SBR_ERR_NULL;
    }
    if ((sbr_fft_size_supported(fft->n) == 0) || (fft->check != sbr_fft_priv_seal(fft)) ||
        ((1u << (fft->log2n & 31u)) != fft->n) || (fft->bitrev == NULL) ||
        (fft->stages > SBR_FFT_MAX_STAGES)) {
        return SBR_ERR_STATE;
    }
    if ((fft->bitrev[0] != 0u) || (fft->bitrev[1] != (fft->n / 2u))) {
        return SBR_ERR_STATE;
    }
    if ((fft->log2n % 2u) == 0u) {
        span = 4u;
    } else {
        span = 8u;
    }
    for (s = 0u; s < fft->stages; s++) {
        if (fft->twiddle[s] == NULL) {
            return SBR_ERR_STATE;
        }
        span *= 4u;
    }
    if (span != fft->n) {
        return SBR_ERR_STATE;
    }
    return SBR_OK;
}

static sbr_status_t check_instance(const sbr_fft_t *fft, const sbr_complex_t *in,
                                   const sbr_complex_t *out)
{
    sbr_status_t st;

    if ((fft == NULL) || (in == NULL) || (out == NULL)) {
        return SBR_ERR_NULL;
    }
    st = sbr_fft_check(fft);
    if (st != SBR_OK) {
        return st;
    }
    /* Only identical or disjoint buffers are supported. */
    if ((in != out) && (sbr_util_overlap(in, (size_t)fft->n * sizeof(sbr_complex_t), out,
                                         (size_t)fft->n * sizeof(sbr_complex_t)) != 0)) {
        return SBR_ERR_OVERLAP;
    }
    return SBR_OK;
}

sbr_status_t sbr_fft_forward(const sbr_fft_t *fft, const sbr_complex_t *in,
                             sbr_complex_t *out)
{
    const sbr_status_t st = check_instance(fft, in, out);
    if (st == SBR_OK) {
        fwd_run(fft, in, out);
    }
    return st;
}

sbr_status_t sbr_fft_inverse(const sbr_fft_t *fft, const sbr_complex_t *in,
                             sbr_complex_t *out)
{
    const sbr_status_t st = check_instance(fft, in, out);
    if (st == SBR_OK) {
        inv_run(fft, in, out);
    }
    return st;
}
