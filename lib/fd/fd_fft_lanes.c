/* SPDX-License-Identifier: MIT */
/* The inverse FFT of four transforms side by side (lane-interleaved arrays), for the
   Fourier-descriptor table matcher (lib/fd/fd_table.c). See fd_fft_lanes.h. */
#include "fd_fft_lanes.h"

/* One radix-2 butterfly on SBR_FFT_LANES transforms: all loads before all stores, so that
   the four lanes form straight-line groups a compiler can keep in one vector register. */
static void lanes_butterfly(float *ar, float *ai, float *br, float *bi, sbr_complex_t w)
{
    float xr[SBR_FFT_LANES];
    float xi[SBR_FFT_LANES];
    float yr[SBR_FFT_LANES];
    float yi[SBR_FFT_LANES];
    float tr[SBR_FFT_LANES];
    float ti[SBR_FFT_LANES];
    uint32_t b;

    for (b = 0u; b < SBR_FFT_LANES; b++) {
        xr[b] = ar[b];
        xi[b] = ai[b];
        yr[b] = br[b];
        yi[b] = bi[b];
    }
    for (b = 0u; b < SBR_FFT_LANES; b++) {
        tr[b] = (yr[b] * w.re) - (yi[b] * w.im);
        ti[b] = (yr[b] * w.im) + (yi[b] * w.re);
    }
    /* one store group per array: the groups stay in program order */
    for (b = 0u; b < SBR_FFT_LANES; b++) {
        ar[b] = xr[b] + tr[b];
    }
    for (b = 0u; b < SBR_FFT_LANES; b++) {
        ai[b] = xi[b] + ti[b];
    }
    for (b = 0u; b < SBR_FFT_LANES; b++) {
        br[b] = xr[b] - tr[b];
    }
    for (b = 0u; b < SBR_FFT_LANES; b++) {
        bi[b] = xi[b] - ti[b];
    }
}

/* The first two radix-2 stages of the decimation-in-time transform on each group of four:
   their twiddles are 1 and i (the inverse transform's e^{+i pi / 2}), so no multiplies.
   Written as whole-lane groups (loads, sums, differences, stores) that compilers keep in
   vector registers. */
static void lanes_first_stages(uint32_t size, float *re, float *im)
{
    uint32_t g;

    for (g = 0u; g < size; g += 4u) {
        float *r = &re[g * SBR_FFT_LANES];
        float *m = &im[g * SBR_FFT_LANES];
        float ar[SBR_FFT_LANES];
        float ai[SBR_FFT_LANES];
        float br[SBR_FFT_LANES];
        float bi[SBR_FFT_LANES];
        float cr[SBR_FFT_LANES];
        float ci[SBR_FFT_LANES];
        float dr[SBR_FFT_LANES];
        float di[SBR_FFT_LANES];
        uint32_t b;
        /* stage 1: (x0 +- x1), (x2 +- x3) */
        for (b = 0u; b < SBR_FFT_LANES; b++) {
            ar[b] = r[b] + r[SBR_FFT_LANES + b];
            ai[b] = m[b] + m[SBR_FFT_LANES + b];
            br[b] = r[b] - r[SBR_FFT_LANES + b];
            bi[b] = m[b] - m[SBR_FFT_LANES + b];
            cr[b] = r[(2u * SBR_FFT_LANES) + b] + r[(3u * SBR_FFT_LANES) + b];
            ci[b] = m[(2u * SBR_FFT_LANES) + b] + m[(3u * SBR_FFT_LANES) + b];
            dr[b] = r[(2u * SBR_FFT_LANES) + b] - r[(3u * SBR_FFT_LANES) + b];
            di[b] = m[(2u * SBR_FFT_LANES) + b] - m[(3u * SBR_FFT_LANES) + b];
        }
        /* stage 2: a +- c, b +- i d */
        for (b = 0u; b < SBR_FFT_LANES; b++) {
            r[b] = ar[b] + cr[b];
        }
        for (b = 0u; b < SBR_FFT_LANES; b++) {
            m[b] = ai[b] + ci[b];
        }
        for (b = 0u; b < SBR_FFT_LANES; b++) {
            r[SBR_FFT_LANES + b] = br[b] - di[b];
        }
        for (b = 0u; b < SBR_FFT_LANES; b++) {
            m[SBR_FFT_LANES + b] = bi[b] + dr[b];
        }
        for (b = 0u; b < SBR_FFT_LANES; b++) {
            r[(2u * SBR_FFT_LANES) + b] = ar[b] - cr[b];
        }
        for (b = 0u; b < SBR_FFT_LANES; b++) {
            m[(2u * SBR_FFT_LANES) + b] = ai[b] - ci[b];
        }
        for (b = 0u; b < SBR_FFT_LANES; b++) {
            r[(3u * SBR_FFT_LANES) + b] = br[b] + di[b];
        }
        for (b = 0u; b < SBR_FFT_LANES; b++) {
            m[(3u * SBR_FFT_LANES) + b] = bi[b] - dr[b];
        }
    }
}

/* In-place inverse transform (unscaled) of SBR_FFT_LANES bit-reversed inputs, size >= 4: the
   first two stages without multiplies, then radix-2 stages. (Fusing pairs of the later
   stages into radix-4 steps was measured slower on x86-64: the compiler spills them.) */
void sbr_fd_priv_lanes_inverse(uint32_t size, const sbr_complex_t *tw, float *re, float *im)
{
    uint32_t half;

    lanes_first_stages(size, re, im);
    for (half = 4u; half < size; half *= 2u) {
        const uint32_t tstep = size / (2u * half);
        uint32_t j;
        for (j = 0u; j < half; j++) {
            const sbr_complex_t w = tw[j * tstep];
            uint32_t i;
            for (i = j; i < size; i += 2u * half) {
                lanes_butterfly(&re[i * SBR_FFT_LANES], &im[i * SBR_FFT_LANES], &re[(i + half) * SBR_FFT_LANES],
                                &im[(i + half) * SBR_FFT_LANES], w);
            }
        }
    }
}
