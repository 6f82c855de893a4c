/* SPDX-License-Identifier: MIT */
/* Unity tests of the recogniser (include/sbr/recog.h): a model learned in the test
   from one synthetic sign finds the sign again elsewhere, larger, in another frame; the
   built-in model is consistent; bad input gets its status. */
#include "unity.h"
#include "sbr/recog.h"
#include "sbr/models.h"
#include "sbr/recog_strips.h"
#include "test_status_table.h"
#include "recog_run.h"

#include <math.h>
#include <string.h>

#define W 160u
#define H 96u
#define MAXP 32u

static uint8_t g_rgb[H][W][3];
static uint8_t g_grey[H][W]; /* a grey copy of the picture (test_class_stage) */
static uint8_t g_grey[H][W];
static uint64_t g_ws[700000u / 8u];
static sbr_part_t g_parts[128];
static sbr_fd_t g_fds[MAXP];
static sbr_model_proto_t g_protos[MAXP];
static uint16_t g_cascade[MAXP];
static sbr_model_t g_model;
static sbr_picto_model_t g_picto; /* version 0 (no class stage) unless a test sets it */
static sbr_recog_config_t g_cfg;
static sbr_detection_t g_dets[16];

static void clear(void)
{
    uint32_t x;
    uint32_t y;
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            g_rgb[y][x][0] = 110u;
            g_rgb[y][x][1] = 120u;
            g_rgb[y][x][2] = 110u;
        }
    }
}

static sbr_image_t view(void)
{
    sbr_image_t v;
    v.width = W;
    v.height = H;
    v.stride = 3u * W;
    v.format = SBR_PIXEL_RGB888;
    v.data = &g_rgb[0][0][0];
    return v;
}

/* A prohibitory-like sign of radius r at (cx, cy): red ring, white disc, dark bar. */
static void draw_sign(float cx, float cy, float r)
{
    uint32_t x;
    uint32_t y;
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            const float dx = (float)x - cx;
            const float dy = (float)y - cy;
            const float d = sqrtf((dx * dx) + (dy * dy));
            uint8_t *p = g_rgb[y][x];
            if ((fabsf(dx) <= 0.2f * r) && (fabsf(dy) <= 0.4f * r)) {
                p[0] = 20u; p[1] = 20u; p[2] = 20u;
            } else if (d <= 0.64f * r) {
                p[0] = 240u; p[1] = 240u; p[2] = 240u;
            } else if (d <= r) {
                p[0] = 210u; p[1] = 20u; p[2] = 30u;
            } else {
                /* background */
            }
        }
    }
}

/* The centre x of a detection's box. */
static float box_cx(const sbr_detection_t *d)
{
    return (float)d->box.x + (0.5f * (float)d->box.width);
}

static void test_config(void)
{
    sbr_recog_config_default(&g_cfg);
    g_cfg.parts.maps = 0x7u; /* intensity, red and blue: the red map's path too */
    g_cfg.parts.map_subsample[SBR_MAP_BLUE] = 1u; /* every map at full resolution: the
                                                     models here are learned from this
                                                     small frame's parts */
    g_cfg.parts.map_polarity[SBR_MAP_INTENSITY] = 0u; /* and both polarities of each, as
                                                        sbr_train learns a part model */
    g_cfg.parts.max_side = 48u;
    g_cfg.parts.max_regions = 256u;
    g_cfg.parts.max_contour = 512u;
    g_cfg.parts.mser.max_nodes = 4000u;
    g_cfg.max_parts = 128u;
    g_cfg.max_votes = 2048u;
    g_cfg.max_hypotheses = 128u;
    g_cfg.max_model_protos = MAXP;
    g_cfg.min_parts = 2u; /* the models here have no class stage */
    g_cfg.outline_maps = 0u; /* the part model's candidates only (the outline candidates:
                                test_outline_candidates()) */
}

/* Learn the model from the parts of one sign of radius r at (cx, cy): every part centred
   on the sign becomes a prototype of class 14 whose offset and size are measured from
   the drawing (the sign is 2r wide). */
static void learn(float cx, float cy, float r)
{
    const sbr_image_t v = view();
    sbr_fft_t fft;
    uint32_t n = 0u;
    uint32_t i;
    uint32_t np = 0u;
    uint32_t g;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init(&fft, g_cfg.parts.fd_n));
    TEST_ASSERT_TRUE(sbr_parts_workspace_size(&g_cfg.parts, W, H) <= sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&v, &g_cfg.parts, &fft, g_ws, sizeof g_ws, g_parts,
                                                    128u, &n, NULL));
    (void)memset(&g_model, 0, sizeof g_model);
    /* group by group, so the prototypes come out sorted by group */
    for (g = 0u; g < SBR_MODEL_GROUPS; g++) {
        g_model.group_first[g] = (uint16_t)np;
        for (i = 0u; (i < n) && (np < MAXP); i++) {
            const sbr_part_t *p = &g_parts[i];
            const uint32_t pg = ((uint32_t)p->map * 2u) + ((uint32_t)p->polarity - 1u);
            sbr_model_proto_t *q = &g_protos[np];
            if ((pg != g) || (fabsf(p->fd.cx - cx) > 0.3f * r) || (fabsf(p->fd.cy - cy) > 0.3f * r) ||
                (p->bbox.width > (uint32_t)(2.0f * r) + 3u)) {
                continue;
            }
            g_fds[np] = p->fd;
            (void)memset(q, 0, sizeof *q);
            q->dx = (cx - p->fd.cx) / p->fd.scale;
            q->dy = (cy - p->fd.cy) / p->fd.scale;
            q->w = (2.0f * r) / p->fd.scale;
            q->h = q->w;
            q->weight = 0.6f;
            q->support = 1u;
            q->map = p->map;
            q->polarity = p->polarity;
            (void)memset(q->class_id, (int)SBR_MODEL_NO_CLASS, sizeof q->class_id);
            q->class_id[0] = 14u;
            q->class_p[0] = 1.0f;
            g_cascade[np] = (uint16_t)np;
            np++;
        }
    }
    g_model.group_first[SBR_MODEL_GROUPS] = (uint16_t)np;
    /* GTSDB's 43 classes; the danger signs (11, 18..31) are upward triangles */
    g_model.class_count = 43u;
    for (i = 0u; i <= SBR_RECOG_MAX_CLASSES; i++) {
        g_model.class_first[i] = (uint16_t)((i <= 14u) ? 0u : np);
    }
    for (i = 0u; i < SBR_RECOG_MAX_CLASSES; i++) {
        g_model.class_outline[i] = (uint8_t)(((i == 11u) || ((i >= 18u) && (i <= 31u))) ? SBR_PICTO_RIM_TRIANGLE
                                                                                        : SBR_PICTO_RIM_DISC);
    }
    g_model.version = SBR_MODEL_VERSION;
    g_model.fd_n = g_cfg.parts.fd_n;
    g_model.fd_m = g_cfg.parts.fd_m;
    g_model.proto_count = np;
    g_model.fds = g_fds;
    g_model.protos = g_protos;
    g_model.cascade = g_cascade;
    g_model.vote_error = 0.1f;
    g_model.score_threshold = 0.5f;
    /* ring outside, ring inside (the disc), disc, bar: several parts over three maps */
    TEST_ASSERT_TRUE(np >= 3u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_check(&g_model));
}

void setUp(void)
{
    (void)memset(&g_picto, 0, sizeof g_picto);
    clear();
    test_config();
    draw_sign(40.0f, 48.0f, 14.0f);
    learn(40.0f, 48.0f, 14.0f);
    clear();
}
void tearDown(void) {}

/* Another frame: the sign 30 % larger elsewhere, and a plain red disc (one part only). */
static void test_finds_sign_elsewhere_and_larger(void)
{
    const sbr_image_t v = view();
    sbr_recog_stats_t st;
    uint32_t n = 0u;
    float cx;
    float cy;
    draw_sign(112.0f, 50.0f, 18.0f);
    TEST_ASSERT_TRUE(sbr_recog_workspace_size(&g_cfg, W, H) <= sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                   16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_UINT32(14u, g_dets[0].class_id);
    cx = box_cx(&g_dets[0]);
    cy = (float)g_dets[0].box.y + (0.5f * (float)g_dets[0].box.height);
    TEST_ASSERT_FLOAT_WITHIN(2.0f, 112.5f, cx);
    TEST_ASSERT_FLOAT_WITHIN(2.0f, 50.5f, cy);
    TEST_ASSERT_FLOAT_WITHIN(4.0f, 36.0f, (float)g_dets[0].box.width);
    TEST_ASSERT_FLOAT_WITHIN(4.0f, 36.0f, (float)g_dets[0].box.height);
    TEST_ASSERT_TRUE(g_dets[0].parts >= 3u);
    /* noisy-OR of >= 3 parts of weight <= 0.6: above 1 - 0.4^3 x (loss to match error) */
    TEST_ASSERT_TRUE(g_dets[0].score > 0.6f);
    TEST_ASSERT_TRUE(g_dets[0].score < 1.0f);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, g_dets[0].class_share);
    TEST_ASSERT_TRUE(st.parts >= 3u);
    TEST_ASSERT_TRUE(st.votes >= 3u);
    TEST_ASSERT_EQUAL_UINT32(0u, st.capacity_hit);
    TEST_ASSERT_EQUAL_UINT32(0u, st.stage_ticks[0]); /* no clock configured */
}

/* The cascade: with a vote error too tight for most parts, the sign's other parts are
   found where the model predicts them (with the looser verification error) and add their
   weight; a second sign elsewhere in the frame lends none of its parts to the first. */
static void test_cascade_finds_the_parts_that_did_not_vote(void)
{
    const sbr_image_t v = view();
    sbr_recog_stats_t st;
    sbr_recog_config_t c = g_cfg;
    const uint32_t np = g_model.proto_count;
    uint32_t off = 0u; /* prototypes made to miss the vote */
    float voted[2];
    float small_sign;
    uint32_t n = 0u;
    uint32_t k;
    /* every other prototype's shape a little off: its match error (a few hundredths) is
       above the vote error below and well under the verification error */
    for (k = 1u; k < np; k += 2u) {
        sbr_fd_t *fd = &g_fds[k];
        float e = 0.0f;
        float s;
        uint32_t j;
        fd->c[fd->m + 3u].re += 0.2f;
        for (j = 0u; j <= (2u * fd->m); j++) {
            e += (fd->c[j].re * fd->c[j].re) + (fd->c[j].im * fd->c[j].im);
        }
        s = 1.0f / sqrtf(e);
        for (j = 0u; j <= (2u * fd->m); j++) {
            fd->c[j].re *= s;
            fd->c[j].im *= s;
        }
        off++;
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_check(&g_model));
    c.vote_error = 0.01f;
    c.verify_error = 0.25f;
    c.min_parts = 1u;
    /* the learned sign (left) and a larger copy 72 px to its right */
    draw_sign(112.0f, 50.0f, 18.0f);
    draw_sign(40.0f, 48.0f, 14.0f);
    c.cascade_depth = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                   16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    TEST_ASSERT_EQUAL_UINT32(0u, st.verified);
    for (k = 0u; k < 2u; k++) {
        const uint32_t right = (g_dets[k].box.x > 60u) ? 1u : 0u;
        TEST_ASSERT_EQUAL_UINT32(np - off, g_dets[k].parts); /* the votes alone */
        voted[right] = g_dets[k].score;
    }
    c.cascade_depth = 8u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                   16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    TEST_ASSERT_EQUAL_UINT32(2u * off, st.verified); /* each sign's missing parts, found */
    small_sign = 0.0f;
    for (k = 0u; k < 2u; k++) {
        const uint32_t right = (g_dets[k].box.x > 60u) ? 1u : 0u;
        TEST_ASSERT_EQUAL_UINT32(np, g_dets[k].parts);
        TEST_ASSERT_TRUE(g_dets[k].score > voted[right]);
        if (right == 0u) {
            small_sign = g_dets[k].score;
        }
    }
    /* the left sign alone: exactly the same score, the right sign's parts lent nothing */
    clear();
    draw_sign(40.0f, 48.0f, 14.0f);
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                   16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_UINT32(off, st.verified);
    TEST_ASSERT_EQUAL_FLOAT(small_sign, g_dets[0].score);
    TEST_ASSERT_TRUE(off >= 1u);
}

/* A frame without the sign: nothing. With min_parts above what one sign offers: nothing. */
static void test_empty_frame_and_min_parts(void)
{
    const sbr_image_t v = view();
    uint32_t n = 99u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                   16u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    draw_sign(112.0f, 50.0f, 18.0f);
    g_cfg.min_parts = 20u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                   16u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
}

/* A ROI: the box comes back in frame pixels, equal to the whole-frame result. */
static void test_roi_offsets_boxes(void)
{
    const sbr_image_t v = view();
    sbr_rect_t roi;
    sbr_detection_t full;
    uint32_t n = 0u;
    draw_sign(112.0f, 50.0f, 18.0f);
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                   16u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    full = g_dets[0];
    roi.x = 70u;
    roi.y = 20u;
    roi.width = 84u;
    roi.height = 64u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, &roi, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                   16u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_UINT32_WITHIN(1u, full.box.x, g_dets[0].box.x);
    TEST_ASSERT_UINT32_WITHIN(1u, full.box.y, g_dets[0].box.y);
    TEST_ASSERT_UINT32_WITHIN(1u, full.box.width, g_dets[0].box.width);
    roi.x = 100u; /* 100 + 84 > 160 */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&v, &roi, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                          g_dets, 16u, &n, NULL));
    roi.x = 70u;
    roi.width = 0u; /* empty */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&v, &roi, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                          g_dets, 16u, &n, NULL));
}

/* The frame as GRAY8: each pixel the mean of its channels. */
static sbr_image_t grey_frame(void)
{
    sbr_image_t v = view();
    uint32_t x;
    uint32_t y;
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            const uint32_t sum = (uint32_t)g_rgb[y][x][0] + g_rgb[y][x][1] + g_rgb[y][x][2];
            g_grey[y][x] = (uint8_t)((sum + 1u) / 3u);
        }
    }
    v.stride = W;
    v.format = SBR_PIXEL_GRAY8;
    v.data = &g_grey[0][0];
    return v;
}

static int same_detection(const sbr_detection_t *a, const sbr_detection_t *b)
{
    return (a->box.x == b->box.x) && (a->box.y == b->box.y) && (a->box.width == b->box.width) &&
           (a->box.height == b->box.height) && (a->class_id == b->class_id) && (a->score == b->score) &&
           (a->parts == b->parts);
}

/* A GRAY8 frame: the sign is found from its intensity parts alone (the colour maps of the
   configuration are skipped), at the colour frame's place; a grey frame gives what the
   same frame with R = G = B gives; a grey frame with colour maps only is refused, and
   stats reads all zero after an error. */
static void test_grey_frame(void)
{
    sbr_image_t g;
    sbr_image_t rgb = view();
    sbr_recog_stats_t st;
    sbr_detection_t first;
    uint32_t n = 0u;
    uint32_t x;
    uint32_t y;
    float cx;
    draw_sign(112.0f, 50.0f, 18.0f);
    g = grey_frame();
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&g, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                   16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_UINT32(14u, g_dets[0].class_id);
    cx = box_cx(&g_dets[0]);
    TEST_ASSERT_FLOAT_WITHIN(2.0f, 112.5f, cx);
    TEST_ASSERT_FLOAT_WITHIN(4.0f, 36.0f, (float)g_dets[0].box.width);
    TEST_ASSERT_TRUE(g_dets[0].parts >= 2u);
    first = g_dets[0];
    {
        /* its parts: those of the intensity map alone, both polarities (grey_polarity 0:
           the ring, red on a colour frame, is a dark region in grey) */
        sbr_parts_config_t pc = g_cfg.parts;
        sbr_fft_t fft;
        uint32_t np = 0u;
        pc.maps = 1u << (uint32_t)SBR_MAP_INTENSITY;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init(&fft, pc.fd_n));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&g, &pc, &fft, g_ws, sizeof g_ws, g_parts, 128u,
                                                        &np, NULL));
        TEST_ASSERT_TRUE(np >= 2u);
        TEST_ASSERT_EQUAL_UINT32(np, st.parts);
    }
    /* the default: a colour frame's intensity map bright only, a grey frame's both; with
       grey_polarity bright only the ring's dark region is not flooded, fewer parts */
    {
        sbr_recog_config_t c;
        sbr_recog_config_default(&c);
        TEST_ASSERT_EQUAL_UINT32(0u, c.grey_polarity);
        TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_MSER_BRIGHT, c.parts.map_polarity[SBR_MAP_INTENSITY]);
        c = g_cfg;
        sbr_recog_stats_t sb;
        uint32_t nb = 0u;
        c.grey_polarity = (uint32_t)SBR_MSER_BRIGHT;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&g, NULL, &c, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                16u, &nb, &sb));
        TEST_ASSERT_TRUE(sb.parts < st.parts);
        c.grey_polarity = 4u;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_config_check(&c));
    }
    /* the same grey values in an RGB frame with the grey frame's polarities (here both,
       the configuration's): the colour maps see nothing, the same result */
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            g_rgb[y][x][0] = g_grey[y][x];
            g_rgb[y][x][1] = g_grey[y][x];
            g_rgb[y][x][2] = g_grey[y][x];
        }
    }
    {
        sbr_recog_config_t c = g_cfg;
        c.parts.map_polarity[SBR_MAP_INTENSITY] = g_cfg.grey_polarity;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&rgb, NULL, &c, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                16u, &n, NULL));
    }
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_TRUE(same_detection(&first, &g_dets[0]));
    /* refused without an intensity map; stats zeroed */
    {
        sbr_recog_config_t c = g_cfg;
        c.parts.maps = (1u << (uint32_t)SBR_MAP_RED) | (1u << (uint32_t)SBR_MAP_BLUE);
        (void)memset(&st, 0x5a, sizeof st);
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&g, NULL, &c, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                              g_dets, 16u, &n, &st));
        TEST_ASSERT_EQUAL_UINT32(0u, n);
        TEST_ASSERT_EQUAL_UINT32(0u, st.parts);
        TEST_ASSERT_EQUAL_UINT32(0u, st.capacity_hit);
        TEST_ASSERT_EQUAL_UINT32(0u, st.stage_ticks[0]);
        (void)memset(&st, 0x5a, sizeof st);
        TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, recog_run(&g, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                             NULL, 16u, &n, &st));
        TEST_ASSERT_EQUAL_UINT32(0u, st.votes);
    }
}

/* Two signs, room for one: the distinct capacity status, and one detection written. */
/* The strip configuration (sbr_recog_detect_strips()) on the 160 x 96 frame in bands of 64
   rows overlapping by 40 (tops 0, 24, 32; cores [0, 44), [44, 68), [68, 96)). A sign of 36
   px centred at row 50 lies wholly in the second and third bands and partly in the
   first: it is reported once, by the band whose core holds its centre, as the whole
   frame reports it. */
static void test_strips(void)
{
    const sbr_image_t v = view();
    sbr_recog_t rec;
    sbr_recog_stats_t st;
    sbr_recog_stats_t whole_st;
    sbr_detection_t whole[4];
    uint32_t n = 0u;
    uint32_t m = 0u;
    const size_t need = sbr_recog_strip_workspace_size(&g_cfg, W, H, 64u);
    draw_sign(112.0f, 50.0f, 18.0f);
    /* one band's workspace and room for its detections */
    TEST_ASSERT_EQUAL_UINT32((uint32_t)(sbr_recog_workspace_size(&g_cfg, W, 64u) +
                                        SBR_WS_ALIGN8(SBR_RECOG_STRIP_BAND_DETECTIONS * sizeof(sbr_detection_t))),
                             (uint32_t)need);
    TEST_ASSERT_TRUE(need < sbr_recog_workspace_size(&g_cfg, W, H));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_init(&rec, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_detect(&rec, &v, NULL, whole, 4u, &m, &whole_st));
    TEST_ASSERT_EQUAL_UINT32(1u, m);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_init(&rec, &g_cfg, &g_model, &g_picto, g_ws, need));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_detect_strips(&rec, &v, 64u, 40u, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_UINT32(whole[0].class_id, g_dets[0].class_id);
    TEST_ASSERT_UINT32_WITHIN(1u, whole[0].box.x, g_dets[0].box.x);
    TEST_ASSERT_UINT32_WITHIN(1u, whole[0].box.y, g_dets[0].box.y);
    TEST_ASSERT_UINT32_WITHIN(1u, whole[0].box.width, g_dets[0].box.width);
    TEST_ASSERT_UINT32_WITHIN(1u, whole[0].box.height, g_dets[0].box.height);
    /* three bands' counters: the sign's parts come from the two bands that hold all of it
       (and from the first, which holds part of it) */
    TEST_ASSERT_TRUE(st.parts >= (2u * whole_st.parts));
    TEST_ASSERT_EQUAL_UINT32(0u, st.capacity_hit);
    /* a band no lower than the frame: one band, the whole frame's result, bit for bit */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_init(&rec, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_detect_strips(&rec, &v, H, 0u, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_TRUE(same_detection(&whole[0], &g_dets[0]));
    TEST_ASSERT_EQUAL_MEMORY(&whole_st, &st, sizeof st);
    /* a band too large for the workspace the recogniser was given; a workspace that holds
       the band but not its detections */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_init(&rec, &g_cfg, &g_model, &g_picto, g_ws, need));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_recog_detect_strips(&rec, &v, 72u, 40u, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    TEST_ASSERT_EQUAL_UINT32(0u, st.parts);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_init(&rec, &g_cfg, &g_model, &g_picto, g_ws, need - 8u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_recog_detect_strips(&rec, &v, 64u, 40u, g_dets, 16u, &n, &st));
}

/* Two signs in different bands' cores: both reported, highest score first; a capacity
   of one keeps the better and says so; bad arguments get their statuses. */
static void test_strips_capacity_and_input(void)
{
    sbr_image_t v = view();
    sbr_recog_t rec;
    sbr_recog_stats_t st;
    sbr_recog_stats_t all;
    sbr_detection_t both[1];
    uint32_t n = 9u;
    draw_sign(40.0f, 22.0f, 14.0f);
    draw_sign(112.0f, 74.0f, 16.0f);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_init(&rec, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_detect_strips(&rec, &v, 64u, 40u, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    all = st;
    TEST_ASSERT_TRUE(g_dets[0].score >= g_dets[1].score);
    TEST_ASSERT_TRUE(((g_dets[0].box.y < 44u) && (g_dets[1].box.y > 44u)) ||
                     ((g_dets[1].box.y < 44u) && (g_dets[0].box.y > 44u)));
    both[0] = g_dets[0];
    /* a capacity of one: the better of the two whichever band comes first, every band
       run (the counters of all three) */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_recog_detect_strips(&rec, &v, 64u, 40u, g_dets, 1u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_TRUE(same_detection(&both[0], &g_dets[0]));
    TEST_ASSERT_EQUAL_MEMORY(&all, &st, sizeof st); /* counters written with the capacity status */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_recog_detect_strips(NULL, &v, 64u, 40u, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_recog_detect_strips(&rec, NULL, 64u, 40u, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_recog_detect_strips(&rec, &v, 64u, 40u, NULL, 16u, &n, &st));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_recog_detect_strips(&rec, &v, 64u, 40u, g_dets, 16u, NULL, &st));
    n = 9u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_detect_strips(&rec, &v, 0u, 0u, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    TEST_ASSERT_EQUAL_UINT32(0u, st.parts);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_detect_strips(&rec, &v, 64u, 64u, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_recog_detect_strips(&rec, &v, 64u, 40u, g_dets, 0u, &n, &st));
    v.stride = 1u; /* shorter than a row */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, sbr_recog_detect_strips(&rec, &v, 64u, 40u, g_dets, 16u, &n, &st));
    rec.check ^= 1u; /* a recogniser changed since its init */
    v = view();
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_recog_detect_strips(&rec, &v, 64u, 40u, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_recog_strip_workspace_size(&g_cfg, W, H, 0u));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_recog_strip_workspace_size(NULL, W, H, 64u));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)(sbr_recog_workspace_size(&g_cfg, W, H) +
                                        SBR_WS_ALIGN8(SBR_RECOG_STRIP_BAND_DETECTIONS * sizeof(sbr_detection_t))),
                             (uint32_t)sbr_recog_strip_workspace_size(&g_cfg, W, H, 1000u));
}

static void test_capacity(void)
{
    const sbr_image_t v = view();
    uint32_t n = 0u;
    draw_sign(40.0f, 48.0f, 14.0f);
    draw_sign(112.0f, 50.0f, 16.0f);
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                   16u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    TEST_ASSERT_TRUE(g_dets[0].score >= g_dets[1].score);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                             g_dets, 1u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
}

static void test_bad_input(void)
{
    sbr_image_t v = view();
    sbr_recog_config_t c = g_cfg;
    uint32_t n = 5u;
    sbr_model_proto_t saved;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, recog_run(NULL, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                         g_dets, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, recog_run(&v, NULL, NULL, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                         g_dets, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, recog_run(&v, NULL, &g_cfg, NULL, &g_picto, g_ws, sizeof g_ws,
                                                         g_dets, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                         NULL, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, NULL, sizeof g_ws,
                                                              g_dets, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, 1000u,
                                                              g_dets, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto,
                                                              (uint8_t *)g_ws + 4, sizeof g_ws - 8u,
                                                              g_dets, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                         g_dets, 0u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    /* configuration out of range */
    c.nms_iou = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_config_check(&c));
    c = g_cfg;
    c.verify_error = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&v, NULL, &c, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                          16u, &n, NULL));
    c = g_cfg;
    c.max_size = 5.0f; /* below min_size */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_config_check(&c));
    c = g_cfg;
    c.match_p = 16u; /* < 2M + 1 = 25 */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_config_check(&c));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_recog_workspace_size(&c, W, H));
    c = g_cfg;
    c.parts.fd_m = 10u; /* the model has 12 */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&v, NULL, &c, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                          16u, &n, NULL));
    c = g_cfg;
    c.max_model_protos = 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&v, NULL, &c, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                          16u, &n, NULL));
    /* a grey image with colour maps only */
    v.format = SBR_PIXEL_GRAY8;
    v.stride = W;
    c.parts.maps = 1u << (uint32_t)SBR_MAP_BLUE;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&v, NULL, &c, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                          g_dets, 16u, &n, NULL));
    c = g_cfg;
    v = view();
    v.stride = 3u * W - 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                          g_dets, 16u, &n, NULL));
    /* corrupted models */
    saved = g_protos[0];
    g_protos[0].weight = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_model_check(&g_model));
    v = view();
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                            g_dets, 16u, &n, NULL));
    g_protos[0] = saved;
    g_protos[0].class_id[1] = 43u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_model_check(&g_model));
    g_protos[0] = saved;
    g_protos[0].map = (uint8_t)(g_protos[0].map ^ 1u); /* no longer in its group */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_model_check(&g_model));
    g_protos[0] = saved;
    g_cascade[0] = 200u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_model_check(&g_model));
    g_cascade[0] = 0u;
    g_fds[1].c[0].re += 0.5f; /* not unit energy any more */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_model_check(&g_model));
    g_fds[1].c[0].re -= 0.5f;
    g_model.group_first[SBR_MODEL_GROUPS] = (uint16_t)(g_model.proto_count + 1u);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_model_check(&g_model));
    g_model.group_first[SBR_MODEL_GROUPS] = (uint16_t)g_model.proto_count;
    g_model.version = 99u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_model_check(&g_model));
    g_model.version = SBR_MODEL_VERSION;
    /* the class tables are the model's: a count in 1..SBR_RECOG_MAX_CLASSES, class ids
       and outlines within it */
    g_model.class_count = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_model_check(&g_model));
    g_model.class_count = SBR_RECOG_MAX_CLASSES + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_model_check(&g_model));
    g_model.class_count = 14u; /* the prototypes say class 14 */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_model_check(&g_model));
    g_model.class_count = 15u; /* a dataset of 15 classes: valid */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_check(&g_model));
    g_model.class_count = SBR_RECOG_MAX_CLASSES;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_check(&g_model));
    g_model.class_count = 43u;
    g_model.class_outline[42] = (uint8_t)(SBR_PICTO_RIM_TRIANGLE_DOWN + 1u);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_model_check(&g_model));
    g_model.class_outline[42] = (uint8_t)SBR_PICTO_RIM_DISC;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_check(&g_model));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_model_check(NULL));
}

/* The recogniser object: set up once, then frame after frame; it keeps copies of the
   configuration and the models' structs (a caller's later change does not reach it), a
   changed or never initialised instance is refused, and the workspace it was given bounds
   the frames it takes. */
static void test_recog_object(void)
{
    static sbr_recog_t zeroed;
    sbr_recog_t rec;
    sbr_recog_config_t c = g_cfg;
    sbr_image_t v = view();
    const size_t need = sbr_recog_workspace_size(&g_cfg, W, H);
    const sbr_rect_t half = {0u, 0u, W / 2u, H};
    sbr_detection_t first[4];
    uint32_t n = 0u;
    uint32_t n1 = 0u;
    draw_sign(40.0f, 48.0f, 14.0f);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_recog_detect(&zeroed, &v, NULL, g_dets, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_init(&rec, &c, &g_model, NULL, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_detect(&rec, &v, NULL, first, 4u, &n1, NULL));
    TEST_ASSERT_EQUAL_UINT32(1u, n1);
    c.min_size = 1000.0f; /* the caller's copy: the recogniser keeps its own */
    c.max_size = 2000.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_detect(&rec, &v, NULL, g_dets, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(n1, n);
    TEST_ASSERT_EQUAL_UINT32(first[0].box.x, g_dets[0].box.x);
    TEST_ASSERT_EQUAL_FLOAT(first[0].score, g_dets[0].score);
    rec.cfg.min_score = 0.9f; /* its own changed after init: refused */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_recog_detect(&rec, &v, NULL, g_dets, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    /* a refused init leaves an instance that detect refuses */
    c.nms_iou = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_init(&rec, &c, &g_model, NULL, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_recog_detect(&rec, &v, NULL, g_dets, 16u, &n, NULL));
    /* a workspace for exactly the frame: the frame and a smaller ROI run, a larger frame
       does not */
    TEST_ASSERT_TRUE(need > 0u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_init(&rec, &g_cfg, &g_model, NULL, g_ws, need));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_detect(&rec, &v, NULL, g_dets, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(n1, n);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_detect(&rec, &v, &half, g_dets, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_init(&rec, &g_cfg, &g_model, NULL, g_ws, need - 8u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_recog_detect(&rec, &v, NULL, g_dets, 16u, &n, NULL));
    v.height = H / 2u; /* a smaller frame fits */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_detect(&rec, &v, NULL, g_dets, 16u, &n, NULL));
}

/* recog.h: every documented status, in one table. */
static void test_recog_h_statuses(void)
{
    status_table_t t;
    const sbr_image_t v = view();
    sbr_image_t grey = view();
    sbr_image_t odd = view();
    sbr_image_t tiny = view();
    sbr_recog_config_t bad = g_cfg;
    sbr_recog_config_t other_m = g_cfg;
    sbr_recog_config_t blue_only = g_cfg;
    sbr_recog_config_t few_protos = g_cfg;
    sbr_model_t corrupt = g_model;
    sbr_model_t builtin;
    sbr_picto_model_t bad_picto;
    sbr_picto_model_t other_classes;
    sbr_recog_t rec;
    const sbr_rect_t outside = {100u, 20u, 84u, 64u};
    uint32_t n = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gtsdb(&g_picto));
    bad_picto = g_picto;
    bad_picto.threshold = NAN;
    other_classes = g_picto;
    other_classes.classes = 42u; /* the library has 43 */
    few_protos.max_model_protos = 1u;
    draw_sign(40.0f, 48.0f, 14.0f);
    draw_sign(112.0f, 50.0f, 16.0f);
    grey.format = SBR_PIXEL_GRAY8;
    grey.stride = W;
    odd.stride = 3u * W - 1u;
    tiny.width = 1u;
    tiny.height = 1u;
    bad.nms_iou = 0.0f;
    other_m.parts.fd_m = 10u;
    blue_only.parts.maps = 1u << (uint32_t)SBR_MAP_BLUE;
    corrupt.version = 99u;
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_model_check(&g_model));
    ROW(&t, SBR_ERR_NULL, sbr_model_check(NULL));
    ROW(&t, SBR_ERR_CORRUPT, sbr_model_check(&corrupt));
    ROW(&t, SBR_OK, sbr_model_gtsdb(&builtin));
    ROW(&t, SBR_ERR_NULL, sbr_model_gtsdb(NULL));
    ROW(&t, SBR_OK, sbr_recog_config_check(&g_cfg));
    ROW(&t, SBR_ERR_NULL, sbr_recog_config_check(NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_recog_config_check(&bad));
    ROW(&t, SBR_OK, sbr_recog_init(&rec, &g_cfg, &g_model, NULL, g_ws, sizeof g_ws));
    ROW(&t, SBR_OK, sbr_recog_init(&rec, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_NULL, sbr_recog_init(NULL, &g_cfg, &g_model, NULL, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_NULL, sbr_recog_init(&rec, NULL, &g_model, NULL, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_NULL, sbr_recog_init(&rec, &g_cfg, NULL, NULL, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_RANGE, sbr_recog_init(&rec, &bad, &g_model, NULL, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_RANGE, sbr_recog_init(&rec, &other_m, &g_model, NULL, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_RANGE, sbr_recog_init(&rec, &few_protos, &g_model, NULL, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_CORRUPT, sbr_recog_init(&rec, &g_cfg, &corrupt, NULL, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_CORRUPT, sbr_recog_init(&rec, &g_cfg, &g_model, &bad_picto, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_CORRUPT, sbr_recog_init(&rec, &g_cfg, &g_model, &other_classes, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_recog_init(&rec, &g_cfg, &g_model, NULL, NULL, sizeof g_ws));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_recog_init(&rec, &g_cfg, &g_model, NULL, g_ws, 0u));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_recog_init(&rec, &g_cfg, &g_model, NULL, (uint8_t *)g_ws + 4, 1000u));
    ROW(&t, SBR_ERR_STATE, sbr_recog_detect(&rec, &v, NULL, g_dets, 16u, &n, NULL)); /* refused above */
    ROW(&t, SBR_OK, sbr_recog_init(&rec, &g_cfg, &g_model, NULL, g_ws, sizeof g_ws));
    ROW(&t, SBR_OK, sbr_recog_detect(&rec, &v, NULL, g_dets, 16u, &n, NULL));
    ROW(&t, SBR_ERR_NULL, sbr_recog_detect(NULL, &v, NULL, g_dets, 16u, &n, NULL));
    ROW(&t, SBR_ERR_NULL, sbr_recog_detect(&rec, NULL, NULL, g_dets, 16u, &n, NULL));
    ROW(&t, SBR_ERR_NULL, sbr_recog_detect(&rec, &v, NULL, NULL, 16u, &n, NULL));
    ROW(&t, SBR_ERR_NULL, sbr_recog_detect(&rec, &v, NULL, g_dets, 16u, NULL, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_recog_detect(&rec, &v, &outside, g_dets, 16u, &n, NULL));
    ROW(&t, SBR_ERR_SIZE, sbr_recog_detect(&rec, &tiny, NULL, g_dets, 16u, &n, NULL));
    ROW(&t, SBR_ERR_SIZE, sbr_recog_detect(&rec, &v, NULL, g_dets, 0u, &n, NULL));
    ROW(&t, SBR_ERR_ALIGN, sbr_recog_detect(&rec, &odd, NULL, g_dets, 16u, &n, NULL));
    ROW(&t, SBR_ERR_RANGE, recog_run(&grey, NULL, &blue_only, &g_model, NULL, g_ws, sizeof g_ws, g_dets, 16u, &n, NULL));
    ROW(&t, SBR_ERR_WORKSPACE, recog_run(&v, NULL, &g_cfg, &g_model, NULL, g_ws, 1000u, g_dets, 16u, &n, NULL));
    ROW(&t, SBR_ERR_CAPACITY, sbr_recog_detect(&rec, &v, NULL, g_dets, 1u, &n, NULL));
    status_table_check(&t);
    TEST_ASSERT_EQUAL_UINT32(1u, n); /* the best one written */
    TEST_ASSERT_EQUAL_size_t(0u, sbr_recog_workspace_size(&bad, W, H));
}

/* A class stage relabels and rescores the part model's detection: a classifier that
   always says class 3 with probability e^4 / (e^4 + 43) gives that class and score; one
   that always says "no sign" leaves nothing; a corrupted one is refused. */
static void test_class_stage(void)
{
    static float w2[44u * (SBR_PICTO_FEATURES + 1u)]; /* 43 classes and the background */
    const sbr_image_t v = view();
    uint32_t n = 0u;
    (void)memset(w2, 0, sizeof w2);
    w2[(3u * (SBR_PICTO_FEATURES + 1u)) + SBR_PICTO_FEATURES] = 4.0f;
    g_picto.version = SBR_PICTO_VERSION;
    g_picto.features = SBR_PICTO_FEATURES;
    g_picto.hidden = 0u;
    g_picto.classes = 43u;
    g_picto.threshold = 0.5f;
    sbr_picto_looks_default(&g_picto.looks);
    g_picto.w1 = NULL;
    g_picto.w2 = w2;
    g_picto.w3 = NULL;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_check(&g_model));
    {
        char msg[80];
        (void)snprintf(msg, sizeof msg, "protos %u", (unsigned)g_model.proto_count);
        TEST_MESSAGE(msg);
    }
    draw_sign(112.0f, 50.0f, 18.0f);
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                   16u, &n, NULL));
    TEST_ASSERT_TRUE(n >= 1u);
    TEST_ASSERT_EQUAL_UINT32(3u, g_dets[0].class_id);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, expf(4.0f) / (expf(4.0f) + 43.0f), g_dets[0].score);
    /* share among the 43 sign classes: e^4 / (e^4 + 42) */
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, expf(4.0f) / (expf(4.0f) + 42.0f), g_dets[0].class_share);
    TEST_ASSERT_FLOAT_WITHIN(3.0f, 112.5f, box_cx(&g_dets[0]));
    /* a box regression that always says "the sign is 10 % of the width to the right":
       each refinement step moves the box by that much and classifies it again */
    {
        static float w3[SBR_PICTO_BOX_OUTPUTS * (SBR_PICTO_FEATURES + 1u)];
        sbr_recog_config_t rc = g_cfg;
        sbr_recog_stats_t st;
        float cx0;
        float w0;
        uint32_t steps;
        (void)memset(w3, 0, sizeof w3);
        w3[SBR_PICTO_FEATURES] = 0.1f;
        g_picto.w3 = w3;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_check(&g_model));
        rc.refine_steps = 0u;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets, 16u,
                                                       &n, &st));
        TEST_ASSERT_TRUE(n >= 1u);
        TEST_ASSERT_EQUAL_UINT32(0u, st.refined);
        cx0 = box_cx(&g_dets[0]);
        w0 = (float)g_dets[0].box.width;
        TEST_ASSERT_FLOAT_WITHIN(3.0f, 112.5f, cx0);
        for (steps = 1u; steps <= 2u; steps++) {
            rc.refine_steps = steps;
            TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                           16u, &n, &st));
            TEST_ASSERT_TRUE(n >= 1u);
            TEST_ASSERT_TRUE(st.refined >= steps);
            TEST_ASSERT_EQUAL_UINT32(3u, g_dets[0].class_id);
            TEST_ASSERT_FLOAT_WITHIN(1.01f, cx0 + (0.1f * w0 * (float)steps), box_cx(&g_dets[0]));
            TEST_ASSERT_FLOAT_WITHIN(1.01f, w0, (float)g_dets[0].box.width);
        }
        /* the gates: the sign classes together are (e^4 + 42) / (e^4 + 43) = 0.9898
           probable at every box. The first move needs refine_first_score, each further
           one refine_score: a first gate above that probability moves nothing, whatever
           the second; a first gate below it and a second above it move the box once. */
        TEST_ASSERT_EQUAL_UINT32(2u, g_cfg.refine_steps);
        TEST_ASSERT_EQUAL_FLOAT(0.01f, g_picto.looks.refine_first_score);
        TEST_ASSERT_EQUAL_FLOAT(0.0003f, g_picto.looks.grey_refine_first_score);
        TEST_ASSERT_EQUAL_FLOAT(0.001f, g_picto.looks.refine_score);
        rc.refine_steps = 2u;
        g_picto.looks.refine_first_score = 0.995f;
        g_picto.looks.refine_score = 0.0f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets, 16u,
                                                       &n, &st));
        TEST_ASSERT_TRUE(n >= 1u);
        TEST_ASSERT_EQUAL_UINT32(0u, st.refined);
        TEST_ASSERT_FLOAT_WITHIN(1.01f, cx0, box_cx(&g_dets[0]));
        g_picto.looks.refine_first_score = 0.98f;
        g_picto.looks.refine_score = 0.995f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets, 16u,
                                                       &n, &st));
        TEST_ASSERT_TRUE(n >= 1u);
        TEST_ASSERT_TRUE(st.refined >= 1u);
        TEST_ASSERT_TRUE(st.refined <= st.classified);
        TEST_ASSERT_FLOAT_WITHIN(1.01f, cx0 + (0.1f * w0), box_cx(&g_dets[0]));
        /* both gates below it: two moves */
        g_picto.looks.refine_score = 0.98f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets, 16u,
                                                       &n, &st));
        TEST_ASSERT_TRUE(n >= 1u);
        TEST_ASSERT_FLOAT_WITHIN(1.01f, cx0 + (0.2f * w0), box_cx(&g_dets[0]));
        /* a grey frame (the same picture) takes grey_refine_first_score: above the signs'
           probability nothing moves there whatever refine_first_score says, below it the
           box moves */
        {
            sbr_image_t gv = v;
            uint32_t x;
            uint32_t y;
            for (y = 0u; y < H; y++) {
                for (x = 0u; x < W; x++) {
                    g_grey[y][x] = (uint8_t)(((uint32_t)g_rgb[y][x][0] + g_rgb[y][x][1] + g_rgb[y][x][2]) / 3u);
                }
            }
            gv.format = SBR_PIXEL_GRAY8;
            gv.stride = W;
            gv.data = &g_grey[0][0];
            g_picto.looks.refine_score = 0.0f;
            g_picto.looks.refine_first_score = 0.0f;
            g_picto.looks.grey_refine_first_score = 0.995f;
            TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&gv, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                           16u, &n, &st));
            TEST_ASSERT_TRUE(st.classified >= 1u);
            TEST_ASSERT_EQUAL_UINT32(0u, st.refined);
            g_picto.looks.refine_first_score = 0.995f;
            g_picto.looks.grey_refine_first_score = 0.0f;
            TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&gv, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                           16u, &n, &st));
            TEST_ASSERT_TRUE(st.refined >= 1u);
            g_picto.looks.grey_refine_first_score = NAN;
            TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&g_picto));
            g_picto.looks.grey_refine_first_score = 1.5f;
            TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, recog_run(&gv, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                                  g_dets, 16u, &n, &st));
            g_picto.looks.grey_refine_first_score = 0.0003f;
        }
        /* out of [0, 1] or NaN: refused */
        g_picto.looks.refine_first_score = NAN;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&g_picto));
        g_picto.looks.refine_first_score = -0.5f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&g_picto));
        g_picto.looks.refine_first_score = 1.5f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                              16u, &n, &st));
        g_picto.looks.refine_first_score = 0.0f;
        rc.refine_steps = SBR_RECOG_MAX_REFINE + 1u;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                              16u, &n, &st));
        g_picto.w3 = NULL;
        sbr_picto_looks_default(&g_picto.looks);
    }
    /* suppression before the class stage (candidate_iou): two signs whose boxes overlap
       by IoU 5 / 57 (the right one drawn over the left one's rim). At 1 (the default)
       both are candidates and, with nms_iou 1, both are reported; at 0.05 the second one
       is dropped before the class stage ever sees it; at 0.2 (above their IoU) both are
       classified again. 0, values above 1 and NaN are refused. */
    {
        sbr_recog_config_t rc = g_cfg;
        sbr_recog_stats_t st;
        float left = 0.0f;
        float right = 0.0f;
        uint32_t k;
        TEST_ASSERT_EQUAL_FLOAT(1.0f, rc.candidate_iou);
        clear();
        draw_sign(58.0f, 48.0f, 15.0f);
        draw_sign(84.0f, 48.0f, 15.0f);
        rc.nms_iou = 1.0f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                       16u, &n, &st));
        TEST_ASSERT_EQUAL_UINT32(2u, n);
        TEST_ASSERT_EQUAL_UINT32(2u, st.classified);
        for (k = 0u; k < n; k++) {
            const float cx = (float)g_dets[k].box.x + (0.5f * (float)g_dets[k].box.width);
            TEST_ASSERT_EQUAL_UINT32(3u, g_dets[k].class_id);
            if (cx < 71.0f) {
                left = cx;
            } else {
                right = cx;
            }
        }
        TEST_ASSERT_FLOAT_WITHIN(3.0f, 58.0f, left);
        TEST_ASSERT_FLOAT_WITHIN(3.0f, 84.0f, right);
        rc.candidate_iou = 0.05f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                       16u, &n, &st));
        TEST_ASSERT_EQUAL_UINT32(1u, n);
        TEST_ASSERT_EQUAL_UINT32(1u, st.classified);
        rc.candidate_iou = 0.2f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                       16u, &n, &st));
        TEST_ASSERT_EQUAL_UINT32(2u, n);
        TEST_ASSERT_EQUAL_UINT32(2u, st.classified);
        rc.candidate_iou = 0.0f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_config_check(&rc));
        rc.candidate_iou = 1.01f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_config_check(&rc));
        rc.candidate_iou = NAN;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                              g_dets, 16u, &n, &st));
        clear();
        draw_sign(112.0f, 50.0f, 18.0f); /* the scene of the tests below */
    }
    /* views: averaging the same probabilities keeps them; each likely candidate costs
       views - 1 extra pictograms; 0 and more than SBR_RECOG_MAX_VIEWS are refused */
    {
        sbr_recog_config_t rc = g_cfg;
        sbr_recog_stats_t st;
        uint32_t nv;
        for (nv = 1u; nv <= SBR_RECOG_MAX_VIEWS; nv += 2u) {
            rc.views = nv;
            TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                           16u, &n, &st));
            TEST_ASSERT_TRUE(n >= 1u);
            TEST_ASSERT_EQUAL_UINT32(3u, g_dets[0].class_id);
            TEST_ASSERT_FLOAT_WITHIN(1e-4f, expf(4.0f) / (expf(4.0f) + 43.0f), g_dets[0].score);
            TEST_ASSERT_EQUAL_UINT32((nv - 1u) * st.classified, st.views);
        }
        /* views only for likely signs: the sign classes here are (e^4 + 42) / (e^4 + 43)
           = 0.982 probable, so a view_score above that classifies every candidate once */
        rc.views = SBR_RECOG_MAX_VIEWS;
        g_picto.looks.view_score = 0.99f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                       16u, &n, &st));
        TEST_ASSERT_TRUE(n >= 1u);
        TEST_ASSERT_TRUE(st.classified >= 1u);
        TEST_ASSERT_EQUAL_UINT32(0u, st.views);
        g_picto.looks.view_score = 0.98f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                       16u, &n, &st));
        TEST_ASSERT_EQUAL_UINT32((SBR_RECOG_MAX_VIEWS - 1u) * st.classified, st.views);
        TEST_ASSERT_TRUE(st.extra_looks >= st.views + st.refined);
        TEST_ASSERT_EQUAL_UINT32(0u, st.capacity_hit & SBR_RECOG_HIT_LOOKS);
        /* the frame's extra-look budget: views cost views - 1 looks a candidate, taken
           whole or not at all; a budget below that skips them (the first look's class
           and score stay) and says so; one candidate's worth serves the first */
        {
            const uint32_t all_views = st.views;
            TEST_ASSERT_EQUAL_UINT32(SBR_RECOG_DEFAULT_MAX_EXTRA_LOOKS, g_cfg.max_extra_looks);
            rc.max_extra_looks = SBR_RECOG_MAX_VIEWS - 2u;
            TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                    g_dets, 16u, &n, &st));
            TEST_ASSERT_TRUE(n >= 1u);
            TEST_ASSERT_EQUAL_UINT32(3u, g_dets[0].class_id);
            TEST_ASSERT_FLOAT_WITHIN(1e-4f, expf(4.0f) / (expf(4.0f) + 43.0f), g_dets[0].score);
            TEST_ASSERT_EQUAL_UINT32(0u, st.views);
            TEST_ASSERT_TRUE(st.extra_looks <= rc.max_extra_looks);
            TEST_ASSERT_EQUAL_UINT32(SBR_RECOG_HIT_LOOKS, st.capacity_hit & SBR_RECOG_HIT_LOOKS);
            rc.max_extra_looks = SBR_RECOG_MAX_VIEWS - 1u;
            rc.refine_steps = 0u;
            rc.triangle_view = 0u;
            TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                    g_dets, 16u, &n, &st));
            TEST_ASSERT_EQUAL_UINT32(SBR_RECOG_MAX_VIEWS - 1u, st.views);
            TEST_ASSERT_EQUAL_UINT32(SBR_RECOG_MAX_VIEWS - 1u, st.extra_looks);
            TEST_ASSERT_TRUE(all_views >= st.views);
            rc.max_extra_looks = 1000001u;
            TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_config_check(&rc));
            rc.max_extra_looks = g_cfg.max_extra_looks;
            rc.refine_steps = g_cfg.refine_steps;
            rc.triangle_view = g_cfg.triangle_view;
        }
        g_picto.looks.view_score = NAN;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&g_picto));
        g_picto.looks.view_score = 1.5f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&g_picto));
        g_picto.looks.view_score = 0.1f;
        rc.views = 0u;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                              16u, &n, &st));
        rc.views = SBR_RECOG_MAX_VIEWS + 1u;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                              16u, &n, &st));
    }
    /* triangle view (on by default): class 18 (a danger sign) gets the logit
       6 - 200 (r - b) of the chromaticities of the box's top-left colour cell. In the
       box's own view that cell holds part of the red ring (r > b): class 3 stays. In the
       triangle view the cell lies outside the triangle, replaced by grey (r = b): class
       18 with exactly e^6 / (e^6 + e^4 + 42), more than class 3's score, so it is
       taken. Off, or a value above 1 refused. The box's own view gives class 18 almost
       nothing (e^(6 - 200 (r - b))), so the default triangle_score skips the candidate
       unless that cell's red is weak; triangle_score 0 always looks, 1 never. */
    {
        const size_t row18 = 18u * (SBR_PICTO_FEATURES + 1u);
        const size_t colour0 = (SBR_PICTO_CELLS * SBR_PICTO_CELLS * 8u) + (SBR_PICTO_THUMB * SBR_PICTO_THUMB);
        sbr_recog_config_t rc = g_cfg;
        const float p18 = expf(6.0f) / (expf(6.0f) + expf(4.0f) + 42.0f);
        TEST_ASSERT_EQUAL_UINT32(1u, rc.triangle_view);
        TEST_ASSERT_EQUAL_FLOAT(0.001f, g_picto.looks.triangle_score);
        g_picto.looks.triangle_score = 0.0f;
        w2[row18 + SBR_PICTO_FEATURES] = 6.0f;
        w2[row18 + colour0] = -200.0f;
        w2[row18 + colour0 + 1u] = 200.0f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                       16u, &n, NULL));
        TEST_ASSERT_TRUE(n >= 1u);
        TEST_ASSERT_EQUAL_UINT32(18u, g_dets[0].class_id);
        TEST_ASSERT_FLOAT_WITHIN(1e-4f, p18, g_dets[0].score);
        /* which classes are triangles is the model's data: with class 18's outline a disc,
           the triangle view neither looks (no triangle class is probable) nor takes it */
        g_model.class_outline[18] = (uint8_t)SBR_PICTO_RIM_DISC;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                       16u, &n, NULL));
        TEST_ASSERT_TRUE(n >= 1u);
        TEST_ASSERT_EQUAL_UINT32(3u, g_dets[0].class_id);
        g_model.class_outline[18] = (uint8_t)SBR_PICTO_RIM_TRIANGLE;
        g_picto.looks.triangle_score = 1.0f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                       16u, &n, NULL));
        TEST_ASSERT_TRUE(n >= 1u);
        TEST_ASSERT_EQUAL_UINT32(3u, g_dets[0].class_id);
        g_picto.looks.triangle_score = NAN;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&g_picto));
        g_picto.looks.triangle_score = 1.5f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&g_picto));
        g_picto.looks.triangle_score = -0.5f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&g_picto));
        g_picto.looks.triangle_score = 0.0f;
        rc.triangle_view = 0u;
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                       16u, &n, NULL));
        TEST_ASSERT_TRUE(n >= 1u);
        TEST_ASSERT_EQUAL_UINT32(3u, g_dets[0].class_id);
        TEST_ASSERT_FLOAT_WITHIN(1e-3f, expf(4.0f) / (expf(4.0f) + 42.0f), g_dets[0].score);
        rc.triangle_view = 2u;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_config_check(&rc));
        sbr_picto_looks_default(&g_picto.looks);
        w2[row18 + SBR_PICTO_FEATURES] = 0.0f;
        w2[row18 + colour0] = 0.0f;
        w2[row18 + colour0 + 1u] = 0.0f;
    }
    w2[(3u * (SBR_PICTO_FEATURES + 1u)) + SBR_PICTO_FEATURES] = 0.0f;
    w2[(43u * (SBR_PICTO_FEATURES + 1u)) + SBR_PICTO_FEATURES] = 8.0f; /* the background output */
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws, g_dets,
                                                   16u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    w2[5] = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, recog_run(&v, NULL, &g_cfg, &g_model, &g_picto, g_ws, sizeof g_ws,
                                                            g_dets, 16u, &n, NULL));
    (void)memset(&g_picto, 0, sizeof g_picto);
}

/* Hostile frames with the built-in library and class stage: a status or detections that
   are well-formed (inside the frame, valid class, score in [min_score, 1]), never a
   crash. */
/* Outline candidates: a red-rimmed disc's outline is a candidate at its own box even when
   the part model gives it no hypothesis (min_parts above any hypothesis's parts), with a
   class stage only; the bound counts them and says when it ran full; a bar is not
   sign-shaped; the options are range-checked. The classifier always says class 3. */
static void test_outline_candidates(void)
{
    static float w2[44u * (SBR_PICTO_FEATURES + 1u)];
    sbr_picto_model_t pm;
    sbr_recog_config_t rc = g_cfg;
    sbr_recog_stats_t st;
    const sbr_image_t v = view();
    uint32_t n = 99u;
    uint32_t x;
    uint32_t y;
    uint32_t k;
    (void)memset(w2, 0, sizeof w2);
    w2[(3u * (SBR_PICTO_FEATURES + 1u)) + SBR_PICTO_FEATURES] = 4.0f;
    (void)memset(&pm, 0, sizeof pm);
    pm.version = SBR_PICTO_VERSION;
    pm.features = SBR_PICTO_FEATURES;
    pm.classes = 43u;
    pm.threshold = 0.5f;
    sbr_picto_looks_default(&pm.looks);
    pm.w2 = w2;
    rc.min_parts = 65535u; /* no part-model candidate */
    rc.outline_maps = 1u << (uint32_t)SBR_MAP_RED;
    /* a paler red around the sign's outline: the red map has two nested regions, the
       sign without and with the pale part. A ring 2 px wide (boxes 37 and 41 px, IoU
       0.81 <= 0.85): two candidates; the corners of the sign's box (both 41 px, IoU 1):
       one */
    for (k = 0u; k < 2u; k++) {
        clear();
        draw_sign(112.0f, 50.0f, 20.0f);
        for (y = 0u; y < H; y++) {
            for (x = 0u; x < W; x++) {
                const float dx = (float)x - 112.0f;
                const float dy = (float)y - 50.0f;
                const float d = sqrtf((dx * dx) + (dy * dy));
                const int pale = (k == 0u) ? ((d > 18.0f) && (d <= 20.0f))
                                           : ((d > 20.0f) && (fabsf(dx) <= 20.0f) && (fabsf(dy) <= 20.0f));
                if (pale != 0) {
                    g_rgb[y][x][0] = 170u;
                    g_rgb[y][x][1] = 70u;
                    g_rgb[y][x][2] = 75u;
                }
            }
        }
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &pm, g_ws, sizeof g_ws, g_dets, 16u,
                                                &n, &st));
        TEST_ASSERT_EQUAL_UINT32(2u - k, st.outlines);
    }
    TEST_ASSERT_EQUAL_UINT32(1u, st.classified);
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_UINT32(0u, g_dets[0].parts);
    TEST_ASSERT_EQUAL_UINT32(3u, g_dets[0].class_id);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, expf(4.0f) / (expf(4.0f) + 43.0f), g_dets[0].score);
    TEST_ASSERT_FLOAT_WITHIN(1.5f, 112.5f, box_cx(&g_dets[0]));
    TEST_ASSERT_UINT32_WITHIN(1u, 41u, g_dets[0].box.width); /* the outline's box */
    TEST_ASSERT_UINT32_WITHIN(1u, 41u, g_dets[0].box.height);
    TEST_ASSERT_EQUAL_UINT32(0u, st.capacity_hit & SBR_RECOG_HIT_OUTLINES);
    /* none: without the option, or without a class stage */
    rc.outline_maps = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &pm, g_ws, sizeof g_ws, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    TEST_ASSERT_EQUAL_UINT32(0u, st.outlines);
    rc.outline_maps = 1u << (uint32_t)SBR_MAP_RED;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, NULL, g_ws, sizeof g_ws, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    TEST_ASSERT_EQUAL_UINT32(0u, st.outlines);
    /* two discs: two candidates; a bound of one takes the first and says so */
    draw_sign(40.0f, 50.0f, 18.0f);
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &pm, g_ws, sizeof g_ws, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(2u, st.outlines);
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    rc.max_outline_candidates = 1u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &pm, g_ws, sizeof g_ws, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(1u, st.outlines);
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_UINT32(SBR_RECOG_HIT_OUTLINES, st.capacity_hit & SBR_RECOG_HIT_OUTLINES);
    rc.max_outline_candidates = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &pm, g_ws, sizeof g_ws, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    TEST_ASSERT_EQUAL_UINT32(SBR_RECOG_HIT_OUTLINES, st.capacity_hit & SBR_RECOG_HIT_OUTLINES);
    rc.max_outline_candidates = SBR_RECOG_DEFAULT_MAX_OUTLINES;
    /* a red bar three times as wide as it is tall is not sign-shaped */
    clear();
    for (y = 44u; y < 56u; y++) {
        for (x = 40u; x < 76u; x++) {
            g_rgb[y][x][0] = 210u;
            g_rgb[y][x][1] = 20u;
            g_rgb[y][x][2] = 30u;
        }
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &rc, &g_model, &pm, g_ws, sizeof g_ws, g_dets, 16u, &n, &st));
    TEST_ASSERT_EQUAL_UINT32(0u, st.outlines);
    /* out of range: refused */
    rc.outline_maps = 1u << SBR_MAP_KINDS;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_config_check(&rc));
    rc.outline_maps = 0u;
    rc.max_outline_candidates = 1000001u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, recog_run(&v, NULL, &rc, &g_model, &pm, g_ws, sizeof g_ws, g_dets, 16u,
                                                   &n, &st));
    /* the defaults: the red and blue maps, 64 */
    sbr_recog_config_default(&rc);
    TEST_ASSERT_EQUAL_UINT32((1u << (uint32_t)SBR_MAP_RED) | (1u << (uint32_t)SBR_MAP_BLUE), rc.outline_maps);
    TEST_ASSERT_EQUAL_UINT32(64u, rc.max_outline_candidates);
    clear();
    draw_sign(112.0f, 50.0f, 18.0f); /* the scene of the tests below */
}

static void test_hostile_frames_builtin(void)
{
    sbr_model_t m;
    sbr_recog_config_t c = g_cfg;
    sbr_image_t v = view();
    uint32_t n = 0u;
    uint32_t i;
    uint32_t x;
    uint32_t y;
    uint32_t k;
    uint32_t state = 12345u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_gtsdb(&m));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gtsdb(&g_picto)); /* with its class stage */
    c.max_model_protos = 1024u;
    c.min_parts = 1u;
    c.max_hypotheses = 64u;
    TEST_ASSERT_TRUE(sbr_recog_workspace_size(&c, W, H) <= sizeof g_ws);
    /* 1 x 1 */
    v.width = 1u;
    v.height = 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, recog_run(&v, NULL, &c, &m, &g_picto, g_ws, sizeof g_ws, g_dets, 16u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    /* a huge (corrupted) stride is refused before any pixel is read */
    v = view();
    v.stride = 0xFFFFFFF0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, recog_run(&v, NULL, &c, &m, &g_picto, g_ws, sizeof g_ws, g_dets, 16u,
                                                          &n, NULL));
    v.stride = SBR_IMAGE_MAX_STRIDE + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, recog_run(&v, NULL, &c, &m, &g_picto, g_ws, sizeof g_ws, g_dets, 16u,
                                                          &n, NULL));
    v = view();
    for (k = 0u; k < 3u; k++) {
        for (y = 0u; y < H; y++) {
            for (x = 0u; x < W; x++) {
                for (i = 0u; i < 3u; i++) {
                    if (k == 0u) {
                        g_rgb[y][x][i] = 0u;
                    } else if (k == 1u) {
                        g_rgb[y][x][i] = 255u;
                    } else {
                        state = (state * 1664525u) + 1013904223u;
                        g_rgb[y][x][i] = (uint8_t)(state >> 24);
                    }
                }
            }
        }
        TEST_ASSERT_EQUAL_INT(SBR_OK, recog_run(&v, NULL, &c, &m, &g_picto, g_ws, sizeof g_ws, g_dets, 16u, &n,
                                                       NULL));
        if (k < 2u) {
            TEST_ASSERT_EQUAL_UINT32(0u, n); /* flat frames have no regions */
        }
        for (i = 0u; i < n; i++) {
            TEST_ASSERT_TRUE(g_dets[i].class_id < m.class_count);
            TEST_ASSERT_TRUE((g_dets[i].score >= c.min_score) && (g_dets[i].score <= 1.0f));
            TEST_ASSERT_TRUE(g_dets[i].box.x + g_dets[i].box.width <= W);
            TEST_ASSERT_TRUE(g_dets[i].box.y + g_dets[i].box.height <= H);
        }
    }
}

/* The built-in library is consistent and fits the default configuration; the macro bound
   is never below the exact workspace size. */
static void test_builtin_model_and_sizes(void)
{
    sbr_model_t builtin;
    sbr_picto_model_t picto;
    const sbr_model_t *m = &builtin;
    sbr_recog_config_t d;
    uint32_t s;
    sbr_recog_config_default(&d);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_model_gtsdb(NULL));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_gtsdb(&builtin));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gtsdb(&picto));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_check(m));
    TEST_ASSERT_EQUAL_UINT32(d.parts.fd_n, m->fd_n);
    TEST_ASSERT_EQUAL_UINT32(d.parts.fd_m, m->fd_m);
    TEST_ASSERT_TRUE(m->proto_count <= d.max_model_protos);
    TEST_ASSERT_EQUAL_UINT32(43u, m->class_count); /* GTSDB's classes, as data of the model */
    TEST_ASSERT_EQUAL_UINT32(43u, picto.classes); /* its class stage: the same classes */
    TEST_ASSERT_EQUAL_UINT8(SBR_PICTO_RIM_TRIANGLE, m->class_outline[11]);  /* danger signs */
    TEST_ASSERT_EQUAL_UINT8(SBR_PICTO_RIM_TRIANGLE, m->class_outline[31]);
    TEST_ASSERT_EQUAL_UINT8(SBR_PICTO_RIM_TRIANGLE_DOWN, m->class_outline[13]); /* yield */
    TEST_ASSERT_EQUAL_UINT8(SBR_PICTO_RIM_DISC, m->class_outline[0]);  /* 20 km/h */
    TEST_ASSERT_TRUE(m->class_first[m->class_count] > 0u);
    TEST_ASSERT_EQUAL_UINT32(SBR_PICTO_VERSION, picto.version);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&picto));
    for (s = 1u; s <= 4u; s *= 2u) {
        d.parts.subsample = s;
        TEST_ASSERT_TRUE(sbr_recog_workspace_size(&d, 1360u, 800u) > 0u);
        TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_RECOG_WORKSPACE_DEFAULT_SIZE(1360u, 800u, s),
                                 (uint32_t)sbr_recog_workspace_size(&d, 1360u, 800u));
    }
    TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_RECOG_WORKSPACE_DEFAULT_SIZE(320u, 240u, 4u),
                             (uint32_t)sbr_recog_workspace_size(&d, 320u, 240u));
    d.parts.subsample = 3u; /* odd sizes: the maps round down */
    TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_RECOG_WORKSPACE_DEFAULT_SIZE(333u, 251u, 3u),
                             (uint32_t)sbr_recog_workspace_size(&d, 333u, 251u));
    /* the workspace of the default at 1360 x 800 (docs/results/realtime.md) */
    TEST_ASSERT_EQUAL_UINT32(7193960u, (uint32_t)SBR_RECOG_WORKSPACE_DEFAULT_SIZE(1360u, 800u, 1u));
    /* the strip configuration: one band's workspace, the macro equal to the function, in
       the 2 MiB an MCU-class ECU's SRAM holds */
    sbr_recog_config_strips(&d);
    TEST_ASSERT_EQUAL_UINT32(SBR_RECOG_STRIP_MAX_CANDIDATES, d.max_candidates);
    TEST_ASSERT_EQUAL_UINT32(SBR_RECOG_STRIP_MAX_NODES, d.parts.mser.max_nodes);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_RECOG_WORKSPACE_STRIP_SIZE(1360u),
                             (uint32_t)sbr_recog_strip_workspace_size(&d, 1360u, 800u, SBR_RECOG_STRIP_ROWS));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_RECOG_WORKSPACE_STRIP_SIZE(640u),
                             (uint32_t)sbr_recog_strip_workspace_size(&d, 640u, 480u, SBR_RECOG_STRIP_ROWS));
    TEST_ASSERT_EQUAL_UINT32(1942760u, (uint32_t)SBR_RECOG_WORKSPACE_STRIP_SIZE(1360u));
    TEST_ASSERT_TRUE(SBR_RECOG_WORKSPACE_STRIP_SIZE(1360u) <= (2u * 1024u * 1024u));
    sbr_recog_config_strips(NULL); /* no-op */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_finds_sign_elsewhere_and_larger);
    RUN_TEST(test_empty_frame_and_min_parts);
    RUN_TEST(test_cascade_finds_the_parts_that_did_not_vote);
    RUN_TEST(test_roi_offsets_boxes);
    RUN_TEST(test_capacity);
    RUN_TEST(test_strips);
    RUN_TEST(test_strips_capacity_and_input);
    RUN_TEST(test_grey_frame);
    RUN_TEST(test_bad_input);
    RUN_TEST(test_recog_object);
    RUN_TEST(test_recog_h_statuses);
    RUN_TEST(test_builtin_model_and_sizes);
    RUN_TEST(test_class_stage);
    RUN_TEST(test_outline_candidates);
    RUN_TEST(test_hostile_frames_builtin);
    return UNITY_END();
}
