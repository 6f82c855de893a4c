// SPDX-License-Identifier: MIT
// Fuzz harness: the recogniser. Configuration fields overwritten from the input, the
// built-in models (with or without the class stage), sbr_recog_init() on a workspace of
// the size the view needs (or one byte short); then frames from the input (size, stride,
// format, pixels), a ROI or bands of rows (sbr_recog_detect_strips(), the workspace one
// band's), a result array of some capacity, and sometimes one byte of the recogniser
// changed after init. A configuration sbr_recog_config_check() refuses is
// refused by init; a changed recogniser gives SBR_ERR_STATE. On SBR_OK / SBR_ERR_CAPACITY:
// count <= capacity, every box inside the frame (and the ROI), scores finite in [0, 1],
// classes of the model; after any other status the statistics are all zero.
#include "fuzz_common.hpp"

#include <cstddef>

extern "C" {
#include "sbr/recog.h"
#include "sbr/models.h"
#include "sbr/recog_strips.h"
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FuzzedDataProvider in(data, size);
    static sbr_model_t model;
    static sbr_picto_model_t picto;
    static bool have_model = false;
    if (!have_model) {
        FZ_STATUS(sbr_model_gtsdb(&model), SBR_OK);
        FZ_STATUS(sbr_picto_gtsdb(&picto), SBR_OK);
        have_model = true;
    }
    sbr_recog_config_t cfg;
    sbr_recog_config_default(&cfg);
    fz_edit_fields(in, &cfg, offsetof(sbr_recog_config_t, clock), 4u);
    std::vector<uint8_t> buf;
    const sbr_pixel_format_t formats[3] = {SBR_PIXEL_RGB888, SBR_PIXEL_BGR888, SBR_PIXEL_GRAY8};
    const sbr_image_t img = fz_image(in, buf, 96u, 96u, formats[in.ConsumeIntegralInRange<uint32_t>(0u, 2u)]);
    sbr_rect_t roi;
    const bool use_roi = in.ConsumeBool();
    roi.x = fz_u32(in, 0u, img.width);
    roi.y = fz_u32(in, 0u, img.height);
    roi.width = fz_u32(in, 1u, img.width);
    roi.height = fz_u32(in, 1u, img.height);
    const bool use_strips = !use_roi && in.ConsumeBool();
    const uint32_t rows = fz_u32(in, 0u, img.height + 8u);
    const uint32_t overlap = fz_u32(in, 0u, rows + 1u);
    const uint32_t w = use_roi ? roi.width : img.width;
    const uint32_t h = use_roi ? roi.height : img.height;
    const sbr_status_t cs = sbr_recog_config_check(&cfg);
    FZ_STATUS(cs, SBR_OK, SBR_ERR_RANGE);
    // the table names a field exactly when the check refuses
    const uint32_t blamed = sbr_recog_config_check_field(&cfg);
    sbr_field_t bf;
    FZ_CHECK((blamed == SBR_FIELD_NONE) == (cs == SBR_OK));
    FZ_CHECK(blamed == SBR_FIELD_NONE || sbr_recog_field_at(blamed, &bf) == SBR_OK);
    size_t need = use_strips ? sbr_recog_strip_workspace_size(&cfg, w, h, rows) : sbr_recog_workspace_size(&cfg, w, h);
    if (use_strips && rows > 0u) {
        // one band's workspace and room for a band's detections
        const size_t band = sbr_recog_workspace_size(&cfg, w, rows < h ? rows : h);
        FZ_CHECK(need == (band == 0u ? 0u
                                     : band + SBR_WS_ALIGN8(SBR_RECOG_STRIP_BAND_DETECTIONS * sizeof(sbr_detection_t))));
    }
    if (!fz_workspace_fits(cs, need, 256u)) {
        return 0;
    }
    const bool short_ws = (need > 0u) && (in.ConsumeIntegral<uint8_t>() >= 240u);
    const size_t given = (need == 0u) ? 4096u : (short_ws ? need - 1u : need);
    void *ws = fz_workspace(given);
    const bool with_picto = in.ConsumeBool();
    sbr_recog_t rec;
    // the class stage's looks: a copy, one of them possibly out of its range
    sbr_picto_model_t stage = picto;
    bool looks_ok = true;
    if (with_picto && in.ConsumeIntegral<uint8_t>() >= 200u) {
        float *looks[5] = {&stage.looks.refine_first_score, &stage.looks.grey_refine_first_score,
                           &stage.looks.refine_score, &stage.looks.view_score, &stage.looks.triangle_score};
        float *l = looks[in.ConsumeIntegralInRange<uint32_t>(0u, 4u)];
        *l = fz_float(in, -0.5f, 1.5f);
        looks_ok = *l >= 0.0f && *l <= 1.0f;
        FZ_CHECK((sbr_picto_check(&stage) == SBR_OK) == looks_ok);
    }
    const sbr_status_t is = sbr_recog_init(&rec, &cfg, &model, with_picto ? &stage : nullptr, ws, given);
    FZ_STATUS(is, SBR_OK, SBR_ERR_RANGE, SBR_ERR_CORRUPT);
    if (!looks_ok) {
        FZ_CHECK(is != SBR_OK);
    }
    if (cs != SBR_OK) {
        FZ_CHECK(is != SBR_OK);
    }
    const bool tamper = in.ConsumeIntegral<uint8_t>() >= 248u;
    if (tamper && is == SBR_OK) { // one byte of the instance changed after init
        uint8_t *rb = reinterpret_cast<uint8_t *>(&rec);
        const size_t at = in.ConsumeIntegralInRange<size_t>(0u, offsetof(sbr_recog_t, check) - 1u);
        rb[at] = static_cast<uint8_t>(rb[at] ^ (1u + in.ConsumeIntegralInRange<uint32_t>(0u, 254u)));
    }
    const uint32_t capacity = in.ConsumeIntegralInRange<uint32_t>(0u, 16u);
    sbr_detection_t dets[16];
    uint32_t count = 12345u;
    sbr_recog_stats_t stats;
    const sbr_status_t st =
        use_strips ? sbr_recog_detect_strips(&rec, &img, rows, overlap, capacity > 0u ? dets : nullptr, capacity,
                                             &count, &stats)
                   : sbr_recog_detect(&rec, &img, use_roi ? &roi : nullptr, capacity > 0u ? dets : nullptr, capacity,
                                      &count, &stats);
    if (use_strips && capacity > 0u && is == SBR_OK && !tamper && (rows == 0u || overlap >= rows)) {
        FZ_CHECK(st != SBR_OK && st != SBR_ERR_CAPACITY); // RANGE, or the frame's own status first
    }
    FZ_STATUS(st, SBR_OK, SBR_ERR_NULL, SBR_ERR_RANGE, SBR_ERR_STATE, SBR_ERR_SIZE, SBR_ERR_ALIGN,
              SBR_ERR_WORKSPACE, SBR_ERR_CAPACITY);
    if (capacity > 0u && (is != SBR_OK || tamper)) {
        FZ_CHECK(st == SBR_ERR_STATE); // an instance init refused, or one changed since
    }
    if (short_ws && st != SBR_ERR_NULL && st != SBR_ERR_STATE && st != SBR_ERR_RANGE && st != SBR_ERR_SIZE && st != SBR_ERR_ALIGN) {
        FZ_CHECK(st == SBR_ERR_WORKSPACE);
    }
    if (st == SBR_OK || st == SBR_ERR_CAPACITY) {
        FZ_CHECK(count <= capacity);
        if (st == SBR_ERR_CAPACITY && !use_strips) {
            FZ_CHECK(count == capacity); // the best `capacity` are written
        }
        for (uint32_t i = 0u; i < count; i++) {
            const sbr_detection_t &d = dets[i];
            FZ_CHECK(d.box.width > 0u && d.box.height > 0u);
            FZ_CHECK((uint64_t)d.box.x + d.box.width <= img.width && (uint64_t)d.box.y + d.box.height <= img.height);
            FZ_CHECK(fz_finite(d.score) && d.score >= 0.0f && d.score <= 1.0f);
            FZ_CHECK(fz_finite(d.class_share) && d.class_share >= 0.0f && d.class_share <= 1.0f);
            FZ_CHECK(d.class_id < model.class_count);
            if (i > 0u) {
                FZ_CHECK(dets[i - 1u].score >= d.score); // highest score first
            }
        }
    } else {
        FZ_CHECK(st == SBR_ERR_NULL || count == 0u || count == 12345u);
        const uint8_t *sb = reinterpret_cast<const uint8_t *>(&stats);
        for (size_t i = 0u; i < sizeof stats; i++) {
            FZ_CHECK(sb[i] == 0u); // documented: all zero after an error
        }
    }
    return 0;
}
