// SPDX-License-Identifier: MIT
// Fuzz harness: the bicycle model (predict, project, wheel pairing) and its particle
// filter. Statuses: SBR_ERR_RANGE exactly when bike.h's ranges of the model, camera and
// state are broken (header and code say the same). On SBR_OK: states finite with the
// heading in (-pi, pi], the speed and steering kept; ellipses finite; pairs within capacity
// with scores >= 0; filter results with finite means and deviations and an effective
// sample size within [0, particles].
#include "fuzz_common.hpp"

#include <cstddef>

extern "C" {
#include "sbr/bike.h"
}

namespace {

sbr_ellipse_t ellipse_from(FuzzedDataProvider &in)
{
    sbr_ellipse_t e;
    e.cx = fz_float(in, 0.0f, 1280.0f);
    e.cy = fz_float(in, 0.0f, 720.0f);
    e.semi_major = fz_float(in, 0.0f, 200.0f);
    e.semi_minor = fz_float(in, 0.0f, 200.0f);
    e.angle = fz_float(in, -1.6f, 1.6f);
    return e;
}

bool state_ok(const sbr_bike_state_t &s)
{
    return fz_finite(s.x) && fz_finite(s.z) && fz_finite(s.heading) && fz_finite(s.speed) && fz_finite(s.steer) &&
           fz_finite(s.roll);
}

// bike.h's ranges, written out from the header (not from the code)
constexpr float kPi = 3.14159265358979f;
bool header_model(const sbr_bike_model_t &m)
{
    return fz_finite(m.wheel_radius) && fz_finite(m.wheelbase) && fz_finite(m.roll_tau) && m.wheel_radius >= 1e-3f &&
           m.wheel_radius <= 10.0f && m.wheelbase > 2.0f * m.wheel_radius && m.wheelbase < 100.0f &&
           m.roll_tau >= 1e-3f && m.roll_tau <= 1e3f;
}
bool header_state(const sbr_bike_state_t &s)
{
    return state_ok(s) && std::fabs(s.x) < 1e4f && std::fabs(s.z) < 1e4f && s.heading > -kPi && s.heading <= kPi &&
           s.speed >= 0.0f && s.speed <= 100.0f && std::fabs(s.steer) < 0.5f * kPi && std::fabs(s.roll) < 0.5f * kPi;
}
bool header_camera(const sbr_camera_t &c)
{
    return fz_finite(c.focal) && fz_finite(c.cx) && fz_finite(c.cy) && fz_finite(c.height) && c.focal >= 1.0f &&
           c.focal <= 1e6f && std::fabs(c.cx) < 1e6f && std::fabs(c.cy) < 1e6f && c.height >= 1e-3f && c.height <= 1e3f;
}

bool ellipse_ok(const sbr_ellipse_t &e)
{
    return fz_finite(e.cx) && fz_finite(e.cy) && fz_finite(e.semi_major) && fz_finite(e.semi_minor) &&
           fz_finite(e.angle);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FuzzedDataProvider in(data, size);
    sbr_bike_model_t model;
    sbr_bike_model_default(&model);
    if (in.ConsumeBool()) {
        model.wheel_radius = fz_float(in, 0.0f, 1.0f);
        model.wheelbase = fz_float(in, 0.0f, 3.0f);
        model.roll_tau = fz_float(in, 0.0f, 2.0f);
    }
    sbr_bike_state_t s;
    // near the scene, or anywhere in the state's range (a bicycle near its 1e4 m edge)
    const bool far = in.ConsumeIntegral<uint8_t>() < 40u;
    s.x = far ? fz_float(in, -9999.99f, 9999.99f) : fz_float(in, -10.0f, 10.0f);
    s.z = far ? fz_float(in, -9999.99f, 9999.99f) : fz_float(in, 0.0f, 50.0f);
    s.heading = fz_float(in, -3.2f, 3.2f);
    s.speed = fz_float(in, 0.0f, in.ConsumeBool() ? 20.0f : 100.0f);
    s.steer = fz_float(in, -1.6f, 1.6f);
    s.roll = fz_float(in, -1.6f, 1.6f);
    sbr_bike_state_t next;
    const uint32_t dt = in.ConsumeBool() ? in.ConsumeIntegralInRange<uint32_t>(0u, 1000000u)
                                         : in.ConsumeIntegralInRange<uint32_t>(0u, 10000001u);
    const sbr_status_t ps = sbr_bike_predict_state(&model, &s, dt, &next);
    FZ_STATUS(ps, SBR_OK, SBR_ERR_NULL, SBR_ERR_RANGE);
    {
        // valid input is refused only when the state dt later leaves the state's range
        // (issue 70, item 15: an SBR_OK with a state the function itself refuses)
        const bool valid = header_model(model) && header_state(s) && dt <= 10000000u;
        const double reach = std::fmax(std::fabs((double)s.x), std::fabs((double)s.z)) + (double)s.speed * dt * 1e-6;
        const double yaw = (double)s.speed * std::tan((double)s.steer) / (double)model.wheelbase;
        const bool may_leave = reach >= 9999.0 || std::fabs(std::atan((double)s.speed * yaw / 9.81)) > 1.5707;
        FZ_CHECK(valid || ps != SBR_OK);
        FZ_CHECK(!valid || ps == SBR_OK || may_leave);
    }
    if (ps == SBR_OK) {
        // what SBR_OK returns is a state the function takes back
        sbr_bike_state_t again;
        FZ_CHECK(sbr_bike_predict_state(&model, &next, 0u, &again) == SBR_OK);
        FZ_CHECK(state_ok(next));
        FZ_CHECK(next.heading > -kPi && next.heading <= kPi);
        FZ_CHECK(next.speed == s.speed && next.steer == s.steer);
    }
    sbr_bike_pf_config_t cfg;
    sbr_bike_pf_config_default(&cfg);
    cfg.particles = 64u;
    fz_edit_fields(in, &cfg, offsetof(sbr_bike_pf_config_t, particles), 2u);
    fz_edit_fields(in, reinterpret_cast<unsigned char *>(&cfg) + offsetof(sbr_bike_pf_config_t, seed),
                   sizeof cfg - offsetof(sbr_bike_pf_config_t, seed), 2u);
    sbr_ellipse_t rear;
    sbr_ellipse_t front;
    const sbr_status_t js = sbr_bike_project(&cfg.camera, &model, &s, &rear, &front);
    FZ_STATUS(js, SBR_OK, SBR_ERR_NULL, SBR_ERR_RANGE, SBR_ERR_DEGENERATE);
    FZ_CHECK((js == SBR_ERR_RANGE) == !(header_camera(cfg.camera) && header_model(model) && header_state(s)));
    if (js == SBR_OK) {
        FZ_CHECK(ellipse_ok(rear) && ellipse_ok(front));
    }
    sbr_ellipse_t ell[10];
    const uint32_t n = in.ConsumeIntegralInRange<uint32_t>(0u, 10u);
    for (uint32_t i = 0u; i < n; i++) {
        ell[i] = (js == SBR_OK && i < 2u && in.ConsumeBool()) ? (i == 0u ? rear : front) : ellipse_from(in);
    }
    sbr_wheel_pair_t pairs[6];
    uint32_t np = 0u;
    const uint32_t cap = in.ConsumeIntegralInRange<uint32_t>(0u, 6u);
    const sbr_status_t ws = sbr_bike_pair_wheels(ell, n, &model, pairs, cap, &np);
    FZ_CHECK(fz_known(ws));
    if (ws == SBR_OK || ws == SBR_ERR_CAPACITY) {
        FZ_CHECK(np <= cap);
        for (uint32_t i = 0u; i < np; i++) {
            FZ_CHECK(pairs[i].first < n && pairs[i].second < n && pairs[i].first != pairs[i].second);
            FZ_CHECK(fz_finite(pairs[i].score) && pairs[i].score >= 0.0f);
            FZ_CHECK(ellipse_ok(pairs[i].wheel[0]) && ellipse_ok(pairs[i].wheel[1]));
        }
    }
    const sbr_status_t cs = sbr_bike_pf_config_check(&cfg);
    const size_t need = sbr_bike_pf_workspace_size(&cfg);
    FZ_CHECK((need == 0u) == (cs != SBR_OK));
    if (cs != SBR_OK || need > ((size_t)16u << 20)) {
        return 0;
    }
    sbr_bike_pf_t pf;
    FZ_STATUS(sbr_bike_pf_init(&pf, &cfg, fz_workspace(need), need), SBR_OK);
    const uint32_t steps = in.ConsumeIntegralInRange<uint32_t>(1u, 6u);
    for (uint32_t k = 0u; k < steps; k++) {
        sbr_bike_result_t r;
        const uint32_t m = in.ConsumeIntegralInRange<uint32_t>(0u, n);
        const sbr_status_t st = sbr_bike_pf_step(&pf, in.ConsumeIntegralInRange<uint32_t>(0u, 200000u), ell, m, &r);
        FZ_STATUS(st, SBR_OK, SBR_ERR_NULL, SBR_ERR_STATE, SBR_ERR_RANGE, SBR_ERR_SIZE);
        if (st == SBR_OK && (r.flags & SBR_BIKE_TRACKING) != 0u) {
            FZ_CHECK(state_ok(r.mean) && state_ok(r.stddev));
            FZ_CHECK(fz_finite(r.ess) && r.ess >= 0.0f && r.ess <= (float)cfg.particles * 1.001f);
        }
    }
    return 0;
}
