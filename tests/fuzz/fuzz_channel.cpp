// SPDX-License-Identifier: MIT
// Fuzz harness: channel encoding, accumulation and decoding, 1-D and 2-D. On SBR_OK: encodings finite
// and >= 0; decoded values finite inside the representable range, certainties finite
// and >= 0, modes sorted by certainty and within capacity.
#include "fuzz_common.hpp"

extern "C" {
#include "sbr/channel.h"
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FuzzedDataProvider in(data, size);
    sbr_channel_config_t cfg;
    sbr_channel_config_default(&cfg);
    cfg.first_centre = fz_float(in, -100.0f, 100.0f);
    cfg.spacing = fz_float(in, 0.0f, 10.0f);
    cfg.count = fz_u32(in, 0u, 64u);
    cfg.overlap = fz_u32(in, 2u, 9u);
    const sbr_status_t cs = sbr_channel_config_check(&cfg);
    FZ_STATUS(cs, SBR_OK, SBR_ERR_RANGE, SBR_ERR_SIZE);
    float lo = 0.0f;
    float hi = 0.0f;
    FZ_CHECK((sbr_channel_range(&cfg, &lo, &hi) == SBR_OK) == (cs == SBR_OK));
    if (cs != SBR_OK) {
        return 0;
    }
    FZ_CHECK(fz_finite(lo) && fz_finite(hi) && lo <= hi);
    std::vector<float> hist(cfg.count + 4u, 0.0f);
    const uint32_t len = in.ConsumeBool() ? cfg.count : in.ConsumeIntegralInRange<uint32_t>(0u, cfg.count + 4u);
    const uint32_t values = in.ConsumeIntegralInRange<uint32_t>(0u, 8u);
    for (uint32_t i = 0u; i < values; i++) {
        const float x = in.ConsumeBool() ? lo + (hi - lo) * in.ConsumeProbability<float>() : fz_float(in, lo - 5.0f, hi + 5.0f);
        const float w = fz_float(in, 0.0f, 2.0f);
        const sbr_status_t as = sbr_channel_accumulate(&cfg, x, w, hist.data(), len);
        FZ_STATUS(as, SBR_OK, SBR_ERR_RANGE, SBR_ERR_SIZE);
    }
    for (uint32_t i = 0u; i < cfg.count; i++) {
        FZ_CHECK(fz_finite(hist[i]) && hist[i] >= 0.0f);
    }
    if (in.ConsumeIntegral<uint8_t>() > 230u) { // a hostile histogram
        hist[in.ConsumeIntegralInRange<uint32_t>(0u, cfg.count - 1u)] = fz_float(in, -1.0f, 1e30f);
    }
    const uint32_t window = fz_u32(in, 0u, cfg.count);
    float value = 0.0f;
    float cert = 0.0f;
    int valid = 7;
    const sbr_status_t ws = sbr_channel_decode_window(&cfg, hist.data(), len, window, &value, &cert, &valid);
    FZ_STATUS(ws, SBR_OK, SBR_ERR_RANGE, SBR_ERR_SIZE, SBR_ERR_NULL);
    if (ws == SBR_OK) {
        FZ_CHECK(fz_finite(value) && fz_finite(cert) && cert >= 0.0f && (valid == 0 || valid == 1));
    }
    sbr_channel_mode_t modes[8];
    uint32_t count = 0u;
    const uint32_t cap = in.ConsumeIntegralInRange<uint32_t>(0u, 8u);
    const sbr_status_t ds = sbr_channel_decode(&cfg, hist.data(), len, fz_float(in, 0.0f, 2.0f),
                                               cap > 0u ? modes : nullptr, cap, &count);
    FZ_STATUS(ds, SBR_OK, SBR_ERR_RANGE, SBR_ERR_SIZE, SBR_ERR_NULL, SBR_ERR_CAPACITY);
    if (ds == SBR_OK || (ds == SBR_ERR_CAPACITY && cap > 0u)) {
        FZ_CHECK(count <= cap || cap == 0u);
        for (uint32_t i = 0u; i < count && i < cap; i++) {
            FZ_CHECK(fz_finite(modes[i].value) && fz_finite(modes[i].certainty) && modes[i].certainty >= 0.0f);
            FZ_CHECK(modes[i].value >= lo - cfg.spacing && modes[i].value <= hi + cfg.spacing);
            if (i > 0u) {
                FZ_CHECK(modes[i - 1u].certainty >= modes[i].certainty);
            }
        }
    }
    // the 2-D grid
    sbr_channel2d_config_t c2;
    c2.x = cfg;
    sbr_channel_config_default(&c2.y);
    c2.y.count = fz_u32(in, 0u, 16u);
    const sbr_status_t c2s = sbr_channel2d_config_check(&c2);
    FZ_CHECK(fz_known(c2s));
    const uint32_t glen = sbr_channel2d_grid_len(&c2);
    FZ_CHECK((glen == 0u) == (c2s != SBR_OK));
    if (c2s != SBR_OK || glen > 4096u) {
        return 0;
    }
    std::vector<float> grid(glen, 0.0f);
    float ylo = 0.0f;
    float yhi = 0.0f;
    FZ_STATUS(sbr_channel_range(&c2.y, &ylo, &yhi), SBR_OK);
    const uint32_t pts = in.ConsumeIntegralInRange<uint32_t>(0u, 6u);
    for (uint32_t i = 0u; i < pts; i++) {
        const float x = lo + (hi - lo) * in.ConsumeProbability<float>();
        const float y = in.ConsumeBool() ? ylo + (yhi - ylo) * in.ConsumeProbability<float>() : fz_float(in, -5.0f, 20.0f);
        const sbr_status_t as = sbr_channel2d_accumulate(&c2, x, y, fz_float(in, 0.0f, 2.0f), grid.data(), glen);
        FZ_STATUS(as, SBR_OK, SBR_ERR_RANGE);
    }
    for (float g : grid) {
        FZ_CHECK(fz_finite(g) && g >= 0.0f && g <= SBR_CHANNEL_MAX_VALUE);
    }
    sbr_channel_mode2d_t m2[4];
    uint32_t n2 = 0u;
    const sbr_status_t d2 = sbr_channel2d_decode(&c2, grid.data(), glen, fz_float(in, 0.0f, 1.0f), m2, 4u, &n2);
    FZ_STATUS(d2, SBR_OK, SBR_ERR_RANGE, SBR_ERR_CAPACITY);
    if (d2 == SBR_OK || d2 == SBR_ERR_CAPACITY) {
        FZ_CHECK(n2 <= 4u);
        for (uint32_t i = 0u; i < n2; i++) {
            FZ_CHECK(fz_finite(m2[i].x) && fz_finite(m2[i].y) && fz_finite(m2[i].certainty) && m2[i].certainty >= 0.0f);
        }
    }
    return 0;
}
