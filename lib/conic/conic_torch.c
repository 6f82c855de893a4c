/* SPDX-License-Identifier: MIT */
/* Conics: the torchlight pose (the plane a circular light cone hits, from the ellipse it
   draws). See include/sbr/conic.h. */
#include "conic_internal.h"

#include <math.h>

/* Torchlight least squares: weight of the quadratic entries (11, 12, 22: the ellipse's
   elongation, poorly conditioned for distant planes) against the linear and constant
   ones (13, 23, 33: its centre and size). */
#define TORCH_WQ 0.1f

/* Residuals (weighted: off-diagonal entries count twice, as in the Frobenius norm) of
   mu * M(n1, n2, k) against the normalised conic g[6] = {11, 12, 22, 13, 23, 33}, and the
   Jacobian rows (d/dmu, d/dn1, d/dn2, d/dk). */
static float torch_residuals(const float p[4], const float g[6], float r[6], float jac[24])
{
    const float mu = p[0];
    const float n1 = p[1];
    const float n2 = p[2];
    const float k = p[3];
    const float w = 1.41421356f;
    const float model[6] = {k - (n1 * n1), -n1 * n2, k - (n2 * n2), n1, n2, -1.0f};
    const float wt[6] = {TORCH_WQ, TORCH_WQ * w, TORCH_WQ, w, w, 1.0f};
    const float jr[24] = {model[0], -2.0f * mu * n1, 0.0f, mu,
                          model[1], -mu * n2, -mu * n1, 0.0f,
                          model[2], 0.0f, -2.0f * mu * n2, mu,
                          model[3], mu, 0.0f, 0.0f,
                          model[4], 0.0f, mu, 0.0f,
                          model[5], 0.0f, 0.0f, 0.0f};
    float acc = 0.0f;
    uint32_t i;
    uint32_t j;
    for (i = 0u; i < 6u; ++i) {
        r[i] = wt[i] * ((mu * model[i]) - g[i]);
        acc += r[i] * r[i];
        for (j = 0u; j < 4u; ++j) {
            jac[(i * 4u) + j] = wt[i] * jr[(i * 4u) + j];
        }
    }
    return acc;
}

/* Unweighted rms misfit of mu * M(n1, n2, k) against g (the consistency measure). */
static float torch_misfit(const float p[4], const float g[6])
{
    const float model[6] = {p[3] - (p[1] * p[1]), -p[1] * p[2], p[3] - (p[2] * p[2]), p[1], p[2], -1.0f};
    const float wt[6] = {1.0f, 2.0f, 1.0f, 2.0f, 2.0f, 1.0f}; /* off-diagonal entries twice */
    float acc = 0.0f;
    uint32_t i;
    for (i = 0u; i < 6u; ++i) {
        const float d = (p[0] * model[i]) - g[i];
        acc += wt[i] * d * d;
    }
    return sqrtf(acc / 9.0f);
}

/* The conic in normalised image coordinates x = f x^ (C^ = diag(f, f, 1) C diag(f, f, 1)),
   scaled to unit weighted Frobenius norm. */
static void torch_normalise(const sbr_conic_t *conic, float focal, float g[6])
{
    const float f2 = focal * focal;
    float nrm = 0.0f;
    uint32_t i;
    g[0] = conic->a * f2;
    g[1] = conic->b * f2;
    g[2] = conic->c * f2;
    g[3] = conic->d * focal;
    g[4] = conic->e * focal;
    g[5] = conic->f;
    for (i = 0u; i < 6u; ++i) {
        const float w = ((i == 1u) || (i == 3u) || (i == 4u)) ? 2.0f : 1.0f;
        nrm += w * g[i] * g[i];
    }
    nrm = sqrtf(nrm);
    for (i = 0u; i < 6u; ++i) {
        g[i] /= nrm;
    }
}

/* One Gauss-Newton step from p (residuals r, Jacobian jac, cost *cost): taken when it
   lowers the cost (p, r, jac and *cost updated, returns 1), else 0. */
static int torch_step(float p[4], const float g[6], float r[6], float jac[24], float *cost)
{
    float jtj[16] = {0};
    float jtr[4] = {0};
    float q[4];
    float r2[6];
    float jac2[24];
    float cost2;
    uint32_t i;
    uint32_t a;
    uint32_t b;
    for (i = 0u; i < 6u; ++i) {
        for (a = 0u; a < 4u; ++a) {
            jtr[a] -= jac[(i * 4u) + a] * r[i];
            for (b = 0u; b < 4u; ++b) {
                jtj[(a * 4u) + b] += jac[(i * 4u) + a] * jac[(i * 4u) + b];
            }
        }
    }
    if (sbr_conic_priv_solve(jtj, jtr, 4u, 1e-20f) == 0) {
        return 0;
    }
    for (a = 0u; a < 4u; ++a) {
        q[a] = p[a] + jtr[a];
    }
    cost2 = torch_residuals(q, g, r2, jac2);
    if ((isfinite(cost2) == 0) || (cost2 >= *cost)) {
        return 0;
    }
    for (a = 0u; a < 4u; ++a) {
        p[a] = q[a];
    }
    for (a = 0u; a < 6u; ++a) {
        r[a] = r2[a];
    }
    for (a = 0u; a < 24u; ++a) {
        jac[a] = jac2[a];
    }
    *cost = cost2;
    return 1;
}

sbr_status_t sbr_torch_pose(const sbr_conic_t *conic, float focal, float max_residual,
                            sbr_torch_pose_t *pose)
{
    sbr_status_t st;
    sbr_conic_class_t cls = SBR_CONIC_REAL_ELLIPSE;
    float g[6];
    float p[4];
    float r[6];
    float jac[24];
    float cost;
    uint32_t it;
    if ((conic == NULL) || (pose == NULL)) {
        return SBR_ERR_NULL;
    }
    if ((sbr_conic_priv_finite(conic) == 0) || (isfinite(focal) == 0) || (focal <= 0.0f) ||
        (isfinite(max_residual) == 0) || (max_residual <= 0.0f)) {
        return SBR_ERR_RANGE;
    }
    st = sbr_conic_classify(conic, SBR_CONIC_ZERO_TOL, &cls);
    if ((st == SBR_OK) && (cls != SBR_CONIC_REAL_ELLIPSE)) {
        st = SBR_ERR_DEGENERATE;
    }
    if (st != SBR_OK) {
        return st;
    }
    torch_normalise(conic, focal, g);
    /* closed form: mu from C33, n from C13 and C23, k from both diagonal entries */
    p[0] = -g[5];
    if (fabsf(p[0]) <= 1e-12f) {
        return SBR_ERR_DEGENERATE;
    }
    p[1] = g[3] / p[0];
    p[2] = g[4] / p[0];
    p[3] = 0.5f * (((g[0] + g[2]) / p[0]) + (p[1] * p[1]) + (p[2] * p[2]));
    cost = torch_residuals(p, g, r, jac);
    /* Gauss-Newton over all six entries, while the cost decreases */
    for (it = 0u; (it < 20u) && (torch_step(p, g, r, jac, &cost) != 0); ++it) {
        /* stepped */
    }
    pose->n1 = p[1];
    pose->n2 = p[2];
    pose->z0_over_r = (p[3] > 0.0f) ? sqrtf(p[3]) : 0.0f;
    pose->residual = torch_misfit(p, g);
    if ((p[3] <= 0.0f) || (pose->residual > max_residual) || (isfinite(pose->residual) == 0)) {
        st = SBR_ERR_DEGENERATE;
    }
    return st;
}
