// SPDX-License-Identifier: MIT
// sbr_conics: the conic methods of papers A and B on synthetic data with known truth.
//
//   sbr_conics [--torch] [--fit] [--bike] [--seed S] [--trials N] [--save DIR]
//
// --torch  (a) renders torchlight images (640x480, f = 500 px, principal point at the
//          image centre, beam radius R = 1) from known poses, with Gaussian pixel noise of
//          several levels (grey levels, sigma, on a beam of 220 over a background of 30);
//          sbr_ellipse_detect finds the beam's ellipse, sbr_torch_pose recovers n1, n2 and
//          Z0/R. Table: errors per noise level over all poses and noise draws.
// --fit    (b) samples noisy points of random ellipses and fits them with sbr_ellipse_fit,
//          OpenCV's fitEllipse and fitEllipseDirect on the very same points: centre, axis
//          and angle errors, and microseconds per fit (median of 5 timing rounds).
// --bike   (c) simulates paper B's scenarios (a bicycle crossing in front of the car, one
//          turning away, one braking) with the bicycle model, renders every frame
//          (1280x720, f = 1000 px, camera 1.2 m above the ground, 25 frames/s: the wheels'
//          tyres, 5 cm wide, drawn in exact perspective, dark on a sky/ground background,
//          Gaussian pixel noise), finds the ellipses with sbr_ellipse_detect, and runs
//          sbr_bike_pf_step on them. Table: state errors per scenario and noise level.
// Without --torch/--fit/--bike all run. --save DIR writes one torchlight image per noise level
// and a few annotated bicycle frames.
// Everything is seeded (--seed, default 1): the same numbers on every run, apart from times.
#include "cli_core.hpp"
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

extern "C" {
#include "sbr/bike.h"
#include "sbr/conic.h"
}

namespace {

constexpr double kPi = 3.14159265358979323846;

double wrap_pi(double a) {  // into (-pi/2, pi/2]
    while (a <= -kPi / 2) a += kPi;
    while (a > kPi / 2) a -= kPi;
    return a;
}

struct Pose {
    double n1, n2, z0r;
};

// Renders the lit beam: 4 x 4 supersampled coverage, then noise.
cv::Mat render_torch(const Pose &p, double f, double noise, std::mt19937 &rng) {
    const int w = 640, h = 480;
    const double px = (w - 1) / 2.0, py = (h - 1) / 2.0;
    cv::Mat img(h, w, CV_8U);
    std::normal_distribution<double> g(0.0, 1.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            int in = 0;
            for (int s = 0; s < 16; ++s) {
                const double xs = x - 0.375 + 0.25 * (s % 4) - px, ys = y - 0.375 + 0.25 * (s / 4) - py;
                const double den = f - p.n1 * xs - p.n2 * ys;
                if (den <= 0) continue;
                const double t = p.z0r / den;  // R = 1
                const double X = t * xs, Y = t * ys;
                in += (X * X + Y * Y <= 1.0) ? 1 : 0;
            }
            double v = 30.0 + 190.0 * in / 16.0 + (noise > 0 ? noise * g(rng) : 0.0);
            img.at<uint8_t>(y, x) = uint8_t(std::clamp(std::lround(v), 0L, 255L));
        }
    return img;
}

struct Stats {
    std::vector<double> v;
    void add(double x) { v.push_back(x); }
    double mean() const {
        double s = 0;
        for (double x : v) s += x;
        return v.empty() ? 0 : s / v.size();
    }
    double max() const { return v.empty() ? 0 : *std::max_element(v.begin(), v.end()); }
    double median() {
        if (v.empty()) return 0;
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    }
};

int run_torch(uint32_t seed, int trials, const std::string &save) {
    const double f = 500.0;
    const std::vector<Pose> poses = {{0.0, 0.0, 5.0},  {0.3, -0.2, 4.0}, {-0.5, 0.3, 6.0},
                                     {0.6, 0.5, 8.0},  {0.2, 0.6, 5.0},  {-0.4, -0.4, 4.0},
                                     {0.0, 0.7, 10.0}, {0.8, 0.0, 6.0}};
    const std::vector<double> noises = {0.0, 5.0, 10.0, 20.0, 40.0};
    sbr_ellipse_detect_config_t cfg;
    sbr_ellipse_detect_config_default(&cfg);
    cfg.mser.polarity = SBR_MSER_BRIGHT;
    cfg.mser.max_nodes = 200000;
    const size_t need = sbr_ellipse_detect_workspace_size(&cfg, 640, 480);
    std::vector<uint64_t> ws(need / 8 + 1);
    std::mt19937 rng(seed);
    std::printf("\n(a) torchlight pose from rendered images: %zu poses x %d noise draws per level, "
                "640x480, f = %.0f px, beam 220 on 30 (grey levels)\n\n", poses.size(), trials, f);
    std::printf("| noise sigma | poses solved | mean abs dn1 | max abs dn1 | mean abs dn2 | max abs dn2 "
                "| mean Z0/R error %% | max Z0/R error %% |\n|---|---|---|---|---|---|---|---|\n");
    bool zero_noise_ok = true;
    for (double noise : noises) {
        Stats d1, d2, dz;
        int solved = 0, total = 0;
        for (int t = 0; t < (noise == 0 ? 1 : trials); ++t)
            for (const Pose &p : poses) {
                ++total;
                cv::Mat img = render_torch(p, f, noise, rng);
                if (!save.empty() && t == 0 && &p == &poses[1])
                    cv::imwrite(save + "/torch_noise" + std::to_string(int(noise)) + ".png", img);
                const sbr_image_t view = {uint32_t(img.cols), uint32_t(img.rows), uint32_t(img.step),
                                          SBR_PIXEL_GRAY8, img.data};
                sbr_ellipse_det_t det[16];
                uint32_t n = 0;
                const sbr_status_t st = sbr_ellipse_detect(&view, &cfg, ws.data(), ws.size() * 8, det, 16, &n);
                if ((st != SBR_OK && st != SBR_ERR_CAPACITY) || n == 0) continue;
                // the beam: the largest ellipse
                uint32_t best = 0;
                for (uint32_t k = 1; k < n; ++k)
                    if (det[k].ellipse.semi_major * det[k].ellipse.semi_minor >
                        det[best].ellipse.semi_major * det[best].ellipse.semi_minor)
                        best = k;
                sbr_ellipse_t centred = det[best].ellipse;
                centred.cx -= float((img.cols - 1) / 2.0);
                centred.cy -= float((img.rows - 1) / 2.0);
                sbr_conic_t q;
                sbr_torch_pose_t pose;
                if (sbr_ellipse_to_conic(&centred, &q) != SBR_OK ||
                    sbr_torch_pose(&q, float(f), SBR_TORCH_MAX_RESIDUAL, &pose) != SBR_OK)
                    continue;
                ++solved;
                d1.add(std::fabs(pose.n1 - p.n1));
                d2.add(std::fabs(pose.n2 - p.n2));
                dz.add(100.0 * std::fabs(pose.z0_over_r - p.z0r) / p.z0r);
            }
        std::printf("| %.0f | %d/%d | %.4f | %.4f | %.4f | %.4f | %.3f | %.3f |\n", noise, solved, total,
                    d1.mean(), d1.max(), d2.mean(), d2.max(), dz.mean(), dz.max());
        if (noise == 0)
            zero_noise_ok = solved == total && d1.max() <= 0.01 && d2.max() <= 0.01 && dz.max() <= 1.0;
    }
    std::printf("\ntorch_zero_noise_target=%s (|dn1|, |dn2| <= 0.01 and Z0/R within 1%% for every pose)\n",
                zero_noise_ok ? "met" : "missed");
    return zero_noise_ok ? 0 : 1;
}

struct FitErr {
    Stats centre, axes, angle;
    int failed = 0;
};

void add_err(FitErr &e, double cx, double cy, double a, double b, double ang, const sbr_ellipse_t &t) {
    e.centre.add(std::hypot(cx - t.cx, cy - t.cy));
    e.axes.add(0.5 * (std::fabs(a - t.semi_major) + std::fabs(b - t.semi_minor)));
    if (t.semi_minor < 0.9f * t.semi_major) e.angle.add(std::fabs(wrap_pi(ang - t.angle)) * 180.0 / kPi);
}

// OpenCV's RotatedRect as semi-axes and the major axis's direction.
void from_box(const cv::RotatedRect &r, double &cx, double &cy, double &a, double &b, double &ang) {
    cx = r.center.x;
    cy = r.center.y;
    double w = r.size.width / 2.0, h = r.size.height / 2.0, t = r.angle * kPi / 180.0;
    if (w >= h) {
        a = w;
        b = h;
        ang = wrap_pi(t);
    } else {
        a = h;
        b = w;
        ang = wrap_pi(t + kPi / 2);
    }
}

int run_fit(uint32_t seed, int trials) {
    const std::vector<double> noises = {0.0, 0.5, 1.0, 2.0};
    const int npts = 100;
    std::mt19937 rng(seed + 1000);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    std::normal_distribution<double> G(0.0, 1.0);
    std::printf("\n(b) ellipse fit on the same noisy points: %d random ellipses per row (semi-axes 20..150 px, "
                "ratio 0.3..1), %d points each\n\n", trials, npts);
    std::printf("| arc | noise px | method | mean centre err px | mean axis err px | mean angle err deg "
                "| failed | us per fit |\n|---|---|---|---|---|---|---|---|\n");
    bool acc_ok = true, speed_ok = true;
    for (double arc : {360.0, 180.0})
        for (double noise : noises) {
            std::vector<sbr_ellipse_t> truth;
            std::vector<std::vector<sbr_pointf_t>> pts;
            std::vector<std::vector<cv::Point2f>> cvpts;
            for (int t = 0; t < trials; ++t) {
                sbr_ellipse_t e;
                e.cx = float(100 + 400 * U(rng));
                e.cy = float(100 + 300 * U(rng));
                e.semi_major = float(20 + 130 * U(rng));
                e.semi_minor = float(e.semi_major * (0.3 + 0.7 * U(rng)));
                e.angle = float(wrap_pi(kPi * U(rng)));
                truth.push_back(e);
                const double t0 = 2 * kPi * U(rng);
                std::vector<sbr_pointf_t> p;
                std::vector<cv::Point2f> c;
                for (int i = 0; i < npts; ++i) {
                    const double s = t0 + (arc * kPi / 180.0) * i / npts;
                    const double u = e.semi_major * std::cos(s), v = e.semi_minor * std::sin(s);
                    const double x = e.cx + u * std::cos(e.angle) - v * std::sin(e.angle) + noise * G(rng);
                    const double y = e.cy + u * std::sin(e.angle) + v * std::cos(e.angle) + noise * G(rng);
                    p.push_back({float(x), float(y)});
                    c.emplace_back(float(x), float(y));
                }
                pts.push_back(p);
                cvpts.push_back(c);
            }
            FitErr es, eo, ed;
            for (int t = 0; t < trials; ++t) {
                sbr_conic_t q;
                sbr_ellipse_t r;
                if (sbr_ellipse_fit(pts[t].data(), npts, &q, &r) == SBR_OK)
                    add_err(es, r.cx, r.cy, r.semi_major, r.semi_minor, r.angle, truth[t]);
                else
                    ++es.failed;
                double cx, cy, a, b, ang;
                from_box(cv::fitEllipse(cvpts[t]), cx, cy, a, b, ang);
                if (std::isfinite(a) && std::isfinite(b) && a > 0) add_err(eo, cx, cy, a, b, ang, truth[t]);
                else ++eo.failed;
                from_box(cv::fitEllipseDirect(cvpts[t]), cx, cy, a, b, ang);
                if (std::isfinite(a) && std::isfinite(b) && a > 0) add_err(ed, cx, cy, a, b, ang, truth[t]);
                else ++ed.failed;
            }
            // time: 5 rounds over all trials, the median round per fit
            auto time_us = [&](int which) {
                Stats rounds;
                volatile float sink = 0;
                for (int r = 0; r < 5; ++r) {
                    const auto t0 = std::chrono::steady_clock::now();
                    for (int t = 0; t < trials; ++t) {
                        if (which == 0) {
                            sbr_conic_t q;
                            sbr_ellipse_t e;
                            sbr_ellipse_fit(pts[t].data(), npts, &q, &e);
                            sink = sink + e.cx;
                        } else if (which == 1) {
                            sink = sink + cv::fitEllipse(cvpts[t]).center.x;
                        } else {
                            sink = sink + cv::fitEllipseDirect(cvpts[t]).center.x;
                        }
                    }
                    rounds.add(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() /
                               trials);
                }
                return rounds.median();
            };
            const double us_s = time_us(0), us_o = time_us(1), us_d = time_us(2);
            const char *names[3] = {"sbr_ellipse_fit", "cv::fitEllipse", "cv::fitEllipseDirect"};
            FitErr *errs[3] = {&es, &eo, &ed};
            const double us[3] = {us_s, us_o, us_d};
            for (int m = 0; m < 3; ++m)
                std::printf("| %.0f deg | %.1f | %s | %.4f | %.4f | %.4f | %d | %.2f |\n", arc, noise, names[m],
                            errs[m]->centre.mean(), errs[m]->axes.mean(), errs[m]->angle.mean(), errs[m]->failed,
                            us[m]);
            // accuracy at least fitEllipseDirect's (2 % slack for float32 vs double at zero noise)
            const double slack = 1.02, floor_px = 1e-3;
            if (es.centre.mean() > std::max(slack * ed.centre.mean(), floor_px) ||
                es.axes.mean() > std::max(slack * ed.axes.mean(), floor_px) || es.failed > ed.failed)
                acc_ok = false;
            if (us_s > us_d) speed_ok = false;
        }
    std::printf("\nfit_accuracy_vs_fitEllipseDirect=%s fit_speed_vs_fitEllipseDirect=%s\n", acc_ok ? "met" : "missed",
                speed_ok ? "met" : "missed");
    return acc_ok ? 0 : 1;
}


// ------------------------------------------------------------------ (c) bicycle

struct Scenario {
    const char *name;
    sbr_bike_state_t start;
    // control at time t: steering angle (set) and acceleration
    double (*steer)(double t);
    double (*accel)(double t);
};

double no_steer(double) { return 0.0; }
double no_accel(double) { return 0.0; }
double turn_steer(double t) { return t < 1.2 ? 0.0 : (t < 2.0 ? 0.3 * (t - 1.2) / 0.8 : 0.3); }
double brake_accel(double t) { return t >= 0.6 ? -3.0 : 0.0; }

// Draws a wheel's tyre (mid-line radius r, width w) in exact perspective, 4 x 4 supersampled.
void draw_tyre(cv::Mat &img, const sbr_camera_t &cam, double r, double w, double x, double z, double th,
               double roll, uint8_t tone) {
    const double dx = std::cos(th), dz = std::sin(th);
    const double ux = -std::sin(roll) * dz, uy = -std::cos(roll), uz = std::sin(roll) * dx;
    const double cx = x + r * ux, cy = cam.height + r * uy, cz = z + r * uz;
    // plane normal n = d x u
    const double nx = 0 * uz - dz * uy, ny = dz * ux - dx * uz, nz = dx * uy - 0 * ux;
    const double reach = (r + w) * cam.focal / std::max(0.5, cz - r - w);
    const double u0 = cam.focal * cx / cz + cam.cx, v0 = cam.focal * cy / cz + cam.cy;
    const int x0 = std::max(0, int(u0 - reach - 2)), x1 = std::min(img.cols - 1, int(u0 + reach + 2));
    const int y0 = std::max(0, int(v0 - reach - 2)), y1 = std::min(img.rows - 1, int(v0 + reach + 2));
    const double pc = nx * cx + ny * cy + nz * cz;
    for (int y = y0; y <= y1; ++y)
        for (int xx = x0; xx <= x1; ++xx) {
            int in = 0;
            for (int s = 0; s < 16; ++s) {
                const double rx = (xx - 0.375 + 0.25 * (s % 4) - cam.cx) / cam.focal;
                const double ry = (y - 0.375 + 0.25 * (s / 4) - cam.cy) / cam.focal;
                const double den = nx * rx + ny * ry + nz;
                if (std::fabs(den) < 1e-9) continue;
                const double t = pc / den;
                if (t <= 0) continue;
                const double px = t * rx - cx, py = t * ry - cy, pz = t - cz;
                const double a = px * dx + pz * dz, b = px * ux + py * uy + pz * uz;
                const double rho = std::sqrt(a * a + b * b);
                in += std::fabs(rho - r) <= w / 2 ? 1 : 0;
            }
            if (in) {
                uint8_t &p = img.at<uint8_t>(y, xx);
                p = uint8_t(std::lround((p * (16 - in) + tone * in) / 16.0));
            }
        }
}

cv::Mat render_bike(const sbr_camera_t &cam, const sbr_bike_model_t &m, const sbr_bike_state_t &s, double noise,
                    std::mt19937 &rng) {
    cv::Mat img(720, 1280, CV_8U);
    for (int y = 0; y < img.rows; ++y) img.row(y).setTo(y < cam.cy ? 175 : 120);  // sky, ground
    const double fx = s.x + m.wheelbase * std::cos(s.heading), fz = s.z + m.wheelbase * std::sin(s.heading);
    // the farther wheel first
    struct W { double x, z, th; } w[2] = {{s.x, s.z, s.heading}, {fx, fz, double(s.heading) + s.steer}};
    if (w[1].z > w[0].z) std::swap(w[0], w[1]);
    for (const W &k : w) draw_tyre(img, cam, m.wheel_radius, 0.05, k.x, k.z, k.th, s.roll, 35);
    if (noise > 0) {
        std::normal_distribution<double> g(0.0, noise);
        for (int y = 0; y < img.rows; ++y)
            for (int x = 0; x < img.cols; ++x) {
                uint8_t &p = img.at<uint8_t>(y, x);
                p = uint8_t(std::clamp(std::lround(p + g(rng)), 0L, 255L));
            }
    }
    return img;
}

double ellipse_dist(const sbr_ellipse_t &a, const sbr_ellipse_t &b) {
    return std::hypot(a.cx - b.cx, a.cy - b.cy) + std::fabs(a.semi_major - b.semi_major);
}

int run_bike(uint32_t seed, int runs, const std::string &save) {
    const Scenario scenarios[3] = {
        {"crossing", {-7.0f, 12.0f, 0.0f, 4.0f, 0.0f, 0.0f}, no_steer, no_accel},
        {"turning", {-6.0f, 10.0f, 0.1f, 4.0f, 0.0f, 0.0f}, turn_steer, no_accel},
        {"braking", {-5.0f, 10.0f, -0.1f, 5.0f, 0.0f, 0.0f}, no_steer, brake_accel},
    };
    const std::vector<double> noises = {0.0, 8.0, 16.0};
    const int frames = 88;  // 3.5 s at 25 frames/s
    const float dt = 0.04f;
    const uint32_t dt_us = 40000u;  // dt as the core takes it
    const int settle = 10;   // position errors from frame 10 (0.4 s) on
    const int settled = 38;  // all state errors from frame 38 (1.5 s) on
    sbr_bike_pf_config_t pcfg;
    sbr_bike_pf_config_default(&pcfg);
    std::vector<uint32_t> pws(sbr_bike_pf_workspace_size(&pcfg) / sizeof(uint32_t));
    sbr_ellipse_detect_config_t dcfg;
    sbr_ellipse_detect_config_default(&dcfg);
    dcfg.mser.max_nodes = 400000;
    const size_t need = sbr_ellipse_detect_workspace_size(&dcfg, 1280, 720);
    std::vector<uint64_t> dws(need / 8 + 1);
    std::printf("\n(c) bicycle tracking from rendered wheel ellipses: %d frames (25/s) per run, %d filter run(s) "
                "per row (seeds %u..), %u particles; tyres 35 on sky 175 / ground 120, noise sigma in grey levels; "
                "RMSE of the position (rear contact point) from frame %d (0.4 s) on, of every state from "
                "frame %d (1.5 s) on, once the motion has told the heading\n\n",
                frames, runs, seed, pcfg.particles, settle, settled);
    std::printf("| scenario | noise | frames with both wheels | wheel association correct | position RMSE m "
                "| settled: position m | heading deg | speed m/s | steering deg | roll deg | detect ms/frame "
                "| filter us/step |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    bool crossing_ok = true;
    double crossing_worst = 0;
    for (const Scenario &sc : scenarios)
        for (double noise : noises) {
            double se_p = 0, se_p2 = 0, se_h = 0, se_v = 0, se_d = 0, se_r = 0;
            long n_err = 0, n_set = 0, both = 0, assoc_ok = 0, assoc_n = 0, total = 0;
            Stats det_ms, pf_us;
            for (int run = 0; run < runs; ++run) {
                std::mt19937 rng(seed * 7919u + uint32_t(run) * 104729u + uint32_t(noise * 10));
                pcfg.seed = seed + uint32_t(run);
                sbr_bike_pf_t pf;
                if (sbr_bike_pf_init(&pf, &pcfg, pws.data(), pws.size() * sizeof(uint32_t)) != SBR_OK)
                    return 1;
                sbr_bike_state_t t = sc.start;
                for (int k = 0; k < frames; ++k) {
                    const double tm = k * dt;
                    if (k > 0) {
                        t.steer = float(sc.steer(tm));
                        sbr_bike_predict_state(&pcfg.model, &t, dt_us, &t);
                        t.speed = float(std::max(0.0, t.speed + sc.accel(tm) * dt));
                    }
                    cv::Mat img = render_bike(pcfg.camera, pcfg.model, t, noise, rng);
                    const sbr_image_t view = {uint32_t(img.cols), uint32_t(img.rows), uint32_t(img.step),
                                              SBR_PIXEL_GRAY8, img.data};
                    sbr_ellipse_det_t det[64];
                    uint32_t n = 0;
                    auto t0 = std::chrono::steady_clock::now();
                    const sbr_status_t st = sbr_ellipse_detect(&view, &dcfg, dws.data(), dws.size() * 8, det, 64, &n);
                    auto t1 = std::chrono::steady_clock::now();
                    det_ms.add(std::chrono::duration<double, std::milli>(t1 - t0).count());
                    if (st != SBR_OK && st != SBR_ERR_CAPACITY) n = 0;
                    sbr_ellipse_t el[SBR_BIKE_MAX_ELLIPSES];
                    const uint32_t ne = std::min<uint32_t>(n, SBR_BIKE_MAX_ELLIPSES);
                    for (uint32_t i = 0; i < ne; ++i) el[i] = det[i].ellipse;
                    sbr_bike_result_t res;
                    t0 = std::chrono::steady_clock::now();
                    if (sbr_bike_pf_step(&pf, dt_us, el, ne, &res) != SBR_OK) return 1;
                    t1 = std::chrono::steady_clock::now();
                    pf_us.add(std::chrono::duration<double, std::micro>(t1 - t0).count());
                    ++total;
                    sbr_ellipse_t tr, tf;
                    const bool visible = sbr_bike_project(&pcfg.camera, &pcfg.model, &t, &tr, &tf) == SBR_OK;
                    if (res.wheels == 3u) {
                        ++both;
                        if (visible) {
                            ++assoc_n;
                            if (ellipse_dist(res.rear, tr) < ellipse_dist(res.rear, tf)) ++assoc_ok;
                        }
                    }
                    if (!save.empty() && run == 0 && noise == noises[1] && k % 20 == 0) {
                        cv::Mat out;
                        cv::cvtColor(img, out, cv::COLOR_GRAY2BGR);
                        sbr_ellipse_t er, ef;
                        if ((res.flags & SBR_BIKE_TRACKING) &&
                            sbr_bike_project(&pcfg.camera, &pcfg.model, &res.mean, &er, &ef) == SBR_OK) {
                            for (const auto &[e, col] : {std::pair{er, cv::Scalar(0, 0, 255)},
                                                         std::pair{ef, cv::Scalar(0, 200, 0)}})
                                cv::ellipse(out, cv::Point2f(e.cx, e.cy), cv::Size2f(e.semi_major, e.semi_minor),
                                            e.angle * 180.0 / kPi, 0, 360, col, 1, cv::LINE_AA);
                        }
                        cv::imwrite(save + "/bike_" + sc.name + "_" + std::to_string(k) + ".png", out);
                    }
                    if (k >= settle) {
                        // no estimate counts as a 10 m miss
                        const bool est = (res.flags & SBR_BIKE_TRACKING) != 0;
                        const double dp = est ? std::hypot(res.mean.x - t.x, res.mean.z - t.z) : 10.0;
                        se_p += dp * dp;
                        ++n_err;
                        if (k >= settled) {
                            const double dh = est ? std::remainder(double(res.mean.heading) - t.heading, 2 * kPi) : kPi;
                            se_p2 += dp * dp;
                            se_h += dh * dh;
                            se_v += est ? (res.mean.speed - t.speed) * (res.mean.speed - t.speed) : 100.0;
                            se_d += est ? (res.mean.steer - t.steer) * (res.mean.steer - t.steer) : 1.0;
                            se_r += est ? (res.mean.roll - t.roll) * (res.mean.roll - t.roll) : 1.0;
                            ++n_set;
                        }
                    }
                }
            }
            const double rp = std::sqrt(se_p / n_err), rd = 180.0 / kPi;
            std::printf("| %s | %.0f | %ld/%ld | %ld/%ld | %.3f | %.3f | %.2f | %.3f | %.2f | %.2f | %.1f | %.0f |\n",
                        sc.name, noise, both, total, assoc_ok, assoc_n, rp, std::sqrt(se_p2 / n_set),
                        std::sqrt(se_h / n_set) * rd, std::sqrt(se_v / n_set), std::sqrt(se_d / n_set) * rd,
                        std::sqrt(se_r / n_set) * rd, det_ms.median(), pf_us.median());
            if (std::string(sc.name) == "crossing") {
                crossing_worst = std::max(crossing_worst, rp);
                if (rp > 0.3) crossing_ok = false;
            }
        }
    std::printf("\nbike_crossing_target=%s (position RMSE <= 0.3 m at every noise level; worst %.3f m)\n",
                crossing_ok ? "met" : "missed", crossing_worst);
    return crossing_ok ? 0 : 1;
}
}  // namespace

int main(int argc, char **argv) {
    bool torch = false, fit = false, bike = false;
    uint32_t seed = 1;
    int trials = 200;
    std::string save;
    CLI::App app{"sbr_conics: conics on synthetic data (docs/usage/conics.md); without --torch/--fit/--bike "
                 "all three"};
    app.add_flag("--torch", torch, "torchlight pose from rendered beams (paper A)");
    app.add_flag("--fit", fit, "ellipse fit against OpenCV's fitEllipseDirect");
    app.add_flag("--bike", bike, "bicycle tracking from rendered wheel ellipses (paper B)");
    app.add_option("--seed", seed, "random seed")->capture_default_str();
    app.add_option("--trials", trials, "trials (torch: /50, bike: /100)")
        ->check(CLI::Range(1, 10000000))
        ->capture_default_str();
    app.add_option("--save", save, "folder for rendered example frames");
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    if (!torch && !fit && !bike) torch = fit = bike = true;
    int rc = 0;
    if (torch) rc |= run_torch(seed, std::max(1, trials / 50), save);
    if (fit) rc |= run_fit(seed, trials);
    if (bike) rc |= run_bike(seed, std::max(1, trials / 100), save);
    return rc;
}
