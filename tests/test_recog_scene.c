/* SPDX-License-Identifier: MIT */
/* The whole recogniser with the built-in library and class stage on one small synthetic
   street scene (drawn with integer arithmetic, so every target renders the same pixels):
   a prohibitory-like sign, a blue "ahead only" disc, a danger-like triangle on a noisy
   gradient. The test checks that it runs within the stated workspace, that its
   detections are well-formed, that each drawn sign is found at the operating point with a
   class of its superclass and a box of IoU >= 0.5, and prints the detections one per line:

     SBRDET class x y width height score_ppm share_ppm parts

   cmake/compare_scene.py runs this program on the host and on the emulated Cortex-M4 and
   requires the same detections (the tolerance is documented there). */
#include "unity.h"
#include "sbr/recog.h"
#include "sbr/models.h"
#include "recog_run.h"

#include <math.h>
#include <string.h>

#define W 160u
#define H 96u
#define CAP 64u

static uint8_t g_rgb[H][W][3];
static uint8_t g_grey[H][W];
static uint64_t g_ws[700000u / 8u];
static sbr_detection_t g_dets[CAP];

void setUp(void) {}
void tearDown(void) {}

static void put(uint32_t x, uint32_t y, uint8_t r, uint8_t g, uint8_t b)
{
    g_rgb[y][x][0] = r;
    g_rgb[y][x][1] = g;
    g_rgb[y][x][2] = b;
}

static int32_t sq(int32_t v)
{
    return v * v;
}

static void draw_scene(void)
{
    uint32_t state = 2024u;
    uint32_t x;
    uint32_t y;
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            const int32_t px = (int32_t)x;
            const int32_t py = (int32_t)y;
            const int32_t d1 = sq(px - 40) + sq(py - 46);           /* prohibitory, r 18 */
            const int32_t d2 = sq(px - 92) + sq(py - 38);           /* mandatory, r 14 */
            const int32_t ty = py - 34;                              /* triangle, apex up */
            const int32_t tx = (px > 132) ? (px - 132) : (132 - px);
            uint32_t base;
            state = (state * 1664525u) + 1013904223u;
            base = 90u + ((y * 60u) / H) + ((state >> 28) & 7u);
            put(x, y, (uint8_t)base, (uint8_t)(base + 10u), (uint8_t)(base - 5u));
            if (d1 <= sq(18)) {
                if ((px >= 31) && (px <= 49) && (py >= 43) && (py <= 49)) {
                    put(x, y, 25u, 25u, 25u); /* a dark bar */
                } else if (d1 <= sq(12)) {
                    put(x, y, 235u, 235u, 230u);
                } else {
                    put(x, y, 200u, 25u, 35u);
                }
            } else if (d2 <= sq(14)) {
                if (((px >= 90) && (px <= 94) && (py >= 33) && (py <= 49)) ||
                    ((py >= 26) && (py <= 33) && (((px > 92) ? (px - 92) : (92 - px)) <= (py - 26)))) {
                    put(x, y, 240u, 240u, 240u); /* an arrow pointing up: "ahead only" */
                } else {
                    put(x, y, 20u, 60u, 170u);
                }
            } else if ((ty >= 0) && (ty <= 30) && ((2 * tx) <= ty)) {
                if ((ty >= 6) && (ty <= 26) && ((2 * tx) <= (ty - 7))) {
                    put(x, y, 240u, 240u, 235u);
                } else {
                    put(x, y, 205u, 30u, 30u);
                }
            } else {
                /* background */
            }
        }
    }
}

/* The drawn signs: their boxes (every pixel the drawing gives them) and GTSDB superclass. */
typedef struct {
    uint32_t x, y, w, h;
    uint32_t superclass; /* 0 prohibitory, 1 mandatory, 2 danger */
} drawn_sign_t;

static const drawn_sign_t k_signs[3] = {
    {22u, 28u, 37u, 37u, 0u},  /* disc of radius 18 at (40, 46) */
    {78u, 24u, 29u, 29u, 1u},  /* disc of radius 14 at (92, 38) */
    {117u, 34u, 31u, 31u, 2u}, /* triangle, apex (132, 34), 31 rows */
};

static uint32_t superclass_of(uint32_t c)
{
    uint32_t s = 3u; /* other */
    if ((c <= 5u) || ((c >= 7u) && (c <= 10u)) || (c == 15u) || (c == 16u)) {
        s = 0u;
    } else if ((c >= 33u) && (c <= 40u)) {
        s = 1u;
    } else if ((c == 11u) || ((c >= 18u) && (c <= 31u))) {
        s = 2u;
    }
    return s;
}

static float iou(const sbr_rect_t *a, const drawn_sign_t *b)
{
    const uint32_t x0 = (a->x > b->x) ? a->x : b->x;
    const uint32_t y0 = (a->y > b->y) ? a->y : b->y;
    const uint32_t ax1 = a->x + a->width;
    const uint32_t ay1 = a->y + a->height;
    const uint32_t x1 = (ax1 < (b->x + b->w)) ? ax1 : (b->x + b->w);
    const uint32_t y1 = (ay1 < (b->y + b->h)) ? ay1 : (b->y + b->h);
    float inter = 0.0f;
    if ((x1 > x0) && (y1 > y0)) {
        inter = (float)(x1 - x0) * (float)(y1 - y0);
    }
    return inter / (((float)a->width * (float)a->height) + ((float)b->w * (float)b->h) - inter);
}

/* Does box match one of the drawn signs (IoU >= 0.5)? */
static int matches_drawn_sign(const sbr_rect_t *box)
{
    int match = 0;
    uint32_t k;
    for (k = 0u; k < 3u; k++) {
        if (iou(box, &k_signs[k]) >= 0.5f) {
            match = 1;
        }
    }
    return match;
}

static void print_detection(const sbr_detection_t *d)
{
    UnityPrint("SBRDET ");
    UnityPrintNumberUnsigned(d->class_id);
    UnityPrint(" ");
    UnityPrintNumberUnsigned(d->box.x);
    UnityPrint(" ");
    UnityPrintNumberUnsigned(d->box.y);
    UnityPrint(" ");
    UnityPrintNumberUnsigned(d->box.width);
    UnityPrint(" ");
    UnityPrintNumberUnsigned(d->box.height);
    UnityPrint(" ");
    UnityPrintNumberUnsigned((UNITY_UINT)((d->score * 1.0e6f) + 0.5f));
    UnityPrint(" ");
    UnityPrintNumberUnsigned((UNITY_UINT)((d->class_share * 1.0e6f) + 0.5f));
    UnityPrint(" ");
    UnityPrintNumberUnsigned(d->parts);
    UNITY_PRINT_EOL();
}

/* The scene's view and a configuration whose workspace fits g_ws; every classified
   candidate reported (min_score 0). */
static void scene_setup(sbr_image_t *v, sbr_recog_config_t *c)
{
    draw_scene();
    v->width = W;
    v->height = H;
    v->stride = 3u * W;
    v->format = SBR_PIXEL_RGB888;
    v->data = &g_rgb[0][0][0];
    sbr_recog_config_default(c);
    c->parts.max_side = 48u;
    c->parts.max_regions = 256u;
    c->parts.max_contour = 512u;
    c->parts.mser.max_nodes = 4000u;
    c->max_parts = 128u;
    c->max_votes = 2048u;
    c->max_hypotheses = 64u;
    c->min_score = 0.0f;
    TEST_ASSERT_TRUE(sbr_recog_workspace_size(c, W, H) <= sizeof g_ws);
}

/* The drawn signs are drawings, not photographs of signs: the class stage, which learns
   from real signs (GTSDB's and GTSRB's 25,000 crops), scores the drawn prohibitory disc
   0.47 (the mandatory disc and the triangle 0.99 and 0.95), below its operating point
   (0.7). The test asks for what a drawing can show: each sign found with its superclass
   and box, above every detection on clutter (the best of those scores 0.005). */
#define SCENE_SCORE 0.25f

/* Every classified candidate is reported (min_score 0), so the comparison covers the
   part model, the class stage and the box refinement, not only the final few. */
static void test_scene(void)
{
    sbr_model_t m;
    sbr_picto_model_t p;
    sbr_recog_config_t c;
    sbr_recog_stats_t st;
    sbr_image_t v;
    uint32_t n = 0u;
    uint32_t i;
    scene_setup(&v, &c);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_gtsdb(&m));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gtsdb(&p));
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, g_dets, CAP, &n, &st));
    TEST_ASSERT_TRUE(n >= 1u); /* something to compare */
    TEST_ASSERT_TRUE(st.classified >= n);
    for (i = 0u; i < n; i++) {
        TEST_ASSERT_TRUE(g_dets[i].class_id < m.class_count);
        TEST_ASSERT_TRUE((g_dets[i].score >= 0.0f) && (g_dets[i].score <= 1.0f));
        TEST_ASSERT_TRUE((i == 0u) || (g_dets[i].score <= g_dets[i - 1u].score));
        TEST_ASSERT_TRUE(g_dets[i].box.x + g_dets[i].box.width <= W);
        TEST_ASSERT_TRUE(g_dets[i].box.y + g_dets[i].box.height <= H);
        print_detection(&g_dets[i]);
    }
    /* each drawn sign: a detection of its superclass with IoU >= 0.5, scored at least
       SCENE_SCORE and above every detection that matches no drawn sign */
    {
        uint32_t k;
        float clutter = 0.0f;
        for (i = 0u; i < n; i++) {
            if ((matches_drawn_sign(&g_dets[i].box) == 0) && (g_dets[i].score > clutter)) {
                clutter = g_dets[i].score;
            }
        }
        for (k = 0u; k < 3u; k++) {
            float sign = 0.0f;
            for (i = 0u; i < n; i++) {
                if ((superclass_of(g_dets[i].class_id) == k_signs[k].superclass) &&
                    (iou(&g_dets[i].box, &k_signs[k]) >= 0.5f) && (g_dets[i].score > sign)) {
                    sign = g_dets[i].score;
                }
            }
            TEST_ASSERT_TRUE_MESSAGE(sign >= SCENE_SCORE, "a drawn sign was not found with its superclass and box");
            TEST_ASSERT_TRUE_MESSAGE(sign > clutter, "clutter scored above a drawn sign");
        }
    }
}

/* The class stage's colour check (sbr_picto_model_t::rim_floor) on the same scene: the
   built-in class stage has one for the yield sign; without tables nothing is dropped;
   with every class's outline checked and the lowest floor (-2) nothing changes; with the
   highest (2) no candidate of a checked class is left (the classes without an outline,
   the diamond and the octagon, stay) and each one dropped is counted. */
static void test_scene_colour_check(void)
{
    static sbr_detection_t plain[CAP];
    static uint8_t shape[SBR_PICTO_MAX_CLASSES];
    static float floor_[SBR_PICTO_MAX_CLASSES];
    sbr_model_t m;
    sbr_picto_model_t p;
    sbr_recog_config_t c;
    sbr_recog_stats_t st;
    sbr_image_t v;
    uint32_t n0 = 0u;
    uint32_t n = 0u;
    uint32_t i;
    uint32_t k;
    scene_setup(&v, &c);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_gtsdb(&m));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gtsdb(&p));
    /* the built-in class stage checks the yield sign's rim */
    TEST_ASSERT_NOT_NULL(p.rim_shape);
    TEST_ASSERT_EQUAL_UINT8(SBR_PICTO_RIM_TRIANGLE_DOWN, p.rim_shape[13]);
    p.rim_shape = NULL;
    p.rim_floor = NULL;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, plain, CAP, &n0, &st));
    TEST_ASSERT_EQUAL_UINT32(0u, st.rim_rejected);
    for (k = 0u; k < p.classes; k++) {
        shape[k] = (uint8_t)(((k == 12u) || (k == 14u)) ? SBR_PICTO_RIM_NONE
                             : ((superclass_of(k) == 2u) ? SBR_PICTO_RIM_TRIANGLE
                                                                    : SBR_PICTO_RIM_DISC));
        floor_[k] = -2.0f;
    }
    shape[13] = (uint8_t)SBR_PICTO_RIM_TRIANGLE_DOWN;
    p.rim_shape = shape;
    p.rim_floor = floor_;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, g_dets, CAP, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(n0, n);
    TEST_ASSERT_EQUAL_UINT32(0u, st.rim_rejected);
    TEST_ASSERT_EQUAL_MEMORY(plain, g_dets, n * sizeof g_dets[0]);
    for (k = 0u; k < p.classes; k++) {
        floor_[k] = 2.0f;
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, g_dets, CAP, &n, &st));
    TEST_ASSERT_TRUE(st.rim_rejected >= 1u);
    for (i = 0u; i < n; i++) {
        TEST_ASSERT_EQUAL_UINT8(SBR_PICTO_RIM_NONE, shape[g_dets[i].class_id]);
    }
    floor_[0] = NAN; /* a corrupted table: the model check refuses the whole call */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, g_dets, CAP, &n, &st));
}

/* The scene as a GRAY8 frame (each pixel the mean of its channels), as a monochrome
   camera gives it: the whole recogniser with the built-in models runs on it, its
   detections are well-formed, the drawn prohibitory sign (a dark ring in grey) is still
   found with its superclass and box, with a score of at least GREY_SCORE and above that
   of every detection that matches no drawn sign (IoU < 0.5); the colour check, which
   would drop every candidate of a checked class in colour with the highest floor, is
   skipped. GREY_SCORE is below the operating point: the built-in class stage is trained
   on colour only, so grey frames lie outside what it was trained on (what grey costs on
   real frames: docs/results/recognition.md, grey frames); the class stage trained with
   GTSRB scores this drawn sign 0.19 in grey (0.47 in colour, test_scene; the best
   clutter 0.008). */
#define GREY_SCORE 0.15f
static void test_scene_grey(void)
{
    static uint8_t shape[SBR_PICTO_MAX_CLASSES];
    static float floor_[SBR_PICTO_MAX_CLASSES];
    sbr_model_t m;
    sbr_picto_model_t p;
    sbr_recog_config_t c;
    sbr_recog_stats_t st;
    sbr_image_t v;
    sbr_image_t g;
    uint32_t n = 0u;
    uint32_t i;
    uint32_t x;
    uint32_t y;
    float sign = 0.0f;    /* the best score of the prohibitory sign, with its superclass */
    float clutter = 0.0f; /* the best score of a detection that matches no drawn sign */
    scene_setup(&v, &c);
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            const uint32_t sum = (uint32_t)g_rgb[y][x][0] + g_rgb[y][x][1] + g_rgb[y][x][2];
            g_grey[y][x] = (uint8_t)((sum + 1u) / 3u);
        }
    }
    g = v;
    g.stride = W;
    g.format = SBR_PIXEL_GRAY8;
    g.data = &g_grey[0][0];
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_gtsdb(&m));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gtsdb(&p));
    for (i = 0u; i < p.classes; i++) {
        shape[i] = (uint8_t)(((i == 12u) || (i == 14u)) ? SBR_PICTO_RIM_NONE : SBR_PICTO_RIM_DISC);
        floor_[i] = 2.0f;
    }
    p.rim_shape = shape;
    p.rim_floor = floor_;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&g, NULL, &c, &m, &p, g_ws, sizeof g_ws, g_dets, CAP, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(0u, st.rim_rejected);
    TEST_ASSERT_TRUE(st.classified >= n);
    for (i = 0u; i < n; i++) {
        TEST_ASSERT_TRUE(g_dets[i].class_id < m.class_count);
        TEST_ASSERT_TRUE((g_dets[i].score >= 0.0f) && (g_dets[i].score <= 1.0f));
        TEST_ASSERT_TRUE(g_dets[i].box.x + g_dets[i].box.width <= W);
        if ((superclass_of(g_dets[i].class_id) == k_signs[0].superclass) &&
            (iou(&g_dets[i].box, &k_signs[0]) >= 0.5f) && (g_dets[i].score > sign)) {
            sign = g_dets[i].score;
        }
        if ((matches_drawn_sign(&g_dets[i].box) == 0) && (g_dets[i].score > clutter)) {
            clutter = g_dets[i].score;
        }
    }
    TEST_ASSERT_TRUE_MESSAGE(sign >= GREY_SCORE, "the prohibitory sign was not found in the grey frame");
    TEST_ASSERT_TRUE_MESSAGE(sign > clutter, "clutter scored above the prohibitory sign in the grey frame");
}

/* The class stage's gate: the built-in one keeps the drawn sign and gates candidates
   away; one that passes everything gives the detections without a gate (cfg.gate = 0),
   one that passes nothing leaves no detection and counts every candidate as gated,
   cfg.gate = 0 ignores it, and a corrupted gate is refused. */
static void test_scene_gate(void)
{
    static sbr_detection_t plain[CAP];
    static float gate[SBR_PICTO_GATE_WEIGHTS(2u)];
    sbr_model_t m;
    sbr_picto_model_t p;
    sbr_recog_config_t c;
    sbr_recog_stats_t st;
    sbr_recog_stats_t st0;
    sbr_image_t v;
    uint32_t n0 = 0u;
    uint32_t n = 0u;
    uint32_t i;
    scene_setup(&v, &c);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_gtsdb(&m));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gtsdb(&p));
    TEST_ASSERT_NOT_NULL(p.gate); /* the built-in class stage has one */
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, g_dets, CAP, &n, &st));
    TEST_ASSERT_TRUE(n >= 1u);
    TEST_ASSERT_TRUE(st.gated >= 1u);
    TEST_ASSERT_TRUE(st.gated < st.classified); /* the sign's candidates pass */
    c.gate = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, plain, CAP, &n0, &st0));
    c.gate = 1u;
    TEST_ASSERT_TRUE(n0 >= 1u);
    TEST_ASSERT_EQUAL_UINT32(0u, st0.gated);
    TEST_ASSERT_EQUAL_INT(g_dets[0].class_id, plain[0].class_id);
    for (i = 0u; i < SBR_PICTO_GATE_WEIGHTS(2u); i++) {
        gate[i] = 0.01f * (float)((int)(i % 5u) - 2);
    }
    p.gate = gate;
    p.gate_hidden = 2u;
    p.gate_threshold = -1.0e30f; /* every candidate passes */
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, g_dets, CAP, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(n0, n);
    TEST_ASSERT_EQUAL_UINT32(0u, st.gated);
    TEST_ASSERT_EQUAL_UINT32(st0.classified, st.classified);
    TEST_ASSERT_EQUAL_MEMORY(plain, g_dets, n * sizeof g_dets[0]);
    p.gate_threshold = 1.0e30f; /* none does */
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, g_dets, CAP, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    TEST_ASSERT_EQUAL_UINT32(st0.classified, st.gated);
    TEST_ASSERT_EQUAL_UINT32(0u, st.refined);
    c.gate = 0u; /* off: the detections without a gate */
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, g_dets, CAP, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(n0, n);
    TEST_ASSERT_EQUAL_MEMORY(plain, g_dets, n * sizeof g_dets[0]);
    c.gate = 2u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, g_dets, CAP, &n, &st));
    c.gate = 1u;
    p.gate_hidden = SBR_PICTO_GATE_HIDDEN_MAX + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, g_dets, CAP, &n, &st));
    p.gate_hidden = 2u;
    gate[3] = INFINITY;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, recog_run(&v, NULL, &c, &m, &p, g_ws, sizeof g_ws, g_dets, CAP, &n, &st));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_scene);
    RUN_TEST(test_scene_colour_check);
    RUN_TEST(test_scene_gate);
    RUN_TEST(test_scene_grey);
    return UNITY_END();
}
