/* SPDX-License-Identifier: MIT */
/* sbr_fft_init(): the instance of a supported length, from the per-length set-up
   functions. */
#include "fft_internal.h"

sbr_status_t sbr_fft_init(sbr_fft_t *fft, uint32_t n)
{
    sbr_status_t st;

    if (fft == NULL) {
        return SBR_ERR_NULL;
    }
    switch (n) {
    case 16u:
        st = sbr_fft_init_16(fft);
        break;
    case 32u:
        st = sbr_fft_init_32(fft);
        break;
    case 64u:
        st = sbr_fft_init_64(fft);
        break;
    case 128u:
        st = sbr_fft_init_128(fft);
        break;
    case 256u:
        st = sbr_fft_init_256(fft);
        break;
    case 512u:
        st = sbr_fft_init_512(fft);
        break;
    case 1024u:
        st = sbr_fft_init_1024(fft);
        break;
    default:
        /* Leave an instance that every transform rejects. */
        (void)sbr_fft_priv_setup(fft, 0u, NULL, NULL, NULL, NULL, NULL);
        fft->check = 0u;
        st = SBR_ERR_SIZE;
        break;
    }
    return st;
}
