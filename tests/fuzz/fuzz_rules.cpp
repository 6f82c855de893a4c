// SPDX-License-Identifier: MIT
// Fuzz harness: the restrictions in force (rules.h) with hostile tables (unknown kinds,
// values where none belong, counts beyond the bound), times that jump or go back, classes
// outside the table and a corrupted instance, against a reference model written here from
// the header's rules. On SBR_OK the state is the reference's: each restriction set by its
// sign, ended by its end sign, expired hold_ms after it was last set; the limit one of the
// table's speeds; its age at most hold_ms. A refused call changes nothing.
#include "fuzz_common.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

extern "C" {
#include "sbr/rules.h"
}

namespace {

struct Reference {
    uint32_t limit = 0, ban = 0, trucks = 0, priority = 0;
    uint64_t since[4] = {0, 0, 0, 0};
};

void step(Reference &r, uint64_t now, uint32_t hold_ms, const sbr_rules_meaning_t *m, const std::vector<uint16_t> &c)
{
    const uint64_t hold = uint64_t(hold_ms) * 1000u;
    uint32_t *v[4] = {&r.limit, &r.ban, &r.trucks, &r.priority};
    for (int s = 0; s < 4; ++s)
        if (*v[s] != 0 && now - r.since[s] > hold) *v[s] = 0;
    for (uint16_t k : c) {
        const sbr_rules_meaning_t &x = m[k];
        switch (x.kind) {
        case SBR_RULES_SPEED: r.limit = x.value; r.since[0] = now; break;
        case SBR_RULES_END_SPEED: if (x.value == 0 || r.limit == x.value) r.limit = 0; break;
        case SBR_RULES_END_ALL: r.limit = r.ban = r.trucks = 0; break;
        case SBR_RULES_NO_OVERTAKING: r.ban = 1; r.since[1] = now; break;
        case SBR_RULES_END_NO_OVERTAKING: r.ban = 0; break;
        case SBR_RULES_NO_OVERTAKING_TRUCKS: r.trucks = 1; r.since[2] = now; break;
        case SBR_RULES_END_NO_OVERTAKING_TRUCKS: r.trucks = 0; break;
        case SBR_RULES_PRIORITY: r.priority = 1; r.since[3] = now; break;
        case SBR_RULES_END_PRIORITY: r.priority = 0; break;
        default: break;
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FuzzedDataProvider in(data, size);
    sbr_rules_config_t cfg;
    sbr_rules_config_default(&cfg);
    std::vector<sbr_rules_meaning_t> own;
    if (in.ConsumeBool()) {
        own.resize(in.ConsumeIntegralInRange<uint32_t>(0u, SBR_RULES_MAX_CLASSES + 2u));
        for (auto &m : own) {
            m.kind = in.ConsumeIntegralInRange<uint8_t>(0u, SBR_RULES_KINDS + 1u);
            m.value = in.ConsumeBool() ? 0u : in.ConsumeIntegral<uint8_t>();
        }
        cfg.meanings = own.empty() ? nullptr : own.data();
        cfg.class_count = uint32_t(own.size());
    }
    cfg.hold_ms = in.ConsumeBool() ? cfg.hold_ms : fz_u32(in, 0u, SBR_RULES_MAX_HOLD_MS + 1u);
    sbr_rules_t r;
    const sbr_status_t is = sbr_rules_init(&r, &cfg);
    FZ_STATUS(is, SBR_OK, SBR_ERR_NULL, SBR_ERR_RANGE);
    FZ_CHECK(is == sbr_rules_config_check(&cfg));
    sbr_rules_state_t out;
    if (is != SBR_OK) {
        FZ_CHECK(sbr_rules_update(&r, 0u, nullptr, 0u, &out) == SBR_ERR_STATE);
        return 0;
    }
    Reference ref;
    uint64_t now = 0;
    bool started = false;
    const uint32_t frames = in.ConsumeIntegralInRange<uint32_t>(1u, 64u);
    for (uint32_t f = 0; f < frames && in.remaining_bytes() > 0; ++f) {
        const uint8_t how = in.ConsumeIntegral<uint8_t>();
        uint64_t t = now + (how < 160u ? in.ConsumeIntegralInRange<uint64_t>(0u, 4000000u)
                                       : in.ConsumeIntegralInRange<uint64_t>(0u, uint64_t(1) << 40));
        if (how >= 160u && how < 200u) {  // the expiry's edge: exactly the hold after a set, or 1 us more
            const uint64_t hold = uint64_t(cfg.hold_ms) * 1000u + (how & 1u);
            t = std::max(now, ref.since[how % 4u] + hold);
        }
        if (how >= 250u && now > 0) t = now - 1u;  // back in time
        std::vector<uint16_t> classes(in.ConsumeIntegralInRange<uint32_t>(0u, 4u));
        for (auto &c : classes) c = uint16_t(fz_u32(in, 0u, cfg.class_count + (in.ConsumeBool() ? 1u : 0u)));
        if (in.ConsumeIntegral<uint8_t>() == 255u) {  // a corrupted instance
            sbr_rules_t bad = r;
            bad.state.priority_road ^= 1u;
            FZ_CHECK(sbr_rules_update(&bad, t, classes.data(), uint32_t(classes.size()), &out) == SBR_ERR_STATE);
        }
        const sbr_rules_t before = r;
        const sbr_status_t st = sbr_rules_update(&r, t, classes.empty() ? nullptr : classes.data(),
                                                 uint32_t(classes.size()), &out);
        FZ_STATUS(st, SBR_OK, SBR_ERR_RANGE);
        bool valid = !(started && t < now);
        for (uint16_t c : classes) valid = valid && c < cfg.class_count;
        FZ_CHECK((st == SBR_OK) == valid);
        if (st != SBR_OK) {
            FZ_CHECK(std::memcmp(&before, &r, sizeof r) == 0);
            continue;
        }
        step(ref, t, cfg.hold_ms, cfg.meanings, classes);
        now = t;
        started = true;
        FZ_CHECK(out.speed_limit_kmh == ref.limit && out.no_overtaking == ref.ban && out.no_overtaking_trucks == ref.trucks &&
                 out.priority_road == ref.priority);
        FZ_CHECK(out.speed_age_ms <= cfg.hold_ms && (out.speed_limit_kmh != 0 || out.speed_age_ms == 0));
        bool known = out.speed_limit_kmh == 0;
        for (uint32_t c = 0; c < cfg.class_count; ++c)
            known = known || (cfg.meanings[c].kind == SBR_RULES_SPEED && cfg.meanings[c].value == out.speed_limit_kmh);
        FZ_CHECK(known);
    }
    return 0;
}
