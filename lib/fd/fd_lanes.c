/* SPDX-License-Identifier: MIT */
/* The table matcher's four-lane helpers (fd_match.h): the correlation at a fractional
   lag of four prototypes side by side, and the lanes' energies. */
#include "fd_match.h"

#include <math.h>

#include "../common/sbr_util.h"

/* fd_match.c's corr_at() (r at a fractional lag) of FD_LANES prototypes at their own
   lags: the same operations in the same order on each lane (whole-lane steps, which
   compilers pack into vectors on SIMD hosts), so each lane's value equals corr_at()'s bit
   for bit. */
void sbr_fd_priv_corr_at_lanes(const sbr_fd_t *q, const sbr_fd_t *const p[FD_LANES],
                               const float lag[FD_LANES], uint32_t size, sbr_complex_t out[FD_LANES])
{
    const uint32_t m = q->m;
    float wr[FD_LANES];
    float wi[FD_LANES];
    float nr[FD_LANES]; /* w^n */
    float ni[FD_LANES];
    float rr[FD_LANES];
    float ri[FD_LANES];
    uint32_t b;
    uint32_t n;

    for (b = 0u; b < FD_LANES; b++) {
        const float a = (SBR_TWO_PI_F * lag[b]) / (float)size;
        wr[b] = cosf(a);
        wi[b] = sinf(a);
        nr[b] = wr[b];
        ni[b] = wi[b];
        rr[b] = 0.0f;
        ri[b] = 0.0f;
    }
    for (n = 1u; n <= m; n++) {
        const sbr_complex_t qp = q->c[m + n];
        const sbr_complex_t qn = q->c[m - n];
        const float cpr[FD_LANES] = {p[0]->c[m + n].re, p[1]->c[m + n].re, p[2]->c[m + n].re,
                                     p[3]->c[m + n].re};
        const float cpi[FD_LANES] = {p[0]->c[m + n].im, p[1]->c[m + n].im, p[2]->c[m + n].im,
                                     p[3]->c[m + n].im};
        const float cnr[FD_LANES] = {p[0]->c[m - n].re, p[1]->c[m - n].re, p[2]->c[m - n].re,
                                     p[3]->c[m - n].re};
        const float cni[FD_LANES] = {p[0]->c[m - n].im, p[1]->c[m - n].im, p[2]->c[m - n].im,
                                     p[3]->c[m - n].im};
        float pr[FD_LANES];
        float pim[FD_LANES];
        float xr[FD_LANES];
        float xim[FD_LANES];
        float t[FD_LANES];
        /* conj(Q) C for +n and -n */
        for (b = 0u; b < FD_LANES; b++) {
            pr[b] = (qp.re * cpr[b]) + (qp.im * cpi[b]);
        }
        for (b = 0u; b < FD_LANES; b++) {
            pim[b] = (qp.re * cpi[b]) - (qp.im * cpr[b]);
        }
        for (b = 0u; b < FD_LANES; b++) {
            xr[b] = (qn.re * cnr[b]) + (qn.im * cni[b]);
        }
        for (b = 0u; b < FD_LANES; b++) {
            xim[b] = (qn.re * cni[b]) - (qn.im * cnr[b]);
        }
        for (b = 0u; b < FD_LANES; b++) {
            rr[b] += ((pr[b] * nr[b]) - (pim[b] * ni[b])) + ((xr[b] * nr[b]) + (xim[b] * ni[b]));
        }
        for (b = 0u; b < FD_LANES; b++) {
            ri[b] += ((pr[b] * ni[b]) + (pim[b] * nr[b])) + ((xim[b] * nr[b]) - (xr[b] * ni[b]));
        }
        for (b = 0u; b < FD_LANES; b++) {
            t[b] = (nr[b] * wr[b]) - (ni[b] * wi[b]);
        }
        for (b = 0u; b < FD_LANES; b++) {
            ni[b] = (nr[b] * wi[b]) + (ni[b] * wr[b]);
        }
        for (b = 0u; b < FD_LANES; b++) {
            nr[b] = t[b];
        }
    }
    for (b = 0u; b < FD_LANES; b++) {
        out[b].re = rr[b];
        out[b].im = ri[b];
    }
}

/* Each lane's energy, sum over the lags of re^2 + im^2 in lag order: whole-lane steps in
   local sums (one vector operation each on SIMD hosts). */
void sbr_fd_priv_lanes_energy(uint32_t size, const float *re, const float *im,
                              float check[FD_LANES])
{
    float ck[FD_LANES];
    uint32_t l;
    uint32_t b;
    for (b = 0u; b < FD_LANES; b++) {
        ck[b] = 0.0f;
    }
    for (l = 0u; l < size; l++) {
        const float *lr = &re[l * FD_LANES];
        const float *li = &im[l * FD_LANES];
        float e[FD_LANES];
        for (b = 0u; b < FD_LANES; b++) {
            e[b] = (lr[b] * lr[b]) + (li[b] * li[b]);
        }
        for (b = 0u; b < FD_LANES; b++) {
            ck[b] += e[b];
        }
    }
    for (b = 0u; b < FD_LANES; b++) {
        check[b] = ck[b];
    }
}
