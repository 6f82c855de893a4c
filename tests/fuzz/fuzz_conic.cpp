// Fuzz harness: conic classification, ellipse <-> conic, direct fit, residual, coverage,
// torchlight pose and ellipse detection. On SBR_OK: classes in the enum; ellipses finite
// with 0 < semi_minor <= semi_major and a conic that sbr_ellipse_to_conic() takes back;
// conics finite; residuals finite and >= 0; coverage in [0, 1]; poses finite; detections
// inside the image.
#include "fuzz_common.hpp"

extern "C" {
#include "sbr/conic.h"
}

namespace {

sbr_conic_t conic_from(FuzzedDataProvider &in)
{
    sbr_conic_t q;
    if (in.ConsumeBool()) { // near an ellipse of the image plane
        sbr_ellipse_t e;
        e.cx = fz_float(in, -2000.0f, 2000.0f);
        e.cy = fz_float(in, -2000.0f, 2000.0f);
        e.semi_major = fz_float(in, 0.0f, 500.0f);
        e.semi_minor = fz_float(in, 0.0f, 500.0f);
        e.angle = fz_float(in, -4.0f, 4.0f);
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

void check_ellipse(const sbr_ellipse_t &e)
{
    FZ_CHECK(fz_finite(e.cx) && fz_finite(e.cy) && fz_finite(e.angle));
    FZ_CHECK(fz_finite(e.semi_major) && fz_finite(e.semi_minor));
    FZ_CHECK(e.semi_minor > 0.0f && e.semi_minor <= e.semi_major);
    sbr_conic_t back;
    FZ_STATUS(sbr_ellipse_to_conic(&e, &back), SBR_OK);
    FZ_CHECK(conic_ok(back));
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
    }
    sbr_ellipse_t e;
    const sbr_status_t es = sbr_conic_to_ellipse(&q, &e);
    FZ_STATUS(es, SBR_OK, SBR_ERR_RANGE, SBR_ERR_DEGENERATE);
    if (es == SBR_OK) {
        check_ellipse(e);
    }
    // points: on the ellipse with noise, or anything
    const uint32_t n = in.ConsumeIntegralInRange<uint32_t>(0u, 64u);
    std::vector<sbr_pointf_t> p(n);
    for (uint32_t i = 0u; i < n; i++) {
        if (es == SBR_OK && in.ConsumeBool()) {
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
    if (in.ConsumeIntegral<uint8_t>() < 200u) {
        fuzz_geometry(in);
    } else {
        fuzz_detect(in);
    }
    return 0;
}
