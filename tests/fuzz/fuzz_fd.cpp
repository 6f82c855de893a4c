// SPDX-License-Identifier: MIT
// Fuzz harness: FFT, Fourier descriptors (from integer and float points), mirror, smooth,
// match and table match. On SBR_OK: the FFT's inverse undoes the forward within float
// rounding; descriptors pass sbr_fd_check() with unit energy; a descriptor matches
// itself with error ~0; every match has error in [0, 4], rotation in [-pi, pi], shift in
// [0, 1), a finite positive scale ratio, and a rotation within max_rotation wherever a peak
// was found under a bound; the table's best is its smallest error; the table's four-lane
// and single paths agree on the status; sbr_fd_check() accepts exactly what fd.h lists
// (the energy summed in long double).
#include "fuzz_common.hpp"

#include <algorithm>
#include <cfloat>
#include <cstring>

extern "C" {
#include "sbr/fd.h"
#include "sbr/fft.h"
}

namespace {

void check_match(const sbr_fd_match_t &r, const sbr_fd_match_config_t *cfg = nullptr)
{
    FZ_CHECK(fz_finite(r.error) && r.error >= 0.0f && r.error <= 4.0f + 1e-4f);
    FZ_CHECK(fz_finite(r.rotation) && std::fabs(r.rotation) <= 3.1416f);
    FZ_CHECK(fz_finite(r.shift) && r.shift >= 0.0f && r.shift < 1.0f + 1e-6f);
    FZ_CHECK(fz_finite(r.scale_ratio) && r.scale_ratio > 0.0f);
    // fd.h: under a rotation bound only peaks within it qualify; none: error 4
    if (cfg != nullptr && cfg->mode == SBR_FD_ROTATION_COVARIANT && cfg->max_rotation < 3.14159265f && r.error < 4.0f) {
        FZ_CHECK(std::fabs(r.rotation) <= cfg->max_rotation + 1e-3f);
    }
}

// fd.h's conditions of a valid descriptor, from the header (energy in long double; near
// float32's limit either answer is right)
int header_valid(const sbr_fd_t &d)
{
    if (d.m == 0u || d.m > SBR_FD_MAX_M || !fz_finite(d.scale) || d.scale <= 0.0f || !fz_finite(d.cx) ||
        !fz_finite(d.cy)) {
        return 0;
    }
    long double e = 0.0L;
    for (uint32_t k = 0u; k <= 2u * d.m; k++) {
        if (!fz_finite(d.c[k].re) || !fz_finite(d.c[k].im)) {
            return 0;
        }
        e += (long double)d.c[k].re * d.c[k].re + (long double)d.c[k].im * d.c[k].im;
    }
    if (e > 2.0L * FLT_MAX) {
        return 0;
    }
    return e < 0.5L * FLT_MAX ? 1 : -1;
}

void fuzz_fft(FuzzedDataProvider &in)
{
    sbr_fft_t fft;
    const uint32_t n = in.ConsumeBool() ? (1u << in.ConsumeIntegralInRange<uint32_t>(3u, 10u)) : fz_u32(in, 0u, 2048u);
    const sbr_status_t st = sbr_fft_init(&fft, n);
    FZ_STATUS(st, SBR_OK, SBR_ERR_SIZE, SBR_ERR_NULL);
    FZ_CHECK((st == SBR_OK) == (sbr_fft_size_supported(n) != 0));
    if (st != SBR_OK) {
        return;
    }
    std::vector<sbr_complex_t> x(n), y(n), z(n);
    float mx = 0.0f;
    bool finite = true;
    for (auto &c : x) {
        c.re = fz_float(in, -1e3f, 1e3f);
        c.im = fz_float(in, -1e3f, 1e3f);
        finite = finite && fz_finite(c.re) && fz_finite(c.im);
        mx = std::max(mx, std::max(std::fabs(c.re), std::fabs(c.im)));
    }
    FZ_STATUS(sbr_fft_check(&fft), SBR_OK);
    const sbr_status_t fs = sbr_fft_forward(&fft, x.data(), y.data());
    FZ_CHECK(fz_known(fs));
    if (fs == SBR_OK && finite && mx < 1e30f) {
        FZ_STATUS(sbr_fft_inverse(&fft, y.data(), z.data()), SBR_OK);
        for (uint32_t i = 0u; i < n; i++) {
            // inverse(forward(x)) = x (the inverse is scaled by 1/N)
            FZ_CHECK(std::fabs(z[i].re - x[i].re) <= 1e-4f * mx * (float)n + 1e-30f);
            FZ_CHECK(std::fabs(z[i].im - x[i].im) <= 1e-4f * mx * (float)n + 1e-30f);
        }
    }
    // in place and a corrupted instance
    FZ_CHECK(fz_known(sbr_fft_forward(&fft, x.data(), x.data())));
    sbr_fft_t bad = fft;
    std::vector<uint8_t> junk = in.ConsumeBytes<uint8_t>(sizeof bad);
    if (!junk.empty()) {
        std::memcpy(&bad, junk.data(), std::min(junk.size(), sizeof bad));
    }
    const sbr_status_t bs = sbr_fft_check(&bad);
    FZ_CHECK(fz_known(bs));
    if (bs != SBR_OK) {
        FZ_CHECK(sbr_fft_forward(&bad, x.data(), y.data()) != SBR_OK);
    }
}

void fuzz_descriptors(FuzzedDataProvider &in)
{
    static sbr_fft_t fft_n[7];
    static sbr_fft_t fft_p;
    static bool init = false;
    if (!init) {
        for (uint32_t k = 0u; k < 7u; k++) { /* N = 16 .. 1024 */
            FZ_STATUS(sbr_fft_init(&fft_n[k], 16u << k), SBR_OK);
        }
        FZ_STATUS(sbr_fft_init(&fft_p, 64u), SBR_OK);
        init = true;
    }
    const sbr_fft_t &fft = fft_n[in.ConsumeIntegralInRange<uint32_t>(0u, 6u)];
    const uint32_t m = fz_u32(in, 1u, 20u);
    const uint32_t count = in.ConsumeIntegralInRange<uint32_t>(0u, 300u);
    std::vector<sbr_complex_t> work(in.ConsumeBool() ? 1024u : in.ConsumeIntegralInRange<uint32_t>(0u, 1024u));
    sbr_fd_t a;
    sbr_fd_t b;
    sbr_status_t st;
    if (in.ConsumeBool()) {
        std::vector<sbr_point_t> p(count);
        for (auto &q : p) {
            q.x = in.ConsumeIntegral<int16_t>();
            q.y = in.ConsumeIntegral<int16_t>();
        }
        st = sbr_fd_from_points(&fft, p.data(), count, m, work.data(), (uint32_t)work.size(), &a);
    } else {
        std::vector<sbr_pointf_t> p(count);
        for (auto &q : p) {
            q.x = fz_float(in, -500.0f, 500.0f);
            q.y = fz_float(in, -500.0f, 500.0f);
        }
        st = sbr_fd_from_pointsf(&fft, p.data(), count, m, work.data(), (uint32_t)work.size(), &a);
    }
    FZ_STATUS(st, SBR_OK, SBR_ERR_NULL, SBR_ERR_STATE, SBR_ERR_SIZE, SBR_ERR_DEGENERATE, SBR_ERR_RANGE);
    if (st != SBR_OK) {
        // a descriptor from bytes: every function must refuse or stay finite
        std::vector<uint8_t> raw = in.ConsumeBytes<uint8_t>(sizeof a);
        std::memset(&a, 0, sizeof a);
        if (!raw.empty()) {
            std::memcpy(&a, raw.data(), std::min(raw.size(), sizeof a));
        }
    } else {
        float e = -1.0f;
        FZ_STATUS(sbr_fd_check(&a, &e), SBR_OK);
        FZ_CHECK(a.m == m && std::fabs(e - 1.0f) < 1e-3f);
        FZ_CHECK(fz_finite(a.cx) && fz_finite(a.cy) && fz_finite(a.scale) && a.scale > 0.0f);
    }
    bool unit = st == SBR_OK;
    if (st == SBR_OK && in.ConsumeIntegral<uint8_t>() < 64u) {
        unit = false;
        // a valid descriptor of another energy (tiny: correlations whose square underflows),
        // the factor log-uniform down to 1e-40 or any float
        const float k = in.ConsumeBool() ? std::pow(10.0f, -in.ConsumeFloatingPointInRange<float>(0.0f, 40.0f))
                                         : fz_float(in, 0.0f, 1.0f);
        for (uint32_t i = 0u; i <= 2u * a.m; i++) {
            a.c[i].re *= k;
            a.c[i].im *= k;
        }
    }
    const bool valid = sbr_fd_check(&a, nullptr) == SBR_OK;
    {
        const int hv = header_valid(a);
        FZ_CHECK(hv < 0 || valid == (hv == 1));
    }
    const sbr_status_t ms = sbr_fd_mirror(&a, &b);
    FZ_STATUS(ms, SBR_OK, SBR_ERR_RANGE, SBR_ERR_NULL);
    FZ_CHECK((ms == SBR_OK) == valid);
    if (ms == SBR_OK) {
        FZ_STATUS(sbr_fd_check(&b, nullptr), SBR_OK);
    }
    const float sigma = fz_float(in, 0.0f, 0.5f);
    const sbr_status_t ss = sbr_fd_smooth(&a, sigma, &b);
    FZ_STATUS(ss, SBR_OK, SBR_ERR_RANGE, SBR_ERR_NULL);
    if (ss == SBR_OK) {
        float e = 0.0f;
        FZ_STATUS(sbr_fd_check(&b, &e), SBR_OK);
    }
    sbr_fd_match_config_t cfg;
    sbr_fd_match_config_default(&cfg);
    if (in.ConsumeBool()) {
        cfg.mode = static_cast<sbr_fd_mode_t>(in.ConsumeIntegralInRange<uint32_t>(0u, 2u));
        cfg.max_rotation = fz_float(in, 0.0f, 3.2f);
        cfg.refine = in.ConsumeIntegralInRange<int>(-1, 2);
        cfg.max_error = fz_float(in, 0.0f, 2.5f);
    }
    std::vector<sbr_complex_t> mw(SBR_FD_TABLE_WORK_LEN(64u));
    sbr_fd_match_t r;
    const sbr_status_t xs = sbr_fd_match(&fft_p, &cfg, &a, &a, mw.data(), 64u, &r);
    FZ_CHECK(fz_known(xs));
    if (xs == SBR_OK) {
        check_match(r, &cfg);
        if (unit && cfg.max_error == 0.0f && cfg.max_rotation >= 3.1415f) {
            FZ_CHECK(r.error < 1e-3f); // a descriptor matches itself
        }
    }
    // a table: the descriptor, its mirror, and corrupted copies
    sbr_fd_t table[6];
    const uint32_t nt = in.ConsumeIntegralInRange<uint32_t>(0u, 6u);
    for (uint32_t i = 0u; i < nt; i++) {
        table[i] = a;
        const uint8_t damage = in.ConsumeIntegral<uint8_t>();
        if (damage > 200u) {
            table[i].c[in.ConsumeIntegralInRange<uint32_t>(0u, 2u * SBR_FD_MAX_M)].re = fz_float(in, -2.0f, 2.0f);
        } else if (damage > 190u) {
            table[i].cx = fz_float(in, -100.0f, 100.0f);
        } else if (damage > 180u) {
            table[i].cy = fz_float(in, -100.0f, 100.0f);
        } else if (damage > 170u) {
            table[i].scale = fz_float(in, 0.0f, 100.0f);
        }
    }
    sbr_fd_match_t res[6];
    sbr_fd_match_t res_lanes[6];
    uint32_t best = 99u;
    // both paths: the four-lane one (work_len >= SBR_FD_TABLE_WORK_LEN) and one pair at a
    // time must refuse and accept the same tables
    sbr_status_t both[2];
    for (uint32_t path = 0u; path < 2u; path++) {
        const uint32_t wl = path == 0u ? SBR_FD_TABLE_WORK_LEN(64u) : 64u;
        best = 99u;
        const sbr_status_t ts = sbr_fd_match_table(&fft_p, &cfg, &a, table, nt, mw.data(), wl, res, &best);
        FZ_CHECK(fz_known(ts));
        both[path] = ts;
        if (path == 0u) {
            std::memcpy(res_lanes, res, sizeof res);
        }
        if (ts == SBR_OK) {
            FZ_CHECK(best < nt);
            for (uint32_t i = 0u; i < nt; i++) {
                check_match(res[i], &cfg);
                FZ_CHECK(res[best].error <= res[i].error);
            }
        } else {
            FZ_CHECK(best == 99u);
        }
    }
    // where |r|^2 <= E(query) E(prototype) stays far below float32's limit, neither path may
    // refuse for overflow: the statuses agree; beyond it, either may find the overflow
    long double emax = 0.0L;
    {
        auto energy = [](const sbr_fd_t &d) {
            long double e = 0.0L;
            for (uint32_t k = 0u; k <= 2u * std::min<uint32_t>(d.m, SBR_FD_MAX_M); k++) {
                e += (long double)d.c[k].re * d.c[k].re + (long double)d.c[k].im * d.c[k].im;
            }
            return e;
        };
        for (uint32_t i = 0u; i < nt; i++) {
            emax = std::max(emax, energy(a) * energy(table[i]) * 64.0L * 64.0L);
        }
    }
    const bool may_overflow = !(emax < 1e34L);
    if (!(both[0] == both[1] || (both[0] != SBR_OK && both[1] != SBR_OK) || may_overflow) && fz_first(__LINE__)) {
        std::fprintf(stderr, "table of %u: four-lane path %d, single path %d\n", nt, (int)both[0], (int)both[1]);
        for (uint32_t i = 0u; i < nt; i++) {
            float e = -1.0f;
            std::fprintf(stderr, "  proto %u: check %d energy %g scale %g cx %g cy %g\n", i,
                         (int)sbr_fd_check(&table[i], &e), e, table[i].scale, table[i].cx, table[i].cy);
        }
        float e = -1.0f;
        std::fprintf(stderr, "  query: check %d energy %g mode %d maxrot %g refine %d maxerr %g\n", (int)sbr_fd_check(&a, &e),
                     e, (int)cfg.mode, cfg.max_rotation, cfg.refine, cfg.max_error);
    }
    FZ_CHECK(both[0] == both[1] || (both[0] != SBR_OK && both[1] != SBR_OK) || may_overflow);
    // the prepared table (sbr_fd_table_init() once, sbr_fd_match_prepared() per query):
    // for entries the check accepts, the same status and, bit for bit, the same matches as
    // sbr_fd_match_table() on the four-lane path; a sub-range matches that range alone
    {
        sbr_fd_table_t tb{};
        std::vector<float> mags(SBR_FD_TABLE_MAGS_LEN(6u, SBR_FD_MAX_M) + 1u);
        const size_t mlen = in.ConsumeBool() ? mags.size() : in.ConsumeIntegralInRange<size_t>(0u, mags.size());
        const sbr_status_t is = sbr_fd_table_init(&tb, nt > 0u ? table : nullptr, nt, mags.data(), mlen);
        FZ_STATUS(is, SBR_OK, SBR_ERR_NULL, SBR_ERR_SIZE, SBR_ERR_RANGE);
        bool entries_ok = nt > 0u;
        for (uint32_t i = 0u; i < nt; i++) {
            float e = 0.0f;
            entries_ok = entries_ok && sbr_fd_check(&table[i], &e) == SBR_OK && table[i].m == table[0].m &&
                         table[i].scale >= SBR_FD_TABLE_MIN_SCALE && table[i].scale <= SBR_FD_TABLE_MAX_SCALE;
        }
        if (entries_ok && mlen >= SBR_FD_TABLE_MAGS_LEN(nt, table[0].m)) {
            FZ_CHECK(is == SBR_OK);
        } else {
            FZ_CHECK(is != SBR_OK);
        }
        sbr_fd_match_t pres[6];
        uint32_t pbest = 99u;
        const sbr_status_t ps =
            sbr_fd_match_prepared(&fft_p, &cfg, &tb, 0u, nt, &a, mw.data(), SBR_FD_TABLE_WORK_LEN(64u), pres, &pbest);
        FZ_STATUS(ps, SBR_OK, SBR_ERR_NULL, SBR_ERR_STATE, SBR_ERR_SIZE, SBR_ERR_RANGE);
        if (is != SBR_OK) {
            FZ_CHECK(ps == SBR_ERR_STATE); // a table init refused stays unusable
        } else if (a.scale >= SBR_FD_TABLE_MIN_SCALE && a.scale <= SBR_FD_TABLE_MAX_SCALE) {
            FZ_CHECK(ps == both[0] || may_overflow);
            if (ps == SBR_OK && both[0] == SBR_OK) {
                FZ_CHECK(pbest < nt);
                FZ_CHECK(std::memcmp(pres, res_lanes, nt * sizeof(sbr_fd_match_t)) == 0);
            }
            if (nt >= 2u) {
                sbr_fd_match_t one;
                uint32_t b1 = 99u;
                FZ_CHECK(sbr_fd_match_prepared(&fft_p, &cfg, &tb, nt - 1u, 2u, &a, mw.data(), SBR_FD_TABLE_WORK_LEN(64u),
                                               &one, &b1) == SBR_ERR_SIZE);
            }
            // a table changed after its init is refused
            sbr_fd_table_t moved = tb;
            moved.count = nt + 1u;
            FZ_CHECK(sbr_fd_match_prepared(&fft_p, &cfg, &moved, 0u, 1u, &a, mw.data(), SBR_FD_TABLE_WORK_LEN(64u), pres,
                                           &pbest) == SBR_ERR_STATE);
        } else {
            FZ_CHECK(ps == SBR_ERR_RANGE || ps == SBR_ERR_NULL);
        }
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FuzzedDataProvider in(data, size);
    if (in.ConsumeIntegral<uint8_t>() < 64u) {
        fuzz_fft(in);
    } else {
        fuzz_descriptors(in);
    }
    return 0;
}
