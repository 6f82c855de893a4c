/* SPDX-License-Identifier: MIT */
/* The recogniser's class stage (picto.h), its model and classifier: the model check,
   the classifier's layers (sbr_picto_classify()) and the box regression
   (sbr_picto_refine()). Features: picto_features.c; rim check: picto_rim.c; gate:
   picto_gate.c; looks: picto_look.c. */
#include "sbr/picto.h"

#include "picto_internal.h"

#include "../common/sbr_util.h"

#include <math.h>
#include <string.h>

/* Version, sizes and tables present (what every call needs; the weights' finiteness is
   sbr_picto_check()'s, once per model). */
static int header_ok(const sbr_picto_model_t *model)
{
    int ok = 0;
    if ((model->version == SBR_PICTO_VERSION) && (model->features == SBR_PICTO_FEATURES) &&
        (model->hidden <= SBR_PICTO_HIDDEN_MAX) && (model->classes >= 1u) &&
        (model->classes <= SBR_PICTO_MAX_CLASSES) && (model->w2 != NULL) &&
        ((model->hidden == 0u) || (model->w1 != NULL))) {
        ok = 1;
    }
    return ok;
}

/* Inputs of the last layers (without the bias), and their row length with it. */
static size_t last_inputs_n(const sbr_picto_model_t *model)
{
    return (size_t)((model->hidden > 0u) ? model->hidden : SBR_PICTO_FEATURES);
}

static size_t last_cols(const sbr_picto_model_t *model)
{
    return last_inputs_n(model) + 1u;
}

static int all_finite(const float *w, size_t n)
{
    int ok = 1;
    size_t i;
    for (i = 0u; (i < n) && (ok != 0); i++) {
        if (isfinite(w[i]) == 0) {
            ok = 0;
        }
    }
    return ok;
}

/* The colour check tables: both absent, or both present with outlines in range and
   finite floors in [-2, 2]. */
static int rim_tables_ok(const sbr_picto_model_t *model)
{
    int ok = 1;
    if ((model->rim_shape == NULL) || (model->rim_floor == NULL)) {
        if ((model->rim_shape != NULL) || (model->rim_floor != NULL)) {
            ok = 0;
        }
    } else {
        uint32_t c;
        for (c = 0u; (c < model->classes) && (ok != 0); c++) {
            const float f = model->rim_floor[c];
            if ((model->rim_shape[c] > (uint8_t)SBR_PICTO_RIM_TRIANGLE_DOWN) ||
                (isfinite(f) == 0) || (f < -2.0f) || (f > 2.0f)) {
                ok = 0;
            }
        }
    }
    return ok;
}

sbr_status_t sbr_picto_check(const sbr_picto_model_t *model)
{
    if (model == NULL) {
        return SBR_ERR_NULL;
    }
    if ((header_ok(model) == 0) || (model->threshold <= 0.0f) ||
        (model->threshold >= 1.0f) || (isfinite(model->threshold) == 0) ||
        (sbr_picto_priv_looks_ok(model) == 0)) {
        return SBR_ERR_CORRUPT;
    }
    if ((all_finite(model->w1, (size_t)model->hidden * (SBR_PICTO_FEATURES + 1u)) == 0) ||
        (all_finite(model->w2, (size_t)(model->classes + 1u) * last_cols(model)) == 0)) {
        return SBR_ERR_CORRUPT;
    }
    if ((model->w3 != NULL) &&
        (all_finite(model->w3, (size_t)SBR_PICTO_BOX_OUTPUTS * last_cols(model)) == 0)) {
        return SBR_ERR_CORRUPT;
    }
    if (rim_tables_ok(model) == 0) {
        return SBR_ERR_CORRUPT;
    }
    if ((model->gate != NULL) &&
        ((model->gate_hidden > SBR_PICTO_GATE_HIDDEN_MAX) ||
         (all_finite(model->gate, (size_t)SBR_PICTO_GATE_WEIGHTS(model->gate_hidden)) == 0) ||
         (isfinite(model->gate_threshold) == 0))) {
        return SBR_ERR_CORRUPT;
    }
    return SBR_OK;
}


/* Checks shared by sbr_picto_classify() and sbr_picto_refine(). */
static sbr_status_t run_check(const sbr_picto_model_t *model, const float *feat, uint32_t len,
                              const void *workspace, size_t workspace_size)
{
    uint32_t i;
    if (len < SBR_PICTO_FEATURES) {
        return SBR_ERR_SIZE;
    }
    if (header_ok(model) == 0) {
        return SBR_ERR_CORRUPT;
    }
    if ((workspace == NULL) || (workspace_size < SBR_PICTO_WORKSPACE_SIZE) ||
        (sbr_util_aligned(workspace, 4u) == 0)) {
        return SBR_ERR_WORKSPACE;
    }
    for (i = 0u; i < SBR_PICTO_FEATURES; i++) {
        if (isfinite(feat[i]) == 0) {
            return SBR_ERR_RANGE;
        }
    }
    return SBR_OK;
}

#if SBR_UTIL_SCALAR_CORE == 0
/* One group of four inputs into a row's four partial sums (a loop over the lanes, which
   the vectoriser makes one vector operation on SIMD hosts). */
static inline void lane4(float s[4], const float *w, const float *b)
{
    uint32_t l;
    for (l = 0u; l < 4u; l++) {
        s[l] += w[l] * b[l];
    }
}
#endif

/* sbr_util_dot() of four rows (w, w + stride, ...) with the same b at once: each row's sum
   is the same sequence of operations as sbr_util_dot()'s (bit for bit), but the four rows'
   additions are independent, so the FPU overlaps them instead of waiting on one chain. */
static void dot4(const float *w, size_t stride, const float *b, size_t n, float out[4])
{
    /* four partial sums per row, as sbr_util_dot(): row r's sum of lane l in s<r>[l]; the
       same operations in the same order on every target, only written for its compiler */
    const float *w0 = w;
    const float *w1 = &w[stride];
    const float *w2 = &w[2u * stride];
    const float *w3 = &w[3u * stride];
    float s0[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s1[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s2[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s3[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const size_t n4 = n - (n % 4u); /* the four-lane part; the tail loop is then visibly
                                        bounded by n - n4 < 4 */
    size_t k;
#if SBR_UTIL_SCALAR_CORE != 0
    /* M-profile cores have no vector unit: the lanes written out with constant indices,
       so that all sixteen sums stay in FPU registers (gcc does not unroll a lane loop
       there and kept them in memory: 2.5 times the instructions) */
    for (k = 0u; k < n4; k += 4u) {
        s0[0] += w0[k] * b[k];
        s0[1] += w0[k + 1u] * b[k + 1u];
        s0[2] += w0[k + 2u] * b[k + 2u];
        s0[3] += w0[k + 3u] * b[k + 3u];
        s1[0] += w1[k] * b[k];
        s1[1] += w1[k + 1u] * b[k + 1u];
        s1[2] += w1[k + 2u] * b[k + 2u];
        s1[3] += w1[k + 3u] * b[k + 3u];
        s2[0] += w2[k] * b[k];
        s2[1] += w2[k + 1u] * b[k + 1u];
        s2[2] += w2[k + 2u] * b[k + 2u];
        s2[3] += w2[k + 3u] * b[k + 3u];
        s3[0] += w3[k] * b[k];
        s3[1] += w3[k + 1u] * b[k + 1u];
        s3[2] += w3[k + 2u] * b[k + 2u];
        s3[3] += w3[k + 3u] * b[k + 3u];
    }
#else
    /* SIMD hosts: one vector a row (lane4()) */
    for (k = 0u; k < n4; k += 4u) {
        lane4(s0, &w0[k], &b[k]);
        lane4(s1, &w1[k], &b[k]);
        lane4(s2, &w2[k], &b[k]);
        lane4(s3, &w3[k], &b[k]);
    }
#endif
    for (k = n4; k < n; k++) {
        s0[0] += w0[k] * b[k];
        s1[0] += w1[k] * b[k];
        s2[0] += w2[k] * b[k];
        s3[0] += w3[k] * b[k];
    }
    out[0] = (s0[0] + s0[1]) + (s0[2] + s0[3]);
    out[1] = (s1[0] + s1[1]) + (s1[2] + s1[3]);
    out[2] = (s2[0] + s2[1]) + (s2[2] + s2[3]);
    out[3] = (s3[0] + s3[1]) + (s3[2] + s3[3]);
}

#if SBR_UTIL_SCALAR_CORE == 0
/* dot4() of eight rows at once (SIMD hosts): each group of four inputs is loaded once for
   the eight rows' vector sums; every row's sum the same operations as dot4()'s. */
static void dot8(const float *w, size_t stride, const float *b, size_t n, float out[8])
{
    const float *w0 = w;
    const float *w1 = &w[stride];
    const float *w2 = &w[2u * stride];
    const float *w3 = &w[3u * stride];
    const float *w4 = &w[4u * stride];
    const float *w5 = &w[5u * stride];
    const float *w6 = &w[6u * stride];
    const float *w7 = &w[7u * stride];
    float s0[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s1[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s2[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s3[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s4[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s5[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s6[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s7[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const size_t n4 = n - (n % 4u);
    size_t k;
    for (k = 0u; k < n4; k += 4u) {
        lane4(s0, &w0[k], &b[k]);
        lane4(s1, &w1[k], &b[k]);
        lane4(s2, &w2[k], &b[k]);
        lane4(s3, &w3[k], &b[k]);
        lane4(s4, &w4[k], &b[k]);
        lane4(s5, &w5[k], &b[k]);
        lane4(s6, &w6[k], &b[k]);
        lane4(s7, &w7[k], &b[k]);
    }
    for (k = n4; k < n; k++) {
        s0[0] += w0[k] * b[k];
        s1[0] += w1[k] * b[k];
        s2[0] += w2[k] * b[k];
        s3[0] += w3[k] * b[k];
        s4[0] += w4[k] * b[k];
        s5[0] += w5[k] * b[k];
        s6[0] += w6[k] * b[k];
        s7[0] += w7[k] * b[k];
    }
    out[0] = (s0[0] + s0[1]) + (s0[2] + s0[3]);
    out[1] = (s1[0] + s1[1]) + (s1[2] + s1[3]);
    out[2] = (s2[0] + s2[1]) + (s2[2] + s2[3]);
    out[3] = (s3[0] + s3[1]) + (s3[2] + s3[3]);
    out[4] = (s4[0] + s4[1]) + (s4[2] + s4[3]);
    out[5] = (s5[0] + s5[1]) + (s5[2] + s5[3]);
    out[6] = (s6[0] + s6[1]) + (s6[2] + s6[3]);
    out[7] = (s7[0] + s7[1]) + (s7[2] + s7[3]);
}
#endif

/* out[r] = sbr_util_dot(row r of w, b) for `rows` rows `stride` apart, eight (SIMD hosts)
   or four rows at a time. */
static void rows_dot(const float *w, size_t stride, uint32_t rows, const float *b, size_t n,
                     float *out)
{
    uint32_t r = 0u;
#if SBR_UTIL_SCALAR_CORE == 0
    while ((r + 8u) <= rows) {
        dot8(&w[(size_t)r * stride], stride, b, n, &out[r]);
        r += 8u;
    }
#endif
    while ((r + 4u) <= rows) {
        dot4(&w[(size_t)r * stride], stride, b, n, &out[r]);
        r += 4u;
    }
    while (r < rows) {
        out[r] = sbr_util_dot(&w[(size_t)r * stride], b, n);
        r++;
    }
}

/* out[r] = w[r] . [in; 1] for `rows` rows of `n_in` inputs and a bias (row stride
   n_in + 1). */
void sbr_picto_priv_affine(const float *w, const float *in, size_t n_in, uint32_t rows, float *out)
{
    const size_t cols = n_in + 1u;
    uint32_t r;
    rows_dot(w, cols, rows, in, n_in, out);
    for (r = 0u; r < rows; r++) {
        out[r] = w[((size_t)r * cols) + n_in] + out[r];
    }
}

/* The last layer's inputs: the rectified hidden units (in the workspace), or the features
   themselves without a hidden layer. */
static const float *last_inputs(const sbr_picto_model_t *model, const float *feat, float *a)
{
    const float *in = feat;
    if (model->hidden > 0u) {
        const size_t n_feat = SBR_PICTO_FEATURES;
        uint32_t i;
        sbr_picto_priv_affine(model->w1, feat, n_feat, model->hidden, a);
        for (i = 0u; i < model->hidden; i++) {
            a[i] = (a[i] > 0.0f) ? a[i] : 0.0f;
        }
        in = a;
    }
    return in;
}

sbr_status_t sbr_picto_classify(const sbr_picto_model_t *model, const float *feat, uint32_t len,
                                float *prob, uint32_t nprob, void *workspace,
                                size_t workspace_size)
{
    float mx;
    float sum = 0.0f;
    uint32_t i;
    uint32_t outputs;
    sbr_status_t st;

    if ((model == NULL) || (feat == NULL) || (prob == NULL)) {
        return SBR_ERR_NULL;
    }
    st = run_check(model, feat, len, workspace, workspace_size);
    if (st != SBR_OK) {
        return st;
    }
    outputs = model->classes + 1u;
    if (nprob < outputs) {
        return SBR_ERR_SIZE;
    }
    sbr_picto_priv_affine(model->w2, last_inputs(model, feat, (float *)workspace), last_inputs_n(model),
           outputs, prob);
    if (all_finite(prob, outputs) == 0) {
        return SBR_ERR_RANGE; /* features so large that the logits overflow */
    }
    mx = prob[0];
    for (i = 1u; i < outputs; i++) {
        if (prob[i] > mx) {
            mx = prob[i];
        }
    }
    for (i = 0u; i < outputs; i++) {
        prob[i] = expf(prob[i] - mx);
        sum += prob[i];
    }
    for (i = 0u; i < outputs; i++) {
        prob[i] /= sum;
    }
    return SBR_OK;
}


sbr_status_t sbr_picto_refine(const sbr_picto_model_t *model, const float *feat, uint32_t len,
                              const float box[4], float refined[4], void *workspace,
                              size_t workspace_size)
{
    const float *in;
    sbr_status_t st;

    if ((model == NULL) || (feat == NULL) || (box == NULL) || (refined == NULL)) {
        return SBR_ERR_NULL;
    }
    st = run_check(model, feat, len, workspace, workspace_size);
    if (st != SBR_OK) {
        return st;
    }
    if (sbr_picto_priv_box_in_domain(box) == 0) {
        return SBR_ERR_RANGE;
    }
    in = feat;
    if (model->w3 != NULL) {
        in = last_inputs(model, feat, (float *)workspace);
    }
    return sbr_picto_priv_refine_from(model, in, box, refined);
}

sbr_status_t sbr_picto_priv_refine_from(const sbr_picto_model_t *model, const float *in,
                                        const float box[4], float refined[4])
{
    float cx;
    float cy;
    float hw;
    float hh;
    if (header_ok(model) == 0) {
        return SBR_ERR_CORRUPT;
    }
    if (sbr_picto_priv_box_in_domain(box) == 0) {
        return SBR_ERR_RANGE;
    }
    cx = 0.5f * (box[0] + box[2]);
    cy = 0.5f * (box[1] + box[3]);
    hw = 0.5f * (box[2] - box[0]);
    hh = 0.5f * (box[3] - box[1]);
    if (model->w3 != NULL) {
        float d[SBR_PICTO_BOX_OUTPUTS];
        sbr_picto_priv_affine(model->w3, in, last_inputs_n(model), SBR_PICTO_BOX_OUTPUTS, d);
        if (all_finite(d, SBR_PICTO_BOX_OUTPUTS) == 0) {
            return SBR_ERR_RANGE; /* features so large that the regression overflows */
        }
        cx += 2.0f * hw * sbr_util_clampf(d[0], -SBR_PICTO_MAX_SHIFT, SBR_PICTO_MAX_SHIFT);
        cy += 2.0f * hh * sbr_util_clampf(d[1], -SBR_PICTO_MAX_SHIFT, SBR_PICTO_MAX_SHIFT);
        hw *= expf(sbr_util_clampf(d[2], -SBR_PICTO_MAX_LOG_SCALE, SBR_PICTO_MAX_LOG_SCALE));
        hh *= expf(sbr_util_clampf(d[3], -SBR_PICTO_MAX_LOG_SCALE, SBR_PICTO_MAX_LOG_SCALE));
    }
    refined[0] = cx - hw;
    refined[1] = cy - hh;
    refined[2] = cx + hw;
    refined[3] = cy + hh;
    return SBR_OK;
}
