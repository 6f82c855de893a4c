/* SPDX-License-Identifier: MIT */
/*
 * The class stage's looks (picto.h, sbr_picto_looks_t) as one table: each threshold's
 * name, range, default and meaning, written here once. The trainer's values
 * (sbr_picto_looks_default()), the model check (sbr_picto_check()), the host tools'
 * options, the Python keywords and docs/usage/configuration.md come from it. Why these
 * defaults: docs/results/realtime.md (refinement, views, triangle view).
 */
#include "sbr/picto.h"

#include "picto_internal.h"

#include <stddef.h>
#include <string.h>

#define LOOK_OFF(name) ((uint32_t)offsetof(sbr_picto_model_t, looks.name))

/* The table, once: X(name, default, meaning); every look is a probability in [0, 1].
   Expanded twice: the numbers and the texts (no pointers: no relocated data). */
#define PICTO_LOOKS(X) \
    X(refine_first_score, 0.01f, "sign probability at which the first box refinement starts (colour frames)") \
    X(grey_refine_first_score, 0.0003f, "refine_first_score on a grey frame") \
    X(refine_score, 0.001f, "sign probability to go on refining") \
    X(view_score, 0.1f, "sign probability for the extra views of the final box") \
    X(triangle_score, 0.001f, "danger probability for the triangle view")

typedef struct look_row_s {
    uint32_t offset;
    float def;
} look_row_t;

typedef struct look_text_s {
    char name[SBR_FIELD_NAME_LEN];
    char help[SBR_FIELD_HELP_LEN];
} look_text_t;

#define LOOK_ROW(name, def, help) {LOOK_OFF(name), (def)},
#define LOOK_TEXT(name, def, help) {#name, help},

static const look_row_t looks[] = {PICTO_LOOKS(LOOK_ROW)};

#define LOOK_COUNT ((uint32_t)((sizeof looks) / (sizeof looks[0])))

uint32_t sbr_picto_look_field_count(void)
{
    return LOOK_COUNT;
}

sbr_status_t sbr_picto_look_field_at(uint32_t index, sbr_field_t *out)
{
    static const look_text_t look_texts[] = {PICTO_LOOKS(LOOK_TEXT)};
    sbr_status_t st = SBR_ERR_NULL;
    if (out != NULL) {
        st = SBR_ERR_RANGE;
        if (index < LOOK_COUNT) {
            (void)memset(out, 0, sizeof *out);
            out->name = look_texts[index].name;
            out->help = look_texts[index].help;
            out->offset = looks[index].offset;
            out->kind = (uint8_t)SBR_FIELD_F32;
            out->count = 1u;
            out->lo_f = 0.0f;
            out->hi_f = 1.0f;
            out->def_f = looks[index].def;
            st = SBR_OK;
        }
    }
    return st;
}

/* The look's value in a model. */
static float look_value(const sbr_picto_model_t *model, uint32_t offset)
{
    float v;
    (void)memcpy((uint8_t *)&v, &((const uint8_t *)model)[offset], sizeof v);
    return v;
}

void sbr_picto_looks_default(sbr_picto_looks_t *out)
{
    if (out != NULL) {
        sbr_picto_model_t m;
        uint32_t i;
        (void)memset(&m, 0, sizeof m);
        for (i = 0u; i < LOOK_COUNT; i++) {
            (void)memcpy(&((uint8_t *)&m)[looks[i].offset], (const uint8_t *)&looks[i].def, sizeof looks[i].def);
        }
        *out = m.looks;
    }
}

int sbr_picto_priv_looks_ok(const sbr_picto_model_t *model)
{
    int ok = 1;
    uint32_t i;
    for (i = 0u; i < LOOK_COUNT; i++) {
        const float v = look_value(model, looks[i].offset);
        if (!((v >= 0.0f) && (v <= 1.0f))) {
            ok = 0;
        }
    }
    return ok;
}
