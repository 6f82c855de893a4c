// SPDX-License-Identifier: MIT
// Fuzz harness: the servo learner and steps (learned J and a given J) with hostile configurations, commands and
// features (NaN, infinities, huge values, angles far off the seam), learning sequences
// that run the field bound full, and a corrupted instance. On SBR_OK: every Jacobian
// entry finite; a step's command finite, within the joint limits and at most max_step
// from y per joint; CONVERGED and LIMIT leave y; iterations never exceed the bound.
#include "fuzz_common.hpp"

#include <vector>

extern "C" {
#include "sbr/servo.h"
}

namespace {

sbr_servo_config_t config_from(FuzzedDataProvider &in)
{
    sbr_servo_config_t cfg;
    const uint32_t m = fz_u32(in, 1u, SBR_SERVO_MAX_JOINTS);
    const uint32_t n = fz_u32(in, 1u, SBR_SERVO_MAX_FEATURES);
    sbr_servo_config_default(&cfg, m, n);
    if (in.ConsumeBool()) {
        cfg.max_fields = fz_u32(in, 1u, 64u);
        cfg.angle_mask = fz_u32(in, 0u, 15u);
        cfg.new_field_activation = fz_float(in, 0.0f, 1.0f);
        cfg.forgetting = fz_float(in, 0.85f, 1.0f);
        cfg.prior = fz_float(in, 0.0f, 1e6f);
        cfg.gain = fz_float(in, 0.0f, 1.2f);
        cfg.max_iterations = fz_u32(in, 0u, 50u);
        for (uint32_t j = 0; j < SBR_SERVO_MAX_JOINTS; ++j) {
            cfg.width[j] = fz_float(in, 0.0f, 2.0f);
            cfg.max_step[j] = fz_float(in, 0.0f, 1.0f);
            cfg.joint_min[j] = fz_float(in, -4.0f, 0.0f);
            cfg.joint_max[j] = fz_float(in, 0.0f, 4.0f);
        }
        for (uint32_t i = 0; i < SBR_SERVO_MAX_FEATURES; ++i) {
            cfg.tolerance[i] = fz_float(in, 0.0f, 2.0f);
        }
    }
    return cfg;
}

void vec(FuzzedDataProvider &in, float *v, uint32_t n, float lo, float hi)
{
    for (uint32_t k = 0; k < n; ++k) {
        v[k] = in.ConsumeIntegral<uint8_t>() < 250u ? in.ConsumeFloatingPointInRange<float>(lo, hi)
                                                     : fz_float(in, lo, hi);
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FuzzedDataProvider in(data, size);
    const sbr_servo_config_t cfg = config_from(in);
    const sbr_status_t cs = sbr_servo_config_check(&cfg);
    FZ_STATUS(cs, SBR_OK, SBR_ERR_SIZE, SBR_ERR_RANGE);
    const size_t need = sbr_servo_workspace_size(&cfg);
    if (cs != SBR_OK) {
        FZ_CHECK(need == 0u);
        return 0;
    }
    FZ_CHECK(need == SBR_SERVO_WORKSPACE_SIZE(cfg.max_fields, cfg.joints, cfg.features));
    std::vector<uint32_t> ws(need / 4u + 1u);
    sbr_servo_t s;
    const size_t given = in.ConsumeBool() ? need : in.ConsumeIntegralInRange<size_t>(0, need);
    const sbr_status_t is = sbr_servo_init(&s, &cfg, ws.data(), given);
    FZ_STATUS(is, SBR_OK, SBR_ERR_WORKSPACE);
    if (is != SBR_OK) {
        FZ_CHECK(given < need);
        return 0;
    }
    const uint32_t m = cfg.joints, n = cfg.features;
    sbr_servo_run_t run;
    FZ_STATUS(sbr_servo_run_start(&run), SBR_OK);
    float y[SBR_SERVO_MAX_JOINTS], dy[SBR_SERVO_MAX_JOINTS], x[SBR_SERVO_MAX_FEATURES];
    float xw[SBR_SERVO_MAX_FEATURES], dx[SBR_SERVO_MAX_FEATURES], yn[SBR_SERVO_MAX_JOINTS];
    float jac[SBR_SERVO_MAX_JOINTS * SBR_SERVO_MAX_FEATURES];
    while (in.remaining_bytes() > 0) {
        const uint8_t op = in.ConsumeIntegral<uint8_t>();
        vec(in, y, m, -3.0f, 3.0f);
        if (op < 140u) {
            vec(in, dy, m, -0.3f, 0.3f);
            vec(in, dx, n, -50.0f, 50.0f);
            FZ_STATUS(sbr_servo_learn(&s, y, dy, dx), SBR_OK, SBR_ERR_RANGE, SBR_ERR_CAPACITY);
        } else if (op < 180u) {
            float act = -1.0f;
            const sbr_status_t js = sbr_servo_jacobian(&s, y, jac, &act);
            FZ_STATUS(js, SBR_OK, SBR_ERR_RANGE, SBR_ERR_DEGENERATE);
            if (js == SBR_OK) {
                FZ_CHECK(act >= 0.0f && fz_finite(act));
                for (uint32_t e = 0; e < m * n; ++e) FZ_CHECK(fz_finite(jac[e]));
            }
        } else if (op < 250u) {
            vec(in, x, n, -500.0f, 500.0f);
            vec(in, xw, n, -500.0f, 500.0f);
            sbr_servo_result_t res;
            const uint32_t before = run.iterations;
            sbr_status_t ss;
            if (op < 215u) {
                ss = sbr_servo_step(&s, &run, y, x, xw, yn, &res);
                FZ_STATUS(ss, SBR_OK, SBR_ERR_RANGE, SBR_ERR_DEGENERATE);
            } else {
                // a Jacobian from elsewhere (an oracle, Broyden's update): any values,
                // rank-deficient ones included; the same step rule and invariants
                vec(in, jac, m * n, -20.0f, 20.0f);
                ss = sbr_servo_step_with(&cfg, &run, jac, y, x, xw, yn, &res);
                FZ_STATUS(ss, SBR_OK, SBR_ERR_RANGE);
            }
            FZ_CHECK(run.iterations <= cfg.max_iterations);
            if (ss == SBR_OK) {
                for (uint32_t j = 0; j < m; ++j) {
                    FZ_CHECK(fz_finite(yn[j]) && yn[j] >= cfg.joint_min[j] && yn[j] <= cfg.joint_max[j]);
                    FZ_CHECK(std::fabs(yn[j] - y[j]) <= cfg.max_step[j] * 1.0001f + 1e-6f);
                    if (res != SBR_SERVO_STEP) FZ_CHECK(yn[j] == y[j]);
                }
                FZ_CHECK(res == SBR_SERVO_STEP ? run.iterations == before + 1u : run.iterations == before);
            }
        } else {
            sbr_servo_t broken = s;
            broken.count = cfg.max_fields + 1u; // a corrupted instance is refused
            FZ_STATUS(sbr_servo_learn(&broken, y, y, y), SBR_ERR_STATE);
            FZ_STATUS(sbr_servo_stats(&broken, nullptr, nullptr), SBR_ERR_STATE);
        }
    }
    uint32_t fields = 0, samples = 0;
    FZ_STATUS(sbr_servo_stats(&s, &fields, &samples), SBR_OK);
    FZ_CHECK(fields <= cfg.max_fields);
    return 0;
}
