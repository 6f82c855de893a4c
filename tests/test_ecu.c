/* SPDX-License-Identifier: MIT */
/* Unity tests of the ECU's per-frame job (include/sbr/ecu.h): a drive with known truth
   through the object (an 80 km/h sign passing with a one-frame misclassification, a
   one-frame false "no overtaking", a failed frame, the end-of-80 sign), read back from the
   CAN frames it sent; stills; the recogniser in the loop; every status. */
#include "unity.h"
#include "sbr/ecu.h"
#include "sbr/models.h"
#include "sbr_port_mock.h"
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

#define P 100000u /* us between frames */
#define T0 1000000000u

static uint64_t g_ws[300000u / 8u];
static uint64_t g_rws[700000u / 8u];
static sbr_ecu_t g_e;
static sbr_can_frame_t g_frames[64];
static sbr_port_mock_t g_port;
static sbr_ecu_result_t g_r;

static void start(uint32_t stills)
{
    sbr_ecu_config_t cfg;
    sbr_ecu_config_default(&cfg);
    cfg.stills = stills;
    cfg.min_score = 0.2f;
    TEST_ASSERT_TRUE(sbr_ecu_workspace_size(&cfg) <= sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ecu_init(&g_e, &cfg, g_ws, sizeof g_ws));
}

static sbr_detection_t det(uint32_t x, uint32_t y, uint32_t w, uint16_t c, float s)
{
    sbr_detection_t d;
    memset(&d, 0, sizeof d);
    d.box.x = x;
    d.box.y = y;
    d.box.width = w;
    d.box.height = w;
    d.class_id = c;
    d.score = s;
    return d;
}

/* One frame's cycle into the mock port; returns the status. */
static sbr_status_t frame(uint64_t t, const sbr_detection_t *d, uint32_t n, uint32_t error)
{
    sbr_ecu_frame_info_t info;
    memset(&info, 0, sizeof info);
    info.processing_ms = 12.5f;
    info.regions = 321u;
    info.error = error;
    sbr_port_mock_init(&g_port, g_frames, 64u);
    return sbr_ecu_output(&g_e, t, d, n, &info, &sbr_port_mock, &g_port, &g_r);
}

/* The cycle's frames decoded: its status, its listed signs (slot order), its detections. */
typedef struct {
    sbr_can_ecu_status_t status;
    sbr_can_confirmed_sign_t sign[4];
    uint32_t signs;
    sbr_can_detection_t det[16];
    uint32_t dets;
    sbr_can_restrictions_t restr;
    uint32_t restr_frames;
} cycle_t;

static sbr_can_e2e_rx_t g_rx[4];

static void rx_start(void)
{
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_rx_init(&g_rx[0], SBR_CAN_ID_CONFIRMED_SIGN));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_rx_init(&g_rx[1], SBR_CAN_ID_ECU_STATUS));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_rx_init(&g_rx[2], SBR_CAN_ID_DETECTION));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_rx_init(&g_rx[3], SBR_CAN_ID_RESTRICTIONS));
}

static cycle_t decode(void)
{
    cycle_t c;
    uint32_t i;
    uint32_t status_at = 99u;
    memset(&c, 0, sizeof c);
    TEST_ASSERT_EQUAL_UINT32(g_r.frames_sent, g_port.count);
    (void)status_at;
    for (i = 0u; i < g_port.count; i++) {
        const sbr_can_frame_t *f = &g_frames[i];
        sbr_can_e2e_result_t res;
        const uint32_t k = (f->id == SBR_CAN_ID_CONFIRMED_SIGN)
                               ? 0u
                               : ((f->id == SBR_CAN_ID_ECU_STATUS) ? 1u : ((f->id == SBR_CAN_ID_RESTRICTIONS) ? 3u : 2u));
        if (f->id == SBR_CAN_ID_TRACKED_OBJECT) {
            continue;
        }
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_check(&g_rx[k], f, &res)); /* every frame protected, in order */
        if (k == 0u) {
            sbr_can_confirmed_sign_t s;
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_confirmed_sign(f, &s));
            if (s.class_id != SBR_CAN_CLASS_NONE) {
                TEST_ASSERT_EQUAL_UINT32(c.signs, s.slot);
                c.sign[c.signs++] = s;
            }
        } else if (k == 1u) {
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_ecu_status(f, &c.status));
            status_at = i;
        } else if (k == 3u) {
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_restrictions(f, &c.restr));
            TEST_ASSERT_EQUAL_UINT32(status_at + 1u, i); /* right after the status */
            c.restr_frames++;
        } else {
            sbr_can_detection_t d;
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_detection(f, &d));
            if ((d.class_id != SBR_CAN_CLASS_NONE_DET) && (c.dets < 16u)) {
                c.det[c.dets++] = d;
            }
        }
    }
    return c;
}

static void test_drive(void)
{
    uint32_t f;
    uint32_t id_a = 0u;
    start(0u);
    rx_start();
    for (f = 0u; f < 22u; f++) {
        sbr_detection_t d[3];
        uint32_t n = 0u;
        cycle_t c;
        /* A: 80 km/h (class 5) on the right, frames 0..8, taken for 60 (3) in frame 4 */
        if (f <= 8u) {
            d[n++] = det(900u + 8u * f, 300u - 3u * f, 30u + 2u * f, (f == 4u) ? 3u : 5u, 0.9f);
        }
        /* a one-frame false "no overtaking" (9) in frame 6, and a weak detection below
           min_score in frame 7 */
        if (f == 6u) {
            d[n++] = det(200u, 500u, 40u, 9u, 0.7f);
        }
        if (f == 7u) {
            d[n++] = det(600u, 100u, 40u, 9u, 0.1f);
        }
        /* C: end of 80 (6) on the left, frames 14..20 */
        if ((f >= 14u) && (f <= 20u)) {
            d[n++] = det(400u - 6u * (f - 14u), 320u, 36u, 6u, 0.8f);
        }
        TEST_ASSERT_EQUAL_INT(SBR_OK, frame(T0 + (uint64_t)f * P, n > 0u ? d : NULL, n, f == 11u ? 1u : 0u));
        c = decode();
        TEST_ASSERT_EQUAL_UINT32(f, c.status.frame_counter);
        TEST_ASSERT_EQUAL_UINT32(f == 11u ? 1u : 0u, c.status.error); /* the failed frame is sent */
        TEST_ASSERT_FLOAT_WITHIN(0.05f, 12.5f, c.status.processing_ms);
        TEST_ASSERT_EQUAL_UINT32(321u, c.status.region_count);
        TEST_ASSERT_EQUAL_UINT32((f == 7u) ? n - 1u : n, c.status.detection_count);
        TEST_ASSERT_EQUAL_UINT32(c.status.detection_count, c.dets);
        TEST_ASSERT_EQUAL_UINT32(0u, g_r.restrictions.no_overtaking); /* the false sign never counts */
        /* what the driver is shown, on CAN: the restrictions of the frame */
        TEST_ASSERT_EQUAL_UINT32(1u, c.restr_frames);
        TEST_ASSERT_EQUAL_UINT32(g_r.restrictions.speed_limit_kmh, c.restr.speed_limit_kmh);
        TEST_ASSERT_EQUAL_UINT32(0u, c.restr.no_overtaking);
        TEST_ASSERT_EQUAL_UINT32(g_r.restrictions.speed_age_ms / 1000u, c.restr.speed_age_s);
        if (f == 0u) {
            TEST_ASSERT_EQUAL_UINT32(0u, c.signs); /* one detection confirms nothing */
            TEST_ASSERT_EQUAL_UINT32(0u, g_r.restrictions.speed_limit_kmh);
            TEST_ASSERT_EQUAL_UINT32(SBR_CAN_TRACK_NONE_DET, c.det[0].track_id);
        }
        if (f == 1u) {
            TEST_ASSERT_EQUAL_UINT32(1u, g_r.confirmed);
            TEST_ASSERT_EQUAL_UINT32(1u, c.signs);
            TEST_ASSERT_EQUAL_UINT32(5u, c.sign[0].class_id);
            TEST_ASSERT_EQUAL_UINT32(80u, c.sign[0].speed_kmh);
            TEST_ASSERT_EQUAL_UINT32(0u, c.sign[0].age_frames);
            TEST_ASSERT_EQUAL_FLOAT(90.0f, c.sign[0].confidence);
            id_a = c.sign[0].track_id;
            TEST_ASSERT_EQUAL_UINT32(id_a % 63u, c.det[0].track_id);
            TEST_ASSERT_EQUAL_UINT32(80u, g_r.restrictions.speed_limit_kmh);
            TEST_ASSERT_EQUAL_UINT32(80u, c.restr.speed_limit_kmh);
        }
        if (f == 12u) {
            TEST_ASSERT_EQUAL_UINT32(1u, c.restr.speed_age_s); /* confirmed in frame 1 */
        }
        if ((f >= 2u) && (f <= 13u)) {
            /* listed once, ageing; the misread frame 4 renames nothing */
            TEST_ASSERT_EQUAL_UINT32(0u, g_r.confirmed);
            TEST_ASSERT_EQUAL_UINT32(1u, c.signs);
            TEST_ASSERT_EQUAL_UINT32(5u, c.sign[0].class_id);
            TEST_ASSERT_EQUAL_UINT32(id_a, c.sign[0].track_id);
            TEST_ASSERT_EQUAL_UINT32(f - 1u, c.sign[0].age_frames);
            TEST_ASSERT_EQUAL_UINT32(80u, g_r.restrictions.speed_limit_kmh);
        }
        if (f == 15u) {
            /* the end of 80 confirmed: listed first, the limit cleared */
            TEST_ASSERT_EQUAL_UINT32(1u, g_r.confirmed);
            TEST_ASSERT_EQUAL_UINT32(2u, c.signs);
            TEST_ASSERT_EQUAL_UINT32(6u, c.sign[0].class_id);
            TEST_ASSERT_EQUAL_UINT32(SBR_CAN_SPEED_NONE, c.sign[0].speed_kmh);
            TEST_ASSERT_TRUE(c.sign[0].track_id != id_a);
            TEST_ASSERT_EQUAL_UINT32(5u, c.sign[1].class_id);
            TEST_ASSERT_EQUAL_UINT32(14u, c.sign[1].age_frames);
            TEST_ASSERT_EQUAL_UINT32(0u, g_r.restrictions.speed_limit_kmh);
        }
    }
}

/* Stills: every detection is a confirmed sign in its own frame, listed by score. */
static void test_stills(void)
{
    sbr_detection_t d[2];
    cycle_t c;
    start(1u);
    rx_start();
    d[0] = det(100u, 100u, 30u, 14u, 0.5f);
    d[1] = det(300u, 100u, 30u, 1u, 0.9f);
    TEST_ASSERT_EQUAL_INT(SBR_OK, frame(T0, d, 2u, 0u));
    c = decode();
    TEST_ASSERT_EQUAL_UINT32(2u, c.signs);
    TEST_ASSERT_EQUAL_UINT32(1u, c.sign[0].class_id);
    TEST_ASSERT_EQUAL_UINT32(30u, c.sign[0].speed_kmh);
    TEST_ASSERT_EQUAL_UINT32(0u, c.sign[0].track_id);
    TEST_ASSERT_EQUAL_UINT32(14u, c.sign[1].class_id);
    TEST_ASSERT_EQUAL_UINT32(1u, c.sign[1].track_id);
    TEST_ASSERT_EQUAL_UINT32(30u, g_r.restrictions.speed_limit_kmh);
    TEST_ASSERT_EQUAL_INT(SBR_OK, frame(T0 + P, d, 1u, 0u));
    c = decode();
    TEST_ASSERT_EQUAL_UINT32(3u, c.signs);
    TEST_ASSERT_EQUAL_UINT32(2u, c.sign[0].track_id);
    TEST_ASSERT_EQUAL_UINT32(1u, c.sign[1].age_frames);
}

/* The recogniser in the loop: an empty frame sends a clean cycle; a frame it refuses
   sends the cycle with error = 1 and the recogniser's status is returned. */
static void test_frame(void)
{
    static uint8_t img[64u * 96u * 3u];
    sbr_recog_config_t rc;
    sbr_model_t model;
    sbr_picto_model_t picto;
    sbr_recog_t rec;
    sbr_image_t v;
    cycle_t c;
    start(0u);
    rx_start();
    sbr_recog_config_default(&rc);
    /* bounds small enough for the emulated Cortex-M4's memory */
    rc.parts.max_side = 48u;
    rc.parts.max_regions = 256u;
    rc.parts.max_contour = 512u;
    rc.parts.mser.max_nodes = 4000u;
    rc.max_parts = 128u;
    rc.max_votes = 2048u;
    rc.max_hypotheses = 64u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_model_gtsdb(&model));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gtsdb(&picto));
    TEST_ASSERT_TRUE(sbr_recog_workspace_size(&rc, 96u, 64u) <= sizeof g_rws);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_init(&rec, &rc, &model, &picto, g_rws, sizeof g_rws));
    memset(img, 128, sizeof img);
    v.width = 96u;
    v.height = 64u;
    v.stride = 96u * 3u;
    v.format = SBR_PIXEL_RGB888;
    v.data = img;
    sbr_port_mock_init(&g_port, g_frames, 64u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ecu_frame(&g_e, &rec, &v, T0, 0u, &sbr_port_mock, &g_port, &g_r));
    c = decode();
    TEST_ASSERT_EQUAL_INT(SBR_OK, g_r.recog);
    TEST_ASSERT_EQUAL_UINT32(0u, c.status.error);
    TEST_ASSERT_EQUAL_UINT32(0u, c.status.detection_count);
    TEST_ASSERT_EQUAL_UINT32(5u, g_r.frames_sent); /* no sign, status, restrictions, no detection, no object */
    v.stride = 7u; /* shorter than a row */
    sbr_port_mock_init(&g_port, g_frames, 64u);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, sbr_ecu_frame(&g_e, &rec, &v, T0 + P, 0u, &sbr_port_mock, &g_port, &g_r));
    c = decode();
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, g_r.recog);
    TEST_ASSERT_EQUAL_UINT32(1u, c.status.error);
    TEST_ASSERT_EQUAL_UINT32(1u, c.status.frame_counter);
}

static void test_statuses(void)
{
    sbr_ecu_config_t cfg;
    sbr_ecu_frame_info_t info;
    sbr_detection_t d = det(100u, 100u, 30u, 14u, 0.5f);
    sbr_ecu_t blank;
    sbr_ecu_config_default(&cfg);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ecu_config_check(&cfg));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_ECU_WORKSPACE_SIZE(16u, 43u, 16u), (uint32_t)sbr_ecu_workspace_size(&cfg));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_ecu_config_check(NULL));
    cfg.rules.class_count = 42u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ecu_config_check(&cfg));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_ecu_workspace_size(&cfg));
    sbr_ecu_config_default(&cfg);
    cfg.sched.frame_budget = SBR_ECU_MAX_FRAMES + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ecu_config_check(&cfg));
    sbr_ecu_config_default(&cfg);
    cfg.min_score = 1.5f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ecu_config_check(&cfg));
    sbr_ecu_config_default(&cfg);
    cfg.signs.max_tracks = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_ecu_init(&g_e, &cfg, g_ws, sizeof g_ws));
    sbr_ecu_config_default(&cfg);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_ecu_init(&g_e, &cfg, g_ws, sbr_ecu_workspace_size(&cfg) - 1u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_ecu_init(&g_e, &cfg, (uint8_t *)g_ws + 4, sizeof g_ws - 8u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_ecu_init(NULL, &cfg, g_ws, sizeof g_ws));
    start(0u);
    memset(&info, 0, sizeof info);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_ecu_output(NULL, T0, &d, 1u, &info, &sbr_port_mock, &g_port, &g_r));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_ecu_output(&g_e, T0, NULL, 1u, &info, &sbr_port_mock, &g_port, &g_r));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_ecu_output(&g_e, T0, &d, 1u, NULL, &sbr_port_mock, &g_port, &g_r));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_ecu_output(&g_e, T0, &d, 1u, &info, NULL, &g_port, &g_r));
    TEST_ASSERT_EQUAL_INT(SBR_OK, frame(T0, &d, 1u, 0u));
    /* refusals send nothing */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, frame(T0, &d, 1u, 0u));
    TEST_ASSERT_EQUAL_UINT32(0u, g_port.count);
    d.score = 1.01f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, frame(T0 + P, &d, 1u, 0u));
    d.score = 0.5f;
    d.class_id = 43u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, frame(T0 + P, &d, 1u, 0u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, frame(T0 + P, &d, 1u, 2u));
    TEST_ASSERT_EQUAL_UINT32(0u, g_port.count);
    /* a port that refuses: its status, the frames before it sent */
    d.class_id = 14u;
    sbr_port_mock_init(&g_port, g_frames, 64u);
    g_port.accept_limit = 2u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY,
                          sbr_ecu_output(&g_e, T0 + P, &d, 1u, &info, &sbr_port_mock, &g_port, &g_r));
    TEST_ASSERT_EQUAL_UINT32(2u, g_r.frames_sent);
    memset(&blank, 0, sizeof blank);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_ecu_output(&blank, T0, &d, 1u, &info, &sbr_port_mock, &g_port, &g_r));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_drive);
    RUN_TEST(test_stills);
    RUN_TEST(test_frame);
    RUN_TEST(test_statuses);
    return UNITY_END();
}
