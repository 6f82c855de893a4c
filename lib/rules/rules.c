/* SPDX-License-Identifier: MIT */
/*
 * The restrictions in force from confirmed signs (include/sbr/rules.h).
 */
#include "sbr/rules.h"

#include <stddef.h>
#include <string.h>

#include "../common/sbr_util.h"

/* "RULE": an initialised instance. */
#define RULES_MAGIC 0x52554C45u

/* The restrictions' slots in since_us. */
#define SLOT_SPEED 0u
#define SLOT_BAN 1u
#define SLOT_BAN_TRUCKS 2u
#define SLOT_PRIORITY 3u

#define M(kind, value) {(uint8_t)(kind), (value)}

sbr_status_t sbr_rules_gtsdb(const sbr_rules_meaning_t **out, uint32_t *count)
{
    /* GTSDB's 43 classes (the value names of dbc/sbr.dbc's SBR_Sign_Class). */
    static const sbr_rules_meaning_t gtsdb[43] = {
        M(SBR_RULES_SPEED, 20u),  M(SBR_RULES_SPEED, 30u), M(SBR_RULES_SPEED, 50u),    /* 0-2 */
        M(SBR_RULES_SPEED, 60u),  M(SBR_RULES_SPEED, 70u), M(SBR_RULES_SPEED, 80u),    /* 3-5 */
        M(SBR_RULES_END_SPEED, 80u),                                                  /* 6 */
        M(SBR_RULES_SPEED, 100u), M(SBR_RULES_SPEED, 120u),                           /* 7-8 */
        M(SBR_RULES_NO_OVERTAKING, 0u), M(SBR_RULES_NO_OVERTAKING_TRUCKS, 0u),         /* 9-10 */
        M(SBR_RULES_NONE, 0u),                                                        /* 11 */
        M(SBR_RULES_PRIORITY, 0u),                                                    /* 12 */
        M(SBR_RULES_END_PRIORITY, 0u), M(SBR_RULES_END_PRIORITY, 0u),                 /* 13-14 */
        M(SBR_RULES_NONE, 0u),    M(SBR_RULES_NONE, 0u),   M(SBR_RULES_NONE, 0u),     /* 15-17 */
        M(SBR_RULES_NONE, 0u),    M(SBR_RULES_NONE, 0u),   M(SBR_RULES_NONE, 0u),     /* 18-20 */
        M(SBR_RULES_NONE, 0u),    M(SBR_RULES_NONE, 0u),   M(SBR_RULES_NONE, 0u),     /* 21-23 */
        M(SBR_RULES_NONE, 0u),    M(SBR_RULES_NONE, 0u),   M(SBR_RULES_NONE, 0u),     /* 24-26 */
        M(SBR_RULES_NONE, 0u),    M(SBR_RULES_NONE, 0u),   M(SBR_RULES_NONE, 0u),     /* 27-29 */
        M(SBR_RULES_NONE, 0u),    M(SBR_RULES_NONE, 0u),                              /* 30-31 */
        M(SBR_RULES_END_ALL, 0u),                                                     /* 32 */
        M(SBR_RULES_NONE, 0u),    M(SBR_RULES_NONE, 0u),   M(SBR_RULES_NONE, 0u),     /* 33-35 */
        M(SBR_RULES_NONE, 0u),    M(SBR_RULES_NONE, 0u),   M(SBR_RULES_NONE, 0u),     /* 36-38 */
        M(SBR_RULES_NONE, 0u),    M(SBR_RULES_NONE, 0u),                              /* 39-40 */
        M(SBR_RULES_END_NO_OVERTAKING, 0u), M(SBR_RULES_END_NO_OVERTAKING_TRUCKS, 0u), /* 41-42 */
    };
    sbr_status_t st = SBR_ERR_NULL;
    if ((out != NULL) && (count != NULL)) {
        *out = gtsdb;
        *count = (uint32_t)((sizeof gtsdb) / (sizeof gtsdb[0]));
        st = SBR_OK;
    }
    return st;
}

void sbr_rules_config_default(sbr_rules_config_t *cfg)
{
    if (cfg != NULL) {
        cfg->hold_ms = SBR_RULES_DEFAULT_HOLD_MS;
        (void)sbr_rules_gtsdb(&cfg->meanings, &cfg->class_count);
    }
}

/* Whether one meaning is well formed. */
static int meaning_ok(const sbr_rules_meaning_t *m)
{
    int ok = 1;
    if (m->kind >= (uint8_t)SBR_RULES_KINDS) {
        ok = 0;
    } else if (m->kind == (uint8_t)SBR_RULES_SPEED) {
        if (m->value == 0u) {
            ok = 0;
        }
    } else if (m->kind != (uint8_t)SBR_RULES_END_SPEED) {
        if (m->value != 0u) {
            ok = 0;
        }
    } else {
        /* an end of speed: any value, 0 ends any limit */
    }
    return ok;
}

sbr_status_t sbr_rules_config_check(const sbr_rules_config_t *cfg)
{
    sbr_status_t st = SBR_ERR_NULL;
    if ((cfg != NULL) && (cfg->meanings != NULL)) {
        st = SBR_OK;
        if ((cfg->hold_ms == 0u) || (cfg->hold_ms > SBR_RULES_MAX_HOLD_MS) || (cfg->class_count == 0u) ||
            (cfg->class_count > SBR_RULES_MAX_CLASSES)) {
            st = SBR_ERR_RANGE;
        } else {
            uint32_t c;
            for (c = 0u; c < cfg->class_count; c++) {
                if (meaning_ok(&cfg->meanings[c]) == 0) {
                    st = SBR_ERR_RANGE;
                }
            }
        }
    }
    return st;
}

/* The integrity word over the bytes before it. */
static uint32_t rules_checksum(const sbr_rules_t *r)
{
    return sbr_util_fnv1a(r, offsetof(sbr_rules_t, check));
}

static void seal(sbr_rules_t *r)
{
    r->magic = RULES_MAGIC;
    r->check = rules_checksum(r);
}

static int sealed(const sbr_rules_t *r)
{
    return ((r->magic == RULES_MAGIC) && (r->check == rules_checksum(r))) ? 1 : 0;
}

sbr_status_t sbr_rules_init(sbr_rules_t *rules, const sbr_rules_config_t *cfg)
{
    sbr_status_t st = SBR_ERR_NULL;
    if (rules != NULL) {
        (void)memset(rules, 0, sizeof *rules);
        st = sbr_rules_config_check(cfg);
        if (st == SBR_OK) {
            rules->cfg = *cfg;
            seal(rules);
        }
    }
    return st;
}

sbr_status_t sbr_rules_reset(sbr_rules_t *rules)
{
    sbr_status_t st = SBR_ERR_NULL;
    if (rules != NULL) {
        st = SBR_ERR_STATE;
        if (sealed(rules) != 0) {
            const sbr_rules_config_t cfg = rules->cfg;
            (void)memset(rules, 0, sizeof *rules);
            rules->cfg = cfg;
            seal(rules);
            st = SBR_OK;
        }
    }
    return st;
}

/* Clears what has not been set or confirmed within hold of now. */
static void expire(sbr_rules_t *r, uint64_t now_us)
{
    const uint64_t hold_us = (uint64_t)r->cfg.hold_ms * 1000u;
    uint32_t *flags[4];
    uint32_t s;
    flags[SLOT_SPEED] = &r->state.speed_limit_kmh;
    flags[SLOT_BAN] = &r->state.no_overtaking;
    flags[SLOT_BAN_TRUCKS] = &r->state.no_overtaking_trucks;
    flags[SLOT_PRIORITY] = &r->state.priority_road;
    for (s = 0u; s < 4u; s++) {
        if ((*flags[s] != 0u) && ((now_us - r->since_us[s]) > hold_us)) {
            *flags[s] = 0u;
        }
    }
}

/* One confirmed sign's meaning applied at now. */
static void apply(sbr_rules_t *r, const sbr_rules_meaning_t *m, uint64_t now_us)
{
    sbr_rules_state_t *s = &r->state;
    switch ((sbr_rules_kind_t)m->kind) {
    case SBR_RULES_SPEED:
        s->speed_limit_kmh = m->value;
        r->since_us[SLOT_SPEED] = now_us;
        break;
    case SBR_RULES_END_SPEED:
        if ((m->value == 0u) || (s->speed_limit_kmh == m->value)) {
            s->speed_limit_kmh = 0u;
        }
        break;
    case SBR_RULES_END_ALL:
        s->speed_limit_kmh = 0u;
        s->no_overtaking = 0u;
        s->no_overtaking_trucks = 0u;
        break;
    case SBR_RULES_NO_OVERTAKING:
        s->no_overtaking = 1u;
        r->since_us[SLOT_BAN] = now_us;
        break;
    case SBR_RULES_END_NO_OVERTAKING:
        s->no_overtaking = 0u;
        break;
    case SBR_RULES_NO_OVERTAKING_TRUCKS:
        s->no_overtaking_trucks = 1u;
        r->since_us[SLOT_BAN_TRUCKS] = now_us;
        break;
    case SBR_RULES_END_NO_OVERTAKING_TRUCKS:
        s->no_overtaking_trucks = 0u;
        break;
    case SBR_RULES_PRIORITY:
        s->priority_road = 1u;
        r->since_us[SLOT_PRIORITY] = now_us;
        break;
    case SBR_RULES_END_PRIORITY:
        s->priority_road = 0u;
        break;
    default:
        /* SBR_RULES_NONE (the table was checked at init) */
        break;
    }
}

sbr_status_t sbr_rules_update(sbr_rules_t *rules, uint64_t now_us, const uint16_t *classes,
                              uint32_t count, sbr_rules_state_t *out)
{
    sbr_status_t st = SBR_ERR_NULL;
    if ((rules != NULL) && (out != NULL) && ((classes != NULL) || (count == 0u))) {
        st = SBR_ERR_STATE;
        if (sealed(rules) != 0) {
            uint32_t i;
            st = SBR_OK;
            if ((rules->started != 0u) && (now_us < rules->now_us)) {
                st = SBR_ERR_RANGE;
            }
            for (i = 0u; (i < count) && (st == SBR_OK); i++) {
                if ((uint32_t)classes[i] >= rules->cfg.class_count) {
                    st = SBR_ERR_RANGE;
                }
            }
            if (st == SBR_OK) {
                expire(rules, now_us);
                for (i = 0u; i < count; i++) {
                    apply(rules, &rules->cfg.meanings[classes[i]], now_us);
                }
                rules->state.speed_age_ms = 0u;
                if (rules->state.speed_limit_kmh != 0u) {
                    /* at most hold_ms, so it fits */
                    rules->state.speed_age_ms = (uint32_t)((now_us - rules->since_us[SLOT_SPEED]) / 1000u);
                }
                rules->now_us = now_us;
                rules->started = 1u;
                seal(rules);
                *out = rules->state;
            }
        }
    }
    return st;
}
