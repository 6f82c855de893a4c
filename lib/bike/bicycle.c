/* SPDX-License-Identifier: MIT */
/* Bicycle tracking from wheel ellipses (paper B), its geometry: argument checks, the
   bicycle's motion, the projection of its wheels, wheel grouping and pairing. The particle
   filter is in bike_filter.c. See include/sbr/bike.h. */
#include "sbr/bike.h"

#include <math.h>
#include <string.h>

#include "../common/sbr_util.h"
#include "bike_internal.h"

/* ---------------------------------------------------------------- validation */

int sbr_bike_priv_model_ok(const sbr_bike_model_t *m)
{
    return (isfinite(m->wheel_radius) != 0) && (isfinite(m->wheelbase) != 0) &&
           (isfinite(m->roll_tau) != 0) && (m->wheel_radius >= 1e-3f) &&
           (m->wheelbase > (2.0f * m->wheel_radius)) && (m->roll_tau >= 1e-3f) &&
           (m->roll_tau <= 1e3f) && (m->wheel_radius <= 10.0f) && (m->wheelbase < 100.0f);
}

int sbr_bike_priv_camera_ok(const sbr_camera_t *c)
{
    return (isfinite(c->focal) != 0) && (isfinite(c->cx) != 0) && (isfinite(c->cy) != 0) &&
           (isfinite(c->height) != 0) && (c->focal >= 1.0f) && (c->height >= 1e-3f) &&
           (c->height <= 1e3f) && (fabsf(c->cx) < 1e6f) && (fabsf(c->cy) < 1e6f) &&
           (c->focal <= 1e6f);
}

static int state_ok(const sbr_bike_state_t *s)
{
    return (isfinite(s->x) != 0) && (isfinite(s->z) != 0) && (isfinite(s->heading) != 0) &&
           (isfinite(s->speed) != 0) && (isfinite(s->steer) != 0) && (isfinite(s->roll) != 0) &&
           (fabsf(s->x) < 1e4f) && (fabsf(s->z) < 1e4f) && (s->heading > -SBR_PI_F) &&
           (s->heading <= SBR_PI_F) &&
           (s->speed >= 0.0f) && (s->speed <= 100.0f) && (fabsf(s->steer) < (0.5f * SBR_PI_F)) &&
           (fabsf(s->roll) < (0.5f * SBR_PI_F));
}

static int ellipse_ok(const sbr_ellipse_t *e)
{
    return (isfinite(e->cx) != 0) && (isfinite(e->cy) != 0) && (isfinite(e->angle) != 0) &&
           (isfinite(e->semi_major) != 0) && (isfinite(e->semi_minor) != 0) &&
           (e->semi_minor > 0.0f) && (e->semi_major >= e->semi_minor) && (e->semi_major < 1e6f) &&
           (fabsf(e->cx) < 1e6f) && (fabsf(e->cy) < 1e6f) && (fabsf(e->angle) < 1e6f);
}

int sbr_bike_priv_ellipses_ok(const sbr_ellipse_t *e, uint32_t n)
{
    uint32_t i;
    int ok = 1;
    for (i = 0u; i < n; ++i) {
        if (ellipse_ok(&e[i]) == 0) {
            ok = 0;
        }
    }
    return ok;
}

/* a in (-pi, pi], whatever the number of turns (a sub-step of a fast, sharply steered
   bicycle turns by more than 2 pi); a finite a. fmodf is exact, and within one period
   the result equals a -+ 2 pi as before. */
float sbr_bike_priv_wrap_angle(float a)
{
    float r = a;
    if ((r > SBR_PI_F) || (r <= -SBR_PI_F)) {
        r = fmodf(r, 2.0f * SBR_PI_F); /* (-2 pi, 2 pi), exact */
        if (r > SBR_PI_F) {
            r -= 2.0f * SBR_PI_F;
        } else if (r <= -SBR_PI_F) {
            r += 2.0f * SBR_PI_F;
        } else {
            /* in range */
        }
        if (r <= -SBR_PI_F) {
            r = SBR_PI_F; /* -pi rounded: the same direction */
        }
    }
    return r;
}

/* ---------------------------------------------------------------- model */

void sbr_bike_model_default(sbr_bike_model_t *model)
{
    if (model != NULL) {
        model->wheel_radius = 0.34f;
        model->wheelbase = 1.05f;
        model->roll_tau = 0.3f;
    }
}

/* The deterministic model, dt already checked. */
void sbr_bike_priv_advance(const sbr_bike_model_t *m, sbr_bike_state_t *s, float dt)
{
    const uint32_t steps = (uint32_t)ceilf(dt / BIKE_SUBSTEP);
    if (steps > 0u) {
        uint32_t k;
        const float h = dt / (float)steps;
        const float relax = 1.0f - expf(-h / m->roll_tau);
        const float yaw_rate = (s->speed * tanf(s->steer)) / m->wheelbase;
        const float roll_eq = atanf((s->speed * yaw_rate) / BIKE_G);
        for (k = 0u; k < steps; ++k) {
            s->x += s->speed * cosf(s->heading) * h;
            s->z += s->speed * sinf(s->heading) * h;
            s->heading = sbr_bike_priv_wrap_angle(s->heading + (yaw_rate * h));
            s->roll += (roll_eq - s->roll) * relax;
        }
    }
}

sbr_status_t sbr_bike_predict_state(const sbr_bike_model_t *model, const sbr_bike_state_t *state,
                                    uint32_t dt_us, sbr_bike_state_t *out)
{
    sbr_status_t st = SBR_OK;
    if ((model == NULL) || (state == NULL) || (out == NULL)) {
        st = SBR_ERR_NULL;
    } else if ((sbr_bike_priv_model_ok(model) == 0) || (state_ok(state) == 0) ||
               (dt_us > BIKE_MAX_DT_STATE_US)) {
        st = SBR_ERR_RANGE;
    } else {
        sbr_bike_state_t s = *state;
        sbr_bike_priv_advance(model, &s, sbr_util_seconds(dt_us));
        /* a state this function would itself refuse is never returned as SBR_OK: one
           that leaves the state's range (|x| or |z| reaching 1e4 m, a roll at pi/2) is
           refused and out left as it was */
        if (state_ok(&s) == 0) {
            st = SBR_ERR_RANGE;
        } else {
            *out = s;
        }
    }
    return st;
}

/* ---------------------------------------------------------------- projection */

/* Image ellipse of a wheel: contact point (x, height, z), plane direction theta, roll. */
static int wheel_ellipse(const sbr_camera_t *cam, float r, float x, float z, float theta, float roll,
                         sbr_ellipse_t *out)
{
    const float dx = cosf(theta);
    const float dz = sinf(theta);
    const float cr = cosf(roll);
    const float sr = sinf(roll);
    /* up in the leaning wheel plane: the vertical (0, -1, 0) tilted by the roll towards left = (-dz, 0, dx) */
    const float ux = -sr * dz;
    const float uy = -cr;
    const float uz = sr * dx;
    const float px = x + (r * ux);
    const float py = cam->height + (r * uy);
    const float pz = z + (r * uz);
    int ok = 0;
    if ((pz - (r * sqrtf((dz * dz) + (uz * uz)))) > BIKE_MIN_Z) {
        /* H = [d u p] maps circle-plane coordinates (alpha, beta, 1) to normalised image
           coordinates; the image conic is adj(H)^T diag(1, 1, -r^2) adj(H). */
        const float h[9] = {dx, ux, px, 0.0f, uy, py, dz, uz, pz};
        float m[9];
        float q[9];
        uint32_t i;
        uint32_t j;
        m[0] = (h[4] * h[8]) - (h[5] * h[7]);
        m[1] = (h[2] * h[7]) - (h[1] * h[8]);
        m[2] = (h[1] * h[5]) - (h[2] * h[4]);
        m[3] = (h[5] * h[6]) - (h[3] * h[8]);
        m[4] = (h[0] * h[8]) - (h[2] * h[6]);
        m[5] = (h[2] * h[3]) - (h[0] * h[5]);
        m[6] = (h[3] * h[7]) - (h[4] * h[6]);
        m[7] = (h[1] * h[6]) - (h[0] * h[7]);
        m[8] = (h[0] * h[4]) - (h[1] * h[3]);
        for (i = 0u; i < 3u; ++i) {
            for (j = 0u; j < 3u; ++j) {
                q[(i * 3u) + j] = (m[i] * m[j]) + (m[3u + i] * m[3u + j]) - (r * r * m[6u + i] * m[6u + j]);
            }
        }
        {
            const sbr_conic_t c = {q[0], q[1], q[4], q[2], q[5], q[8]};
            sbr_ellipse_t e;
            if (sbr_conic_to_ellipse(&c, &e) == SBR_OK) {
                out->cx = (cam->focal * e.cx) + cam->cx;
                out->cy = (cam->focal * e.cy) + cam->cy;
                out->semi_major = cam->focal * e.semi_major;
                out->semi_minor = cam->focal * e.semi_minor;
                out->angle = e.angle;
                ok = 1;
            }
        }
    }
    return ok;
}

/* Both wheels of a checked state; 0 when either is not an ellipse in front of the camera. */
int sbr_bike_priv_project_both(const sbr_camera_t *cam, const sbr_bike_model_t *m, const sbr_bike_state_t *s,
                        sbr_ellipse_t *rear, sbr_ellipse_t *front)
{
    const float fx = s->x + (m->wheelbase * cosf(s->heading));
    const float fz = s->z + (m->wheelbase * sinf(s->heading));
    int ok = wheel_ellipse(cam, m->wheel_radius, s->x, s->z, s->heading, s->roll, rear);
    if (ok != 0) {
        ok = wheel_ellipse(cam, m->wheel_radius, fx, fz, s->heading + s->steer, s->roll, front);
    }
    return ok;
}

sbr_status_t sbr_bike_project(const sbr_camera_t *camera, const sbr_bike_model_t *model,
                              const sbr_bike_state_t *state, sbr_ellipse_t *rear,
                              sbr_ellipse_t *front)
{
    sbr_status_t st = SBR_OK;
    if ((camera == NULL) || (model == NULL) || (state == NULL)) {
        st = SBR_ERR_NULL;
    } else if ((sbr_bike_priv_camera_ok(camera) == 0) || (sbr_bike_priv_model_ok(model) == 0) ||
               (state_ok(state) == 0)) {
        st = SBR_ERR_RANGE;
    } else {
        sbr_ellipse_t r;
        sbr_ellipse_t f;
        if (sbr_bike_priv_project_both(camera, model, state, &r, &f) == 0) {
            st = SBR_ERR_DEGENERATE;
        } else {
            if (rear != NULL) {
                *rear = r;
            }
            if (front != NULL) {
                *front = f;
            }
        }
    }
    return st;
}

/* ---------------------------------------------------------------- wheel candidates and pairs */

sbr_ellipse_t sbr_bike_priv_group_ellipse(const wheel_group_t *g)
{
    const float k = 1.0f / (float)g->n;
    sbr_ellipse_t e;
    e.cx = g->cx * k;
    e.cy = g->cy * k;
    e.semi_major = g->a * k;
    e.semi_minor = fminf(g->b * k, e.semi_major);
    e.angle = 0.5f * atan2f(g->ey, g->ex);
    if (e.angle <= (-0.5f * SBR_PI_F)) {
        e.angle += SBR_PI_F;
    }
    return e;
}

/* Concentric ellipses (a tyre's inner and outer edge) into groups; returns the count. */
uint32_t sbr_bike_priv_group_ellipses(const sbr_ellipse_t *el, uint32_t n, wheel_group_t *g)
{
    uint32_t ng = 0u;
    uint32_t i;
    for (i = 0u; i < n; ++i) {
        const sbr_ellipse_t *e = &el[i];
        uint32_t j;
        uint32_t hit = ng;
        for (j = 0u; (j < ng) && (hit == ng); ++j) {
            const sbr_ellipse_t m = sbr_bike_priv_group_ellipse(&g[j]);
            const float big = fmaxf(m.semi_major, e->semi_major);
            const float small = fminf(m.semi_major, e->semi_major);
            const float dx = m.cx - e->cx;
            const float dy = m.cy - e->cy;
            const float tol = 2.0f + (0.2f * big);
            if ((((dx * dx) + (dy * dy)) < (tol * tol)) && (big <= (1.5f * small))) {
                hit = j;
            }
        }
        if (hit == ng) {
            g[ng].cx = 0.0f;
            g[ng].cy = 0.0f;
            g[ng].a = 0.0f;
            g[ng].b = 0.0f;
            g[ng].ex = 0.0f;
            g[ng].ey = 0.0f;
            g[ng].n = 0u;
            g[ng].first = i;
            ng++;
        }
        {
            const float el_ = e->semi_major - e->semi_minor;
            g[hit].cx += e->cx;
            g[hit].cy += e->cy;
            g[hit].a += e->semi_major;
            g[hit].b += e->semi_minor;
            g[hit].ex += el_ * cosf(2.0f * e->angle);
            g[hit].ey += el_ * sinf(2.0f * e->angle);
            g[hit].n++;
        }
    }
    return ng;
}

/* Pair score of two wheel candidates, or a negative value when they cannot pair. */
static float pair_score(const sbr_ellipse_t *p, const sbr_ellipse_t *q, const sbr_bike_model_t *m)
{
    const float am = 0.5f * (p->semi_major + q->semi_major);
    const float ratio = fmaxf(p->semi_major, q->semi_major) / fminf(p->semi_major, q->semi_major);
    const float rp = p->semi_minor / p->semi_major;
    const float rq = q->semi_minor / q->semi_major;
    const float dx = q->cx - p->cx;
    const float dy = q->cy - p->cy;
    const float dist = sqrtf((dx * dx) + (dy * dy));
    const float side = (m->wheelbase / m->wheel_radius) * am;
    const float dmax = 1.3f * ((m->wheelbase / m->wheel_radius) + 0.5f) * am;
    const float vmax = (0.6f * am) + (0.3f * fabsf(dx));
    float score = -1.0f;
    if ((ratio <= 1.6f) && (fabsf(rp - rq) <= 0.35f) && (dist >= (0.5f * am)) && (dist <= dmax) &&
        (fabsf(dy) <= vmax)) {
        score = (ratio - 1.0f) + fabsf(rp - rq) + (fabsf(dy) / am) + (fabsf(dist - side) / side);
    }
    return score;
}

/* Insert the pair (p, q) of score s into pairs[0 .. *kept), kept sorted best (lowest)
   first and at most cap long: a pair that falls off the end is dropped. */
static void insert_pair(sbr_wheel_pair_t *pairs, uint32_t cap, uint32_t *kept, const sbr_ellipse_t *p,
                        const sbr_ellipse_t *q, uint32_t first, uint32_t second, float s)
{
    uint32_t pos = *kept;
    while ((pos > 0u) && (pairs[pos - 1u].score > s)) {
        if (pos < cap) {
            pairs[pos] = pairs[pos - 1u];
        }
        pos--;
    }
    if (pos < cap) {
        pairs[pos].wheel[0] = *p;
        pairs[pos].wheel[1] = *q;
        pairs[pos].first = first;
        pairs[pos].second = second;
        pairs[pos].score = s;
        if (*kept < cap) {
            (*kept)++;
        }
    }
}

/* Pairs of groups, best first, at most cap; returns how many qualified in all. */
uint32_t sbr_bike_priv_pair_groups(const wheel_group_t *g, uint32_t ng, const sbr_bike_model_t *m,
                            sbr_wheel_pair_t *pairs, uint32_t cap)
{
    uint32_t total = 0u;
    uint32_t kept = 0u;
    uint32_t i;
    for (i = 0u; i < ng; ++i) {
        const sbr_ellipse_t p = sbr_bike_priv_group_ellipse(&g[i]);
        uint32_t j;
        for (j = i + 1u; j < ng; ++j) {
            const sbr_ellipse_t q = sbr_bike_priv_group_ellipse(&g[j]);
            const float s = pair_score(&p, &q, m);
            if (s >= 0.0f) {
                total++;
                insert_pair(pairs, cap, &kept, &p, &q, g[i].first, g[j].first, s);
            }
        }
    }
    return total;
}

sbr_status_t sbr_bike_pair_wheels(const sbr_ellipse_t *ellipses, uint32_t n,
                                  const sbr_bike_model_t *model, sbr_wheel_pair_t *pairs,
                                  uint32_t capacity, uint32_t *count)
{
    sbr_status_t st = SBR_OK;
    if ((model == NULL) || (count == NULL) || ((ellipses == NULL) && (n > 0u)) ||
        ((pairs == NULL) && (capacity > 0u))) {
        st = SBR_ERR_NULL;
    } else if (n > SBR_BIKE_MAX_ELLIPSES) {
        st = SBR_ERR_SIZE;
    } else if ((sbr_bike_priv_model_ok(model) == 0) || (sbr_bike_priv_ellipses_ok(ellipses, n) == 0)) {
        st = SBR_ERR_RANGE;
    } else {
        wheel_group_t g[SBR_BIKE_MAX_ELLIPSES];
        const uint32_t ng = sbr_bike_priv_group_ellipses(ellipses, n, g);
        const uint32_t total = sbr_bike_priv_pair_groups(g, ng, model, pairs, capacity);
        *count = (total < capacity) ? total : capacity;
        if (total > capacity) {
            st = SBR_ERR_CAPACITY;
        }
    }
    return st;
}
