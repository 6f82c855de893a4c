// SPDX-License-Identifier: MIT
// Fuzz harness: conic classification, ellipse <-> conic, direct fit, residual, coverage,
// torchlight pose and ellipse detection. On SBR_OK: classes in the enum and, where the
// conic is clear of the zero rule's thresholds, the class conic.h's rule gives in exact
// (long double) arithmetic; ellipses finite with 0 < semi_minor <= semi_major, the
// geometry of the conic they came from (exactly), and a conic that sbr_ellipse_to_conic()
// takes back and that is, exactly, that ellipse within 1 %; fitted conics that are that
// ellipse; a refused call leaves its output untouched; conics finite; residuals finite and
// >= 0; coverage in [0, 1]; poses finite; detections inside the image; the workspace macro
// equal to its function.
#include "fuzz_common.hpp"
#include "fuzz_exact.hpp"

#include <cfloat>

extern "C" {
#include "sbr/conic.h"
}

namespace {

// The float32 conic of an ellipse computed in long double and rounded once: thin and far
// ellipses whose constant term barely holds their shape (what sbr_ellipse_to_conic()
// refuses to make, but a caller may have).
sbr_conic_t rounded_conic(FuzzedDataProvider &in)
{
    const long double cx = fz_float(in, -2e5f, 2e5f), cy = fz_float(in, -2e5f, 2e5f);
    const long double ma = std::fabs((long double)fz_float(in, 1e-3f, 500.0f)) + 1e-3L;
    const long double mi = ma * std::fabs((long double)fz_float(in, 1e-4f, 1.0f));
    const long double t = fz_float(in, -4.0f, 4.0f);
    const long double cs = std::cos(t), sn = std::sin(t), ia = 1.0L / (ma * ma), ib = 1.0L / (mi * mi);
    const long double a = cs * cs * ia + sn * sn * ib, b = cs * sn * (ia - ib), c = sn * sn * ia + cs * cs * ib;
    const long double k = in.ConsumeBool() ? 1.0L : std::pow(10.0L, (long double)in.ConsumeIntegralInRange<int>(-30, 30));
    sbr_conic_t q;
    q.a = (float)(k * a);
    q.b = (float)(k * b);
    q.c = (float)(k * c);
    q.d = (float)(-k * (a * cx + b * cy));
    q.e = (float)(-k * (b * cx + c * cy));
    q.f = (float)(k * (a * cx * cx + 2.0L * b * cx * cy + c * cy * cy - 1.0L));
    return q;
}

// An ellipse as a caller gives one: centre within +-reach, axes to 500 px, any angle.
sbr_ellipse_t ellipse_from(FuzzedDataProvider &in, float reach)
{
    sbr_ellipse_t e;
    e.cx = fz_float(in, -reach, reach);
    e.cy = fz_float(in, -reach, reach);
    e.semi_major = fz_float(in, 0.0f, 500.0f);
    e.semi_minor = fz_float(in, 0.0f, 500.0f);
    e.angle = fz_float(in, -4.0f, 4.0f);
    return e;
}

sbr_conic_t conic_from(FuzzedDataProvider &in)
{
    sbr_conic_t q;
    const uint8_t kind = in.ConsumeIntegral<uint8_t>();
    if (kind < 64u) {
        return rounded_conic(in);
    }
    if (kind < 160u) { // near an ellipse of the image plane
        const sbr_ellipse_t e = ellipse_from(in, 2000.0f);
        if (sbr_ellipse_to_conic(&e, &q) == SBR_OK) {
            return q;
        }
    }
    q.a = fz_float(in, -2.0f, 2.0f);
    q.b = fz_float(in, -2.0f, 2.0f);
    q.c = fz_float(in, -2.0f, 2.0f);
    q.d = fz_float(in, -500.0f, 500.0f);
    q.e = fz_float(in, -500.0f, 500.0f);
    q.f = fz_float(in, -1e5f, 1e5f);
    return q;
}

bool conic_ok(const sbr_conic_t &q)
{
    return fz_finite(q.a) && fz_finite(q.b) && fz_finite(q.c) && fz_finite(q.d) && fz_finite(q.e) && fz_finite(q.f);
}

// conic.h's 1 % (of each semi-axis; of the semi-major for the centre), with room for the
// float32 geometry's own rounding
constexpr long double kSameEllipse = 0.0105L;

void check_ellipse(const sbr_ellipse_t &e)
{
    FZ_CHECK(fz_finite(e.cx) && fz_finite(e.cy) && fz_finite(e.angle));
    FZ_CHECK(fz_finite(e.semi_major) && fz_finite(e.semi_minor));
    FZ_CHECK(e.semi_minor > 0.0f && e.semi_minor <= e.semi_major);
    sbr_conic_t back;
    FZ_STATUS(sbr_ellipse_to_conic(&e, &back), SBR_OK);
    FZ_CHECK(conic_ok(back));
    FZ_CHECK(exact_is_ellipse(back, e, kSameEllipse));
}

// The class conic.h's zero rule gives in exact arithmetic, where the conic is clear of
// its thresholds (a factor 2 either way); -1 where it is not.
int exact_class(const sbr_conic_t &q, float tol)
{
    const ExactConic x = exact_conic(q, true);
    const long double t = tol, t_hi = std::fmax(2.0L * t, 0x1p-38L), t_lo = 0.5L * t;
    if (x.q == 0.0L) {
        return -1; // the no-centre cases: not checked here
    }
    if (std::fabs(x.d22) > t_hi * x.q * x.q) {
        const long double s = (x.a + x.c) < 0.0L ? -1.0L : 1.0L;
        const bool zero = std::fabs(x.f0) < t_lo * x.terms, nonzero = std::fabs(x.f0) > t_hi * x.terms;
        if (x.d22 > 0.0L) {
            return zero ? SBR_CONIC_POINT_ELLIPSE
                        : (nonzero ? (s * x.f0 < 0.0L ? SBR_CONIC_REAL_ELLIPSE : SBR_CONIC_IMAGINARY_ELLIPSE) : -1);
        }
        return zero ? SBR_CONIC_INTERSECTING_LINES : (nonzero ? SBR_CONIC_HYPERBOLA : -1);
    }
    return -1;
}

// SBR_ERR_RANGE from the classification of finite entries: only for a centre float32
// cannot place (linear or constant terms beyond 2^50 or 2^100 times the quadratic part,
// with a factor 2 for the power-of-two scaling).
bool centre_out_of_reach(const sbr_conic_t &q)
{
    const ExactConic x = exact_conic(q, true);
    return x.q > 0.0L && (std::fmax(std::fabs(x.d), std::fabs(x.e)) > 0x1p49L * x.q || std::fabs(x.f) > 0x1p99L * x.q);
}

// A conic without a centre built exactly from small integers (issue 70, item 14): two
// parallel lines, real or imaginary, a double line or a parabola in u = p x + q y, each
// scaled by a power of two 2^k (|k| <= 100: a scale the class does not depend on). The
// class is known by construction; sbr_conic_classify() at tol 0 must give it.
void fuzz_no_centre(FuzzedDataProvider &in)
{
    const long double p = in.ConsumeIntegralInRange<int>(-40, 40), q = in.ConsumeIntegralInRange<int>(-40, 40);
    const long double r = in.ConsumeIntegralInRange<int>(-300, 300), t = in.ConsumeIntegralInRange<int>(-300, 300);
    const int kind = in.ConsumeIntegralInRange<int>(0, 3);
    const int k = in.ConsumeIntegralInRange<int>(-100, 100);
    if (p == 0.0L && q == 0.0L) {
        return;
    }
    // u = p x + q y; the conic as A u^2 + 2 D x + 2 E y + F with exact small integers
    long double d = 0.0L, e = 0.0L, f = 0.0L;
    sbr_conic_class_t want = SBR_CONIC_DOUBLE_LINE;
    switch (kind) {
    case 0: // (u + r)(u + t): real parallel lines (r != t), a double line (r == t)
        d = p * (r + t) / 2.0L;
        e = q * (r + t) / 2.0L;
        f = r * t;
        want = r == t ? SBR_CONIC_DOUBLE_LINE : SBR_CONIC_PARALLEL_LINES;
        break;
    case 1: // (u + r)^2 + t^2, t != 0: no real point
        if (t == 0.0L) {
            return;
        }
        d = p * r;
        e = q * r;
        f = r * r + t * t;
        want = SBR_CONIC_IMAGINARY_PARALLEL_LINES;
        break;
    case 2: // u^2 + 2 (r x + t y): a parabola when (r, t) is not parallel to (p, q)
        if (p * t - q * r == 0.0L) {
            return;
        }
        d = r;
        e = t;
        want = SBR_CONIC_PARABOLA;
        break;
    default: // (u + r)^2: a double line
        d = p * r;
        e = q * r;
        f = r * r;
        want = SBR_CONIC_DOUBLE_LINE;
        break;
    }
    // every entry an integer below 2^20 (the halves of case 0 are whole or .5): exact in
    // float32 as long as it keeps 24 bits, and ldexp by k exact unless out of range
    const long double v[6] = {p * p, p * q, q * q, d, e, f};
    float c[6];
    for (int i = 0; i < 6; ++i) {
        if (std::fabs(v[i]) >= 0x1p23L) {
            return;
        }
        const long double sc = std::ldexp(v[i], k);
        if (v[i] != 0.0L && (std::fabs(sc) < 0x1p-126L || std::fabs(sc) > 0x1p127L)) {
            return;
        }
        c[i] = (float)sc;
    }
    const sbr_conic_t qc = {c[0], c[1], c[2], c[3], c[4], c[5]};
    sbr_conic_class_t cls = (sbr_conic_class_t)0;
    FZ_STATUS(sbr_conic_classify(&qc, 0.0f, &cls), SBR_OK);
    if (cls != want && fz_first(__LINE__)) {
        std::fprintf(stderr, "conic %.9g %.9g %.9g %.9g %.9g %.9g (2^%d): class %d, by construction %d\n", qc.a, qc.b,
                     qc.c, qc.d, qc.e, qc.f, k, (int)cls, (int)want);
    }
    FZ_CHECK(cls == want);
}

void fuzz_geometry(FuzzedDataProvider &in)
{
    const sbr_conic_t q = conic_from(in);
    sbr_conic_class_t cls;
    const float tol = in.ConsumeBool() ? SBR_CONIC_ZERO_TOL : fz_float(in, 0.0f, 1.0f);
    const sbr_status_t cs = sbr_conic_classify(&q, tol, &cls);
    FZ_STATUS(cs, SBR_OK, SBR_ERR_RANGE, SBR_ERR_DEGENERATE);
    if (cs == SBR_OK) {
        FZ_CHECK((int)cls >= (int)SBR_CONIC_REAL_ELLIPSE && (int)cls <= (int)SBR_CONIC_INTERSECTING_LINES);
        const int want = exact_class(q, tol);
        if (!(want < 0 || (int)cls == want) && fz_first(__LINE__)) {
            std::fprintf(stderr, "conic %.9g %.9g %.9g %.9g %.9g %.9g tol %.9g: class %d, exactly %d\n", q.a, q.b, q.c,
                         q.d, q.e, q.f, tol, (int)cls, want);
        }
        FZ_CHECK(want < 0 || (int)cls == want);
    } else if (cs == SBR_ERR_RANGE && conic_ok(q) && tol >= 0.0f && tol < 1.0f) {
        if (!centre_out_of_reach(q) && fz_first(__LINE__)) {
            std::fprintf(stderr, "conic %.9g %.9g %.9g %.9g %.9g %.9g tol %.9g\n", q.a, q.b, q.c, q.d, q.e, q.f, tol);
        }
        FZ_CHECK(centre_out_of_reach(q));
    }
    sbr_ellipse_t e = {7.0f, 7.0f, 7.0f, 7.0f, 7.0f};
    const sbr_status_t es = sbr_conic_to_ellipse(&q, &e);
    FZ_STATUS(es, SBR_OK, SBR_ERR_RANGE, SBR_ERR_DEGENERATE);
    if (es == SBR_OK) {
        check_ellipse(e);
        // the geometry is the conic's own (exactly), and the conic a real ellipse at the
        // default tolerance
        const ExactConic x = exact_conic(q);
        long double major = 0.0L, minor = 0.0L;
        FZ_CHECK(exact_ellipse(x, major, minor));
        FZ_CHECK(near_rel(major, e.semi_major, e.semi_major, 1e-3L) && near_rel(minor, e.semi_minor, e.semi_minor, 1e-3L));
        const long double reach = 1e-3L * e.semi_major + 1e-5L * std::fmax(std::fabs(x.xc), std::fabs(x.yc));
        FZ_CHECK(std::fabs(x.xc - e.cx) <= reach && std::fabs(x.yc - e.cy) <= reach);
        sbr_conic_class_t c2;
        FZ_STATUS(sbr_conic_classify(&q, SBR_CONIC_ZERO_TOL, &c2), SBR_OK);
        FZ_CHECK(c2 == SBR_CONIC_REAL_ELLIPSE);
    } else {
        FZ_CHECK(e.cx == 7.0f && e.cy == 7.0f && e.semi_major == 7.0f && e.semi_minor == 7.0f && e.angle == 7.0f);
    }
    {
        // an ellipse given directly: its conic is that ellipse, or the call is refused
        // and the output untouched
        const sbr_ellipse_t g = ellipse_from(in, 2e5f);
        const sbr_conic_t guard = {7.0f, 7.0f, 7.0f, 7.0f, 7.0f, 7.0f};
        sbr_conic_t gq = guard;
        const sbr_status_t gs = sbr_ellipse_to_conic(&g, &gq);
        FZ_STATUS(gs, SBR_OK, SBR_ERR_RANGE);
        if (gs == SBR_OK) {
            FZ_CHECK(conic_ok(gq) && exact_is_ellipse(gq, g, kSameEllipse));
        } else {
            FZ_CHECK(std::memcmp(&gq, &guard, sizeof gq) == 0);
        }
    }
    // points: on the ellipse with noise, a cluster of nearly equal points, or anything
    const uint32_t n = in.ConsumeIntegralInRange<uint32_t>(0u, 256u);
    std::vector<sbr_pointf_t> p(n);
    const bool cluster = in.ConsumeIntegral<uint8_t>() < 48u;
    const float bx = fz_float(in, -1000.0f, 1000.0f), by = fz_float(in, -1000.0f, 1000.0f);
    const float spread = in.ConsumeFloatingPointInRange<float>(0.0f, 0.5f);
    for (uint32_t i = 0u; i < n; i++) {
        if (cluster) {
            const bool same = in.ConsumeBool();
            p[i].x = bx + (same ? 0.0f : fz_float(in, -spread, spread));
            p[i].y = by + (same ? 0.0f : fz_float(in, -spread, spread));
        } else if (es == SBR_OK && in.ConsumeBool()) {
            const float t = 6.2831853f * (float)i / (float)n;
            const float u = e.semi_major * std::cos(t);
            const float v = e.semi_minor * std::sin(t);
            p[i].x = e.cx + u * std::cos(e.angle) - v * std::sin(e.angle) + fz_float(in, -1.0f, 1.0f);
            p[i].y = e.cy + u * std::sin(e.angle) + v * std::cos(e.angle);
        } else {
            p[i].x = fz_float(in, -1000.0f, 1000.0f);
            p[i].y = fz_float(in, -1000.0f, 1000.0f);
        }
    }
    sbr_conic_t fit;
    sbr_ellipse_t fe;
    const sbr_status_t fs = sbr_ellipse_fit(p.data(), n, &fit, &fe);
    FZ_STATUS(fs, SBR_OK, SBR_ERR_NULL, SBR_ERR_SIZE, SBR_ERR_RANGE, SBR_ERR_DEGENERATE);
    if (fs == SBR_OK) {
        FZ_CHECK(conic_ok(fit));
        check_ellipse(fe);
        FZ_CHECK(exact_is_ellipse(fit, fe, kSameEllipse));
    }
    float rms = -1.0f;
    float mx = -1.0f;
    const sbr_status_t rs = sbr_conic_residual(&q, p.data(), n, &rms, &mx);
    FZ_STATUS(rs, SBR_OK, SBR_ERR_NULL, SBR_ERR_SIZE, SBR_ERR_RANGE);
    if (rs == SBR_OK) {
        FZ_CHECK(fz_finite(rms) && rms >= 0.0f && fz_finite(mx) && mx >= 0.0f);
    }
    float cov = -1.0f;
    const sbr_status_t vs = sbr_ellipse_coverage(&q, p.data(), n, fz_float(in, 0.0f, 5.0f), &cov);
    FZ_STATUS(vs, SBR_OK, SBR_ERR_NULL, SBR_ERR_SIZE, SBR_ERR_RANGE, SBR_ERR_DEGENERATE);
    if (vs == SBR_OK) {
        FZ_CHECK(cov >= 0.0f && cov <= 1.0f);
    }
    sbr_torch_pose_t pose;
    const sbr_status_t ts = sbr_torch_pose(&q, fz_float(in, 0.0f, 3000.0f), fz_float(in, 0.0f, 1.0f), &pose);
    FZ_CHECK(fz_known(ts));
    if (ts == SBR_OK) {
        FZ_CHECK(fz_finite(pose.n1) && fz_finite(pose.n2) && fz_finite(pose.z0_over_r) && fz_finite(pose.residual));
        FZ_CHECK(pose.residual >= 0.0f);
    }
}

void fuzz_detect(FuzzedDataProvider &in)
{
    std::vector<uint8_t> buf;
    const sbr_image_t img = fz_image(in, buf, 64u, 64u, SBR_PIXEL_GRAY8);
    sbr_ellipse_detect_config_t cfg;
    sbr_ellipse_detect_config_default(&cfg);
    fz_edit_fields(in, &cfg, sizeof cfg, 3u);
    const sbr_status_t cs = sbr_ellipse_detect_config_check(&cfg);
    const size_t need = sbr_ellipse_detect_workspace_size(&cfg, img.width, img.height);
    if (need > 0u) {
        // conic.h: the macro equals the function for the configuration's values
        FZ_CHECK(need == SBR_ELLIPSE_DETECT_WORKSPACE_SIZE(img.width, img.height, cfg.mser.delta, cfg.mser.max_nodes, cfg.mser.max_heap,
                                                             cfg.max_regions, cfg.max_contour_points));
    }
    if (!fz_workspace_fits(cs, need, 64u)) {
        return;
    }
    sbr_ellipse_det_t det[16];
    uint32_t n = 0u;
    const uint32_t cap = in.ConsumeIntegralInRange<uint32_t>(0u, 16u);
    const sbr_status_t st = sbr_ellipse_detect(&img, &cfg, fz_workspace(need > 0u ? need : 64u), need, det, cap, &n);
    FZ_CHECK(fz_known(st));
    if (st == SBR_OK || st == SBR_ERR_CAPACITY) {
        FZ_CHECK(n <= cap);
        for (uint32_t i = 0u; i < n; i++) {
            check_ellipse(det[i].ellipse);
            FZ_CHECK(conic_ok(det[i].conic));
            FZ_CHECK(fz_finite(det[i].residual) && det[i].residual >= 0.0f && det[i].residual <= cfg.max_residual);
            FZ_CHECK(det[i].coverage >= 0.0f && det[i].coverage <= 1.0f && det[i].merged >= 1u);
        }
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FuzzedDataProvider in(data, size);
    const uint8_t which = in.ConsumeIntegral<uint8_t>();
    if (which < 170u) {
        fuzz_geometry(in);
    } else if (which < 200u) {
        fuzz_no_centre(in);
    } else {
        fuzz_detect(in);
    }
    return 0;
}
