// SPDX-License-Identifier: MIT
// Fuzz harness: pictogram features (box and triangle outline), classification and box
// refinement with the built-in class stage, its colour check and its gate. On SBR_OK:
// features finite; the model's classes + 1 probabilities finite in [0, 1] summing to 1
// (nothing written beyond them); refined boxes finite and
// not empty; gate features and scores finite.
#include "fuzz_common.hpp"

extern "C" {
#include "sbr/picto.h"
#include "sbr/models.h"
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FuzzedDataProvider in(data, size);
    static sbr_picto_model_t model;
    static bool have = false;
    if (!have) {
        FZ_STATUS(sbr_picto_gtsdb(&model), SBR_OK);
        FZ_STATUS(sbr_picto_check(&model), SBR_OK);
        have = true;
    }
    std::vector<uint8_t> buf;
    const sbr_image_t img = fz_image(in, buf, 72u, 72u, in.ConsumeBool() ? SBR_PIXEL_RGB888 : SBR_PIXEL_GRAY8);
    float box[4];
    for (float &b : box) {
        b = fz_float(in, -40.0f, 110.0f);
    }
    const uint32_t outline = in.ConsumeBool() ? 0u : fz_u32(in, 0u, 2u);
    static float feat[SBR_PICTO_FEATURES + 4u];
    const uint32_t len = in.ConsumeBool() ? SBR_PICTO_FEATURES : fz_u32(in, 0u, SBR_PICTO_FEATURES + 4u);
    void *ws = fz_workspace(SBR_PICTO_WORKSPACE_SIZE);
    const size_t wsz = in.ConsumeIntegral<uint8_t>() < 245u ? SBR_PICTO_WORKSPACE_SIZE : SBR_PICTO_WORKSPACE_SIZE - 4u;
    const sbr_status_t fs = sbr_picto_features_outline(&img, box, outline, feat, len, ws, wsz);
    FZ_CHECK(fz_known(fs));
    if (fs != SBR_OK) {
        // features as a hostile caller hands them in
        for (uint32_t i = 0u; i < SBR_PICTO_FEATURES; i++) {
            feat[i] = (in.remaining_bytes() > 0u) ? fz_float(in, -3.0f, 3.0f) : 0.0f;
        }
    } else {
        for (uint32_t i = 0u; i < SBR_PICTO_FEATURES; i++) {
            FZ_CHECK(fz_finite(feat[i]));
        }
    }
    // the model's classes + 1 outputs are written, the rest of the caller's array is not
    float prob[SBR_PICTO_MAX_OUTPUTS];
    for (float &p : prob) {
        p = -7.0f;
    }
    const uint32_t outputs = model.classes + 1u;
    const sbr_status_t cs = sbr_picto_classify(&model, feat, SBR_PICTO_FEATURES, prob, SBR_PICTO_MAX_OUTPUTS, ws,
                                               SBR_PICTO_WORKSPACE_SIZE);
    FZ_STATUS(cs, SBR_OK, SBR_ERR_RANGE);
    if (cs == SBR_OK) {
        float sum = 0.0f;
        for (uint32_t i = 0u; i < SBR_PICTO_MAX_OUTPUTS; i++) {
            const float p = prob[i];
            if (i < outputs) {
                FZ_CHECK(fz_finite(p) && p >= 0.0f && p <= 1.0f);
                sum += p;
            } else {
                FZ_CHECK(p == -7.0f);
            }
        }
        FZ_CHECK(std::fabs(sum - 1.0f) < 1e-3f);
    }
    float refined[4];
    const sbr_status_t rs = sbr_picto_refine(&model, feat, SBR_PICTO_FEATURES, box, refined, ws,
                                             SBR_PICTO_WORKSPACE_SIZE);
    FZ_STATUS(rs, SBR_OK, SBR_ERR_RANGE);
    if (rs == SBR_OK) {
        for (float r : refined) {
            FZ_CHECK(fz_finite(r));
        }
        FZ_CHECK(refined[2] > refined[0] && refined[3] > refined[1]);
    }
    // the colour check on the same box and image, any shape a caller may pass
    float contrast = 7.0f;
    const uint32_t shape = fz_u32(in, 0u, 4u);
    const sbr_status_t ks = sbr_picto_rim_contrast(&img, box, shape, &contrast);
    FZ_CHECK(fz_known(ks));
    if (ks == SBR_OK) {
        FZ_CHECK(contrast >= -2.0f && contrast <= 2.0f);
    } else {
        FZ_CHECK(contrast == 7.0f);
    }
    // the gate's features and score on the same box (the built-in gate, or none)
    static float gfeat[SBR_PICTO_GATE_FEATURES + 4u];
    const uint32_t glen = in.ConsumeBool() ? SBR_PICTO_GATE_FEATURES : fz_u32(in, 0u, SBR_PICTO_GATE_FEATURES + 4u);
    const size_t gsz = in.ConsumeIntegral<uint8_t>() < 245u ? SBR_PICTO_GATE_WORKSPACE_SIZE : SBR_PICTO_GATE_WORKSPACE_SIZE - 4u;
    const sbr_status_t gs = sbr_picto_gate_features(&img, box, gfeat, glen, ws, gsz);
    FZ_CHECK(fz_known(gs));
    if (gs == SBR_OK) {
        for (uint32_t i = 0u; i < SBR_PICTO_GATE_FEATURES; i++) {
            FZ_CHECK(fz_finite(gfeat[i]));
        }
    } else {
        for (uint32_t i = 0u; i < SBR_PICTO_GATE_FEATURES; i++) {
            gfeat[i] = (in.remaining_bytes() > 0u) ? fz_float(in, -3.0f, 3.0f) : 0.0f;
        }
    }
    float score = 7.0f;
    const sbr_status_t ss = sbr_picto_gate(&model, gfeat, SBR_PICTO_GATE_FEATURES, &score);
    if (model.gate == nullptr) {
        FZ_STATUS(ss, SBR_ERR_NULL);
    } else {
        FZ_STATUS(ss, SBR_OK, SBR_ERR_RANGE);
        FZ_CHECK(ss != SBR_OK || fz_finite(score));
    }
    return 0;
}
