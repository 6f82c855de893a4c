// SPDX-License-Identifier: MIT
// Shared by sbr's libFuzzer harnesses (tests/fuzz/): reading values from the input, and
// invariant checks that abort (so libFuzzer reports the input) when an output that came
// with SBR_OK breaks what the header promises.
#ifndef SBR_FUZZ_COMMON_HPP
#define SBR_FUZZ_COMMON_HPP

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <initializer_list>

#include <vector>

extern "C" {
#include "sbr/image.h"
#include "sbr/status.h"
}

// A failed invariant aborts, so libFuzzer keeps the input. With SBR_FUZZ_KEEP_GOING set
// (a survey of which checks an old build breaks, docs/usage/fuzz.md), each failing check
// is reported once, with the executions and seconds until it first failed, and the run
// goes on.
inline bool fz_keep_going(const char *cond, const char *file, int line)
{
    static const bool keep = std::getenv("SBR_FUZZ_KEEP_GOING") != nullptr;
    static std::vector<int> seen;
    static unsigned long runs = 0; // calls that failed a check, a rough clock
    static const std::time_t t0 = std::time(nullptr);
    if (!keep) {
        return false;
    }
    ++runs;
    for (int l : seen) {
        if (l == line) {
            return true;
        }
    }
    seen.push_back(line);
    std::fprintf(stderr, "sbr fuzz: first failure of %s (%s:%d) after %ld s\n", cond, file, line,
                 (long)(std::time(nullptr) - t0));
    return true;
}

// Diagnostics printed before a check fails: always when failures abort, once per place
// in the survey mode.
inline bool fz_first(int line)
{
    static std::vector<int> seen;
    if (std::getenv("SBR_FUZZ_KEEP_GOING") == nullptr) {
        return true;
    }
    for (int l : seen) {
        if (l == line) {
            return false;
        }
    }
    seen.push_back(line);
    return true;
}

#define FZ_CHECK(cond)                                                                     \
    do {                                                                                   \
        if (!(cond) && !fz_keep_going(#cond, __FILE__, __LINE__)) {                       \
            std::fprintf(stderr, "sbr fuzz: invariant failed: %s (%s:%d)\n", #cond,        \
                         __FILE__, __LINE__);                                              \
            std::abort();                                                                  \
        }                                                                                  \
    } while (0)

// The status is one of those the function documents.
inline bool fz_in(sbr_status_t st, std::initializer_list<sbr_status_t> documented)
{
    for (sbr_status_t d : documented) {
        if (st == d) {
            return true;
        }
    }
    std::fprintf(stderr, "sbr fuzz: undocumented status %d (%s)\n", (int)st, sbr_status_str(st));
    return false;
}
#define FZ_STATUS(st, ...) FZ_CHECK(fz_in((st), {__VA_ARGS__}))

// A float as a hostile caller gives it: mostly in [lo, hi], sometimes a special value
// (NaN, +-Inf, 0, -0, the extremes of float, a denormal) or any bit pattern.
inline float fz_float(FuzzedDataProvider &in, float lo, float hi)
{
    const uint8_t kind = in.ConsumeIntegral<uint8_t>();
    if (kind < 200u) {
        return in.ConsumeFloatingPointInRange<float>(lo, hi);
    }
    if (kind < 240u) {
        static const float special[] = {NAN, INFINITY, -INFINITY, 0.0f, -0.0f, 3.4e38f, -3.4e38f,
                                        1e-45f, 1e-30f, 1e30f, -1.0f, 1.0f, 0.5f, 1e6f, -1e6f};
        return special[in.ConsumeIntegralInRange<size_t>(0, sizeof(special) / sizeof(special[0]) - 1)];
    }
    uint32_t bits = in.ConsumeIntegral<uint32_t>();
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

// A count: mostly small, sometimes anything.
inline uint32_t fz_u32(FuzzedDataProvider &in, uint32_t lo, uint32_t hi)
{
    if (in.ConsumeIntegral<uint8_t>() < 230u) {
        return in.ConsumeIntegralInRange<uint32_t>(lo, hi);
    }
    return in.ConsumeIntegral<uint32_t>();
}

// Overwrite up to `edits` 4-byte fields of a configuration struct whose first `bytes`
// bytes are all uint32_t/float fields (offsets multiple of 4), with values from the input.
inline void fz_edit_fields(FuzzedDataProvider &in, void *cfg, size_t bytes, uint32_t edits)
{
    const size_t fields = bytes / 4u;
    const uint32_t n = in.ConsumeIntegralInRange<uint32_t>(0u, edits);
    for (uint32_t i = 0u; (i < n) && (fields > 0u); i++) {
        const size_t f = in.ConsumeIntegralInRange<size_t>(0u, fields - 1u);
        uint32_t v;
        const uint8_t how = in.ConsumeIntegral<uint8_t>();
        if (how < 96u) { // a small integer
            v = in.ConsumeIntegralInRange<uint32_t>(0u, 64u);
        } else if (how < 192u) { // a float in a plausible range, or a special value
            const float x = fz_float(in, -4.0f, 4.0f);
            std::memcpy(&v, &x, sizeof v);
        } else { // the old value scaled or any bits
            v = in.ConsumeIntegral<uint32_t>();
        }
        std::memcpy(static_cast<unsigned char *>(cfg) + (4u * f), &v, sizeof v);
    }
}

inline bool fz_finite(float x) { return std::isfinite(x) != 0; }

// Any status sbr defines.
inline bool fz_known(sbr_status_t st) { return (st <= SBR_OK) && (st >= SBR_ERR_CORRUPT); }

// An image view from the input: size up to max_w x max_h, a format (sometimes one the
// caller did not ask for, or none), a stride (sometimes too short or odd), the pixels
// from the input (repeated when it runs out). `buf` owns the pixels.
inline sbr_image_t fz_image(FuzzedDataProvider &in, std::vector<uint8_t> &buf, uint32_t max_w,
                            uint32_t max_h, sbr_pixel_format_t usual)
{
    sbr_image_t img;
    img.width = in.ConsumeIntegralInRange<uint32_t>(1u, max_w);
    img.height = in.ConsumeIntegralInRange<uint32_t>(1u, max_h);
    const uint8_t f = in.ConsumeIntegral<uint8_t>();
    img.format = (f < 200u) ? usual
                            : static_cast<sbr_pixel_format_t>(in.ConsumeIntegralInRange<uint32_t>(0u, 5u));
    const uint32_t bpp = (img.format == SBR_PIXEL_GRAY8) ? 1u : 3u;
    const uint8_t k = in.ConsumeIntegral<uint8_t>();
    uint32_t stride = img.width * bpp;
    if (k >= 160u && k < 230u) {
        stride += in.ConsumeIntegralInRange<uint32_t>(1u, 16u);
    } else if (k >= 230u) {
        stride = in.ConsumeIntegralInRange<uint32_t>(0u, img.width * bpp + 8u);
    }
    img.stride = stride;
    const size_t bytes = (size_t)((stride > img.width * bpp) ? stride : img.width * bpp) * img.height;
    buf.assign(bytes + 16u, 0u);
    const std::vector<uint8_t> px = in.ConsumeBytes<uint8_t>(in.ConsumeIntegralInRange<size_t>(0u, bytes));
    for (size_t i = 0; (i < bytes) && !px.empty(); i++) {
        buf[i] = px[i % px.size()];
    }
    img.data = (in.ConsumeIntegral<uint8_t>() < 250u) ? buf.data() : nullptr;
    return img;
}

// A configuration's workspace size: 0 for a configuration its check refused (checked);
// true when the harness can give it (at most `limit_mb` MiB).
inline bool fz_workspace_fits(sbr_status_t config_status, size_t need, size_t limit_mb)
{
    if (config_status != SBR_OK) {
        FZ_CHECK(need == 0u); // a bad configuration has no workspace size
    }
    return need <= (limit_mb << 20);
}

// 8-byte aligned scratch of at least `bytes` bytes, reused between runs.
inline void *fz_workspace(size_t bytes)
{
    static std::vector<uint64_t> ws;
    if (ws.size() * 8u < bytes) {
        ws.assign((bytes + 7u) / 8u, 0u);
    }
    return ws.data();
}

#endif
