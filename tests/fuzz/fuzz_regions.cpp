// SPDX-License-Identifier: MIT
// Fuzz harness: maps, MSER, region masks, contour tracing and part extraction. Images and
// configuration fields from the input. On SBR_OK: maps of the promised size; regions
// inside the map with area within the bounds; masks that contain the seed; contours
// whose points lie in the mask and whose index ranges fit the point array; parts with
// finite descriptors inside the image.
#include "fuzz_common.hpp"
#include <cstring>

extern "C" {
#include "sbr/contour.h"
#include "sbr/fft.h"
#include "sbr/map.h"
#include "sbr/mser.h"
#include "sbr/parts.h"
}

namespace {

void fuzz_map_mser_contour(FuzzedDataProvider &in)
{
    std::vector<uint8_t> buf;
    const sbr_image_t img = fz_image(in, buf, 64u, 64u, SBR_PIXEL_RGB888);
    const auto kind = static_cast<sbr_map_kind_t>(in.ConsumeIntegralInRange<uint32_t>(0u, 4u));
    const uint32_t sub = fz_u32(in, 1u, 3u);
    std::vector<uint8_t> map(64u * 64u + 64u);
    const uint32_t mstride = in.ConsumeBool() ? 64u : in.ConsumeIntegralInRange<uint32_t>(0u, 66u);
    sbr_image_t view;
    const sbr_status_t ms = sbr_map_make(&img, kind, sub, map.data(), mstride, map.size(), &view);
    FZ_CHECK(fz_known(ms));
    if (ms != SBR_OK) {
        return;
    }
    FZ_CHECK(view.width == img.width / sub && view.height == img.height / sub);
    FZ_CHECK(view.format == SBR_PIXEL_GRAY8 && view.data == map.data() && view.stride == mstride);
    sbr_mser_config_t cfg;
    sbr_mser_config_default(&cfg);
    fz_edit_fields(in, &cfg, sizeof cfg, 3u);
    const sbr_status_t cs = sbr_mser_config_check(&cfg);
    // mser.h's ranges, written out from the header: the check accepts exactly those
    const bool header_ok = cfg.delta >= 1u && cfg.delta <= SBR_MSER_MAX_DELTA && cfg.min_area >= 1u &&
                           cfg.max_area >= cfg.min_area && cfg.max_variation > 0.0f && cfg.max_variation <= 1e30f &&
                           cfg.min_diversity >= 0.0f && cfg.min_diversity < 1.0f && cfg.polarity >= 1u &&
                           cfg.polarity <= 3u && cfg.dark_max <= 255u && cfg.bright_min <= 255u;
    FZ_CHECK((cs == SBR_OK) == header_ok);
    const size_t need = sbr_mser_workspace_size(&cfg, view.width, view.height);
    if (need > 0u) {
        // the macro equals the function for the configuration's max_nodes and max_heap
        FZ_CHECK(need == SBR_MSER_WORKSPACE_SIZE(view.width, view.height, cfg.delta, cfg.max_nodes, cfg.max_heap));
    }
    if (!fz_workspace_fits(cs, need, 64u)) {
        return;
    }
    void *ws = fz_workspace(need > 0u ? need : 64u);
    sbr_mser_region_t regions[64];
    uint32_t n = 0u;
    const uint32_t cap = in.ConsumeIntegralInRange<uint32_t>(0u, 64u);
    const sbr_status_t st = sbr_mser_detect(&view, &cfg, ws, need, regions, cap, &n);
    FZ_STATUS(st, SBR_OK, SBR_ERR_NULL, SBR_ERR_RANGE, SBR_ERR_SIZE, SBR_ERR_ALIGN, SBR_ERR_WORKSPACE,
              SBR_ERR_CAPACITY);
    if (st != SBR_OK && st != SBR_ERR_CAPACITY) {
        return;
    }
    FZ_CHECK(n <= cap);
    // the part stage's entry: the map written at sbr_mser_map_slot() and detected in place
    // gives the same regions and status, and the map back
    if (cap > 0u) {
        std::vector<uint64_t> ws2(need / 8u + 1u);
        uint8_t *slot = sbr_mser_map_slot(&cfg, view.width, view.height, ws2.data(), need);
        FZ_CHECK(slot != nullptr);
        for (uint32_t y = 0u; y < view.height; y++) {
            std::memcpy(&slot[(size_t)y * view.width], &view.data[(size_t)y * view.stride], view.width);
        }
        sbr_mser_region_t again[64];
        uint32_t m = 0u;
        sbr_image_t back{};
        const sbr_status_t s2 =
            sbr_mser_detect_in_place(view.width, view.height, &cfg, ws2.data(), need, again, cap, &m, &back);
        FZ_CHECK(s2 == st && m == n);
        for (uint32_t i = 0u; i < n; i++) { // field by field (the struct's tail padding is not written)
            const sbr_mser_region_t &p = again[i], &q = regions[i];
            FZ_CHECK(p.bbox.x == q.bbox.x && p.bbox.y == q.bbox.y && p.bbox.width == q.bbox.width &&
                     p.bbox.height == q.bbox.height && p.area == q.area &&
                     std::memcmp(&p.variation, &q.variation, sizeof p.variation) == 0 && p.seed_x == q.seed_x &&
                     p.seed_y == q.seed_y && p.level == q.level && p.polarity == q.polarity);
        }
        for (uint32_t y = 0u; y < view.height; y++) {
            FZ_CHECK(std::memcmp(&back.data[(size_t)y * back.stride], &view.data[(size_t)y * view.stride], view.width) ==
                     0);
        }
        FZ_CHECK(sbr_mser_map_slot(&cfg, view.width, view.height, ws2.data(), need - 1u) == nullptr);
    }
    std::vector<uint8_t> mask;
    for (uint32_t i = 0u; i < n && i < 8u; i++) {
        const sbr_mser_region_t &r = regions[i];
        FZ_CHECK(r.bbox.width > 0u && r.bbox.height > 0u);
        FZ_CHECK((uint64_t)r.bbox.x + r.bbox.width <= view.width && (uint64_t)r.bbox.y + r.bbox.height <= view.height);
        FZ_CHECK(r.area >= cfg.min_area && r.area <= cfg.max_area && r.area <= r.bbox.width * r.bbox.height);
        FZ_CHECK(r.seed_x >= r.bbox.x && r.seed_x < r.bbox.x + r.bbox.width);
        FZ_CHECK(r.seed_y >= r.bbox.y && r.seed_y < r.bbox.y + r.bbox.height);
        FZ_CHECK(fz_finite(r.variation) && r.variation >= 0.0f);
        // the level limits: no region within delta of a limit or beyond it
        if (r.polarity == SBR_MSER_DARK && cfg.dark_max < 255u) {
            FZ_CHECK((uint32_t)r.level + cfg.delta <= cfg.dark_max);
        }
        if (r.polarity == SBR_MSER_BRIGHT && cfg.bright_min > 0u) {
            FZ_CHECK((uint32_t)r.level >= cfg.bright_min + cfg.delta);
        }
        const size_t mws = SBR_MSER_MASK_WORKSPACE_SIZE(r.bbox.width, r.bbox.height);
        mask.assign((size_t)r.bbox.width * r.bbox.height, 0u);
        const sbr_status_t rs = sbr_mser_region_mask(&view, &r, fz_workspace(mws), mws, mask.data(),
                                                     r.bbox.width, mask.size());
        FZ_STATUS(rs, SBR_OK);
        uint32_t on = 0u;
        for (uint8_t v : mask) {
            on += (v != 0u) ? 1u : 0u;
        }
        // the region is its extremal component; all of it unless a bound stopped a flood
        FZ_CHECK(st == SBR_ERR_CAPACITY ? on >= r.area : on == r.area);
        FZ_CHECK(mask[(size_t)(r.seed_y - r.bbox.y) * r.bbox.width + (r.seed_x - r.bbox.x)] != 0u);
        // the region's outer contour
        sbr_image_t mview;
        mview.width = r.bbox.width;
        mview.height = r.bbox.height;
        mview.stride = r.bbox.width;
        mview.format = SBR_PIXEL_GRAY8;
        mview.data = mask.data();
        const size_t cws = sbr_contour_workspace_size(mview.width, mview.height);
        sbr_point_t pts[512];
        sbr_contour_t cont[4];
        uint32_t nc = 0u;
        const uint32_t pcap = in.ConsumeIntegralInRange<uint32_t>(0u, 512u);
        const uint32_t ccap = in.ConsumeIntegralInRange<uint32_t>(0u, 4u);
        const sbr_status_t ks = sbr_contour_find_external(&mview, fz_workspace(cws), cws, pts, pcap, cont, ccap, &nc);
        FZ_STATUS(ks, SBR_OK, SBR_ERR_CAPACITY, SBR_ERR_NULL);
        if (ks == SBR_OK || ks == SBR_ERR_CAPACITY) {
            FZ_CHECK(nc <= ccap);
            for (uint32_t c = 0u; c < nc; c++) {
                FZ_CHECK(cont[c].length >= 1u && (uint64_t)cont[c].first + cont[c].length <= pcap);
                for (uint32_t k = 0u; k < cont[c].length; k++) {
                    const sbr_point_t p = pts[cont[c].first + k];
                    FZ_CHECK(p.x >= 0 && p.y >= 0 && (uint32_t)p.x < mview.width && (uint32_t)p.y < mview.height);
                    FZ_CHECK(mask[(size_t)p.y * mview.width + (size_t)p.x] != 0u);
                }
            }
            if (ks == SBR_OK) {
                FZ_CHECK(nc >= 1u || r.area == 0u);
            }
        }
    }
}

void fuzz_parts(FuzzedDataProvider &in)
{
    std::vector<uint8_t> buf;
    const sbr_image_t img = fz_image(in, buf, 80u, 80u, SBR_PIXEL_RGB888);
    sbr_parts_config_t cfg;
    sbr_parts_config_default(&cfg);
    fz_edit_fields(in, &cfg, sizeof cfg, 3u);
    sbr_fft_t fft;
    const uint32_t n_fft = in.ConsumeBool() ? cfg.fd_n : (1u << in.ConsumeIntegralInRange<uint32_t>(2u, 11u));
    const bool fft_ok = sbr_fft_init(&fft, n_fft) == SBR_OK;
    const sbr_status_t cs = sbr_parts_config_check(&cfg);
    FZ_STATUS(cs, SBR_OK, SBR_ERR_RANGE, SBR_ERR_SIZE);
    const size_t need = sbr_parts_workspace_size(&cfg, img.width, img.height);
    if (!fz_workspace_fits(cs, need, 128u)) {
        return;
    }
    static sbr_part_t parts[128];
    uint32_t n = 0u;
    sbr_parts_stats_t stats;
    const uint32_t cap = in.ConsumeIntegralInRange<uint32_t>(0u, 128u);
    const sbr_status_t st = sbr_parts_extract(&img, &cfg, fft_ok ? &fft : nullptr, fz_workspace(need > 0u ? need : 64u),
                                              need, parts, cap, &n, &stats);
    FZ_CHECK(fz_known(st));
    if (st == SBR_OK || st == SBR_ERR_CAPACITY) {
        FZ_CHECK(n <= cap);
        for (uint32_t i = 0u; i < n; i++) {
            const sbr_part_t &p = parts[i];
            FZ_STATUS(sbr_fd_check(&p.fd, nullptr), SBR_OK);
            FZ_CHECK(p.fd.m == cfg.fd_m);
            FZ_CHECK((uint64_t)p.bbox.x + p.bbox.width <= img.width && (uint64_t)p.bbox.y + p.bbox.height <= img.height);
            FZ_CHECK(p.map < SBR_MAP_KINDS && (cfg.maps & (1u << p.map)) != 0u);
            // a part's polarity is one its map selects (map_polarity, else mser.polarity)
            const uint32_t sel = cfg.map_polarity[p.map] != 0u ? cfg.map_polarity[p.map] : cfg.mser.polarity;
            FZ_CHECK((sel & p.polarity) != 0u);
        }
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FuzzedDataProvider in(data, size);
    if (in.ConsumeBool()) {
        fuzz_map_mser_contour(in);
    } else {
        fuzz_parts(in);
    }
    return 0;
}
