// SPDX-License-Identifier: MIT
// sbr_servo: visual servoing of a simulated low-cost 5-joint arm with an inverse image
// Jacobian learned from the arm's own random motions (paper F; include/sbr/servo.h).
//
//   sbr_servo [--learn N] [--trials T] [--seed S] [--csv] [--save DIR] [--curve]
//
// The arm (unknown to the learner): base yaw, shoulder, elbow and wrist pitch, wrist roll;
// link lengths and joint offsets drawn per seed, servos with backlash and a command-
// dependent gain error. A pinhole camera (640 x 480, f = 500 px) looks down on it over a
// textured table; frames get Gaussian pixel noise. The gripper carries a flat, asymmetric
// plate at its tip, facing along the gripper's axis.
//
// 1. Recognition by motion ("action precedes perception"): from 40 frames of random
//    configurations, the per-pixel median is the background (what does not move); in
//    each frame, what differs from it and survives an opening by a 7 px disc (the thin
//    links do not) is a moving blob; the blobs' Fourier descriptors (sbr_fd) are clustered by
//    rotation-invariant match error, and the largest cluster's medoid becomes the
//    gripper's prototype; the median colour of the cluster's interiors is the plate's.
//    From then on each blob is measured to sub-pixel accuracy: each pixel's coverage by
//    the plate (from frame, background and plate colour) gives the centroid and, traced at
//    coverage 0.5, the outline whose descriptor is matched (the prototype is re-learned from
//    the refined cluster). Later frames find the gripper by sbr_fd_match against it:
//    the features are its centroid (u, v) and the match's rotation (theta).
// 2. Learning: N random motions (random walks from random configurations), each pair
//    (command, command change, feature change seen through recognition) into
//    sbr_servo_learn().
// 3. Trials: T targets, each the gripper's image pose recognised in a frame rendered at a
//    random reachable configuration; from the home configuration, servo steps until the
//    features are within tolerance or 30 steps. Methods, all with the same step rule (gain,
//    trust bound, joint limits) and the same recognised features: (a) learned (sbr_servo,
//    learning its executed steps as it goes), (b) the image Jacobian of the true model
//    (central differences, its pseudo-inverse: an oracle), (c) the same of a miscalibrated
//    model (links +-10 %, joint offsets +-5 deg), (d) Broyden's update of the image
//    Jacobian from a scaled identity start. Success: the true gripper centroid within 1 px
//    of the target's and its orientation within 2 deg, within 30 steps.
// --csv: method,success_rate,median_err_px,p95_err_px,median_iters; then the recognition
// rate and the learner's workspace and time per call. --curve: the learned method's
// success rate for N = 250, 500, 1000, 2000. --save DIR: frames of the first runs with the
// target and the path. Seeded: the same numbers on every run, apart from times.
#include "cli_core.hpp"
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

extern "C" {
#include "sbr/contour.h"
#include "sbr/fd.h"
#include "sbr/fft.h"
#include "sbr/servo.h"
}

namespace {

constexpr int kJ = 5, kF = 3, kW = 640, kH = 480;
constexpr double kPi = 3.14159265358979323846;
constexpr double kFocal = 500.0;
using Q = std::array<double, kJ>;
using X = std::array<double, kF>;

const Q kMin = {-0.9, 0.15, -2.3, -1.9, -1.6};
const Q kMax = {0.9, 1.25, -0.7, -0.3, 1.6};
const Q kHome = {0.0, 0.7, -1.5, -0.9, 0.0};

double wrap(double a) {
    while (a <= -kPi) a += 2 * kPi;
    while (a > kPi) a -= 2 * kPi;
    return a;
}

struct Vec3 {
    double x, y, z;
};
Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// The arm's geometry; `truth` also has the servos' imperfections.
struct Arm {
    double base = 0.12, l1 = 0.22, l2 = 0.20, l3 = 0.09;
    Q offset{};
    Q gain_err{}, gain_slope{};
    double backlash = 0.004;

    // The joint angles a command gives (servo gain error; backlash is in Servos).
    Q angles(const Q &c) const {
        Q a;
        for (int j = 0; j < kJ; ++j) a[j] = offset[j] + c[j] * (1.0 + gain_err[j] + gain_slope[j] * c[j]);
        return a;
    }
    // Joint positions and the tip frame (tip, gripper axis, jaw direction) from angles.
    void pose(const Q &a, std::vector<Vec3> &joints, Vec3 &axis, Vec3 &jaw) const {
        const double t1 = a[1], t2 = a[1] + a[2], t3 = a[1] + a[2] + a[3];
        const double c0 = std::cos(a[0]), s0 = std::sin(a[0]);
        auto at = [&](double r, double z) { return Vec3{r * c0, r * s0, z}; };
        const double r1 = l1 * std::cos(t1), z1 = base + l1 * std::sin(t1);
        const double r2 = r1 + l2 * std::cos(t2), z2 = z1 + l2 * std::sin(t2);
        const double r3 = r2 + l3 * std::cos(t3), z3 = z2 + l3 * std::sin(t3);
        joints = {at(0, 0), at(0, base), at(r1, z1), at(r2, z2), at(r3, z3)};
        axis = {std::cos(t3) * c0, std::cos(t3) * s0, std::sin(t3)};
        const Vec3 p0 = {-s0, c0, 0.0};
        const Vec3 p1 = cross(axis, p0);
        jaw = std::cos(a[4]) * p0 + std::sin(a[4]) * p1;
    }
};

// The camera: 1.0 m above the table at (0.25, 0), looking straight down; u along world y.
cv::Point2d project(const Vec3 &p) {
    const double d = 1.0 - p.z;
    return {kW / 2.0 + kFocal * p.y / d, kH / 2.0 + kFocal * (p.x - 0.25) / d};
}

// The gripper's plate: an asymmetric outline in the plane across the gripper axis
// (metres, x along the jaw, y across it).
const std::vector<cv::Point2d> kPlate = {{0.05, -0.018}, {0.05, 0.018}, {-0.015, 0.018}, {-0.015, 0.045},
                                         {-0.045, 0.045}, {-0.045, -0.03}, {-0.015, -0.03}, {-0.015, -0.018}};

std::vector<cv::Point2d> plate_image(const Arm &arm, const Q &angles) {
    std::vector<Vec3> j;
    Vec3 axis, jaw;
    arm.pose(angles, j, axis, jaw);
    const Vec3 side = cross(axis, jaw);
    std::vector<cv::Point2d> out;
    for (const auto &p : kPlate) out.push_back(project(j.back() + p.x * jaw + p.y * side));
    return out;
}

// A closed polygon's twice signed area and area centroid (shoelace sums); points with
// members x and y.
template <typename P>
double shoelace(const P *pts, size_t n, double &cx, double &cy) {
    double a = 0;
    cx = cy = 0;
    for (size_t i = 0; i < n; ++i) {
        const P &p = pts[i], &q = pts[(i + 1) % n];
        const double c = double(p.x) * double(q.y) - double(q.x) * double(p.y);
        a += c;
        cx += (double(p.x) + double(q.x)) * c;
        cy += (double(p.y) + double(q.y)) * c;
    }
    cx /= 3 * a;
    cy /= 3 * a;
    return a;
}

// The plate's image pose from the model: the projected plate's area centroid and the image
// angle of its jaw direction (the trials judge the angle by World::truth_now()).
X true_features(const Arm &arm, const Q &angles) {
    const auto poly = plate_image(arm, angles);
    double cx, cy;
    shoelace(poly.data(), poly.size(), cx, cy);
    std::vector<Vec3> j;
    Vec3 axis, jaw;
    arm.pose(angles, j, axis, jaw);
    const cv::Point2d t0 = project(j.back()), t1 = project(j.back() + 0.03 * jaw);
    return {cx, cy, std::atan2(t1.y - t0.y, t1.x - t0.x)};
}

// Servos with backlash: each joint's effective command follows the given one only beyond
// a dead band.
struct Servos {
    Q eff{};
    double band = 0.0;
    void set(const Q &c) {
        for (int j = 0; j < kJ; ++j) {
            if (c[j] > eff[j] + band) eff[j] = c[j] - band;
            if (c[j] < eff[j] - band) eff[j] = c[j] + band;
        }
    }
};

struct Scene {
    cv::Mat table;  // BGR texture
    std::mt19937 noise_rng;
    double noise = 3.0;

    explicit Scene(uint32_t seed) : noise_rng(seed + 7) {
        std::mt19937 r(seed);
        cv::Mat small(kH / 16, kW / 16, CV_8UC3);
        for (int y = 0; y < small.rows; ++y)
            for (int x = 0; x < small.cols; ++x)
                small.at<cv::Vec3b>(y, x) = cv::Vec3b(uint8_t(90 + r() % 60), uint8_t(100 + r() % 50), uint8_t(80 + r() % 60));
        cv::resize(small, table, cv::Size(kW, kH), 0, 0, cv::INTER_CUBIC);
        for (int k = 0; k < 60; ++k)  // grain and specks
            cv::circle(table, cv::Point(int(r() % kW), int(r() % kH)), int(2 + r() % 6),
                       cv::Scalar(double(60 + r() % 80), double(60 + r() % 80), double(60 + r() % 80)), -1,
                       cv::LINE_AA);
    }

    cv::Mat render(const Arm &arm, const Q &angles) {
        cv::Mat img = table.clone();
        std::vector<Vec3> j;
        Vec3 axis, jaw;
        arm.pose(angles, j, axis, jaw);
        for (size_t k = 1; k + 1 < j.size(); ++k)
            cv::line(img, project(j[k]), project(j[k + 1]), cv::Scalar(45, 45, 50), 2, cv::LINE_AA);
        const auto poly = plate_image(arm, angles);
        std::vector<cv::Point> ip;
        for (const auto &p : poly) ip.emplace_back(int(std::lround(p.x * 16)), int(std::lround(p.y * 16)));
        const cv::Point *pts = ip.data();
        const int n = int(ip.size());
        cv::fillPoly(img, &pts, &n, 1, cv::Scalar(30, 140, 235), cv::LINE_AA, 4);
        cv::Mat g(img.size(), CV_16SC3);
        cv::randn(g, 0.0, noise);
        cv::Mat out;
        img.convertTo(out, CV_16SC3);
        out += g;
        out.convertTo(img, CV_8UC3);
        return img;
    }
};

// A blob: its descriptor, area and area centroid (of its traced boundary polygon, or after
// GripperFinder::refine() of its coverage), and the frame around it with its filled outline.
struct Blob {
    sbr_fd_t fd;
    double area, cx, cy;
    cv::Rect roi;
    cv::Mat crop, mask;
};

// The recogniser of the gripper: background model, blob extraction, prototype.
class GripperFinder {
public:
    GripperFinder() {
        sbr_fft_init(&fft_n_, 128);
        sbr_fft_init(&fft_p_, 64);
        ws_.resize(sbr_contour_workspace_size(kW, kH));
        pts_.resize(64 * 1024);
        cont_.resize(256);
    }
    // The background: per pixel and channel, the median of frames of random poses.
    void set_background(const std::vector<cv::Mat> &frames) {
        bg_.create(kH, kW, CV_8UC3);
        std::vector<uint8_t> v(frames.size());
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                for (int c = 0; c < 3; ++c) {
                    for (size_t k = 0; k < frames.size(); ++k) v[k] = frames[k].at<cv::Vec3b>(y, x)[c];
                    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
                    bg_.at<cv::Vec3b>(y, x)[c] = v[v.size() / 2];
                }
    }
    // Moving blobs of a frame: a channel differs from the background by more than 40, and
    // the pixel survives an opening by a 7 px disc (the thin links do not).
    std::vector<Blob> blobs(const cv::Mat &frame) {
        cv::Mat d, m;
        cv::absdiff(frame, bg_, d);
        std::vector<cv::Mat> ch;
        cv::split(d, ch);
        cv::max(ch[0], ch[1], m);
        cv::max(m, ch[2], m);
        cv::threshold(m, m, 40, 255, cv::THRESH_BINARY);
        // the opening (a disc: the same for every orientation) drops the thin links
        cv::morphologyEx(m, m, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_ELLIPSE, {7, 7}));
        sbr_image_t v{uint32_t(kW), uint32_t(kH), uint32_t(m.step[0]), SBR_PIXEL_GRAY8, m.data};
        uint32_t n = 0;
        std::vector<Blob> out;
        const sbr_status_t st = sbr_contour_find_external(&v, ws_.data(), ws_.size(), pts_.data(), uint32_t(pts_.size()),
                                                          cont_.data(), uint32_t(cont_.size()), &n);
        if (st != SBR_OK && st != SBR_ERR_CAPACITY) return out;
        std::vector<sbr_complex_t> work(128);
        for (uint32_t k = 0; k < n; ++k) {
            const sbr_contour_t &c = cont_[k];
            if (c.length < 30) continue;
            Blob b{};
            b.area = std::fabs(shoelace(&pts_[c.first], c.length, b.cx, b.cy)) / 2;
            if (b.area < 150 || b.area > 20000) continue;
            if (sbr_fd_from_points(&fft_n_, &pts_[c.first], c.length, 12, work.data(), 128, &b.fd) != SBR_OK) continue;
            std::vector<cv::Point> poly;
            for (uint32_t i = 0; i < c.length; ++i) poly.emplace_back(pts_[c.first + i].x, pts_[c.first + i].y);
            b.roi = (cv::boundingRect(poly) + cv::Size(2 * kMargin, 2 * kMargin) - cv::Point(kMargin, kMargin)) &
                    cv::Rect(0, 0, kW, kH);
            b.crop = frame(b.roi).clone();
            b.mask = cv::Mat::zeros(b.roi.size(), CV_8U);
            for (auto &p : poly) p -= b.roi.tl();
            cv::fillPoly(b.mask, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(255));
            out.push_back(b);
        }
        return out;
    }
    // Sub-pixel measurement of a blob once the plate's colour is known: each pixel's
    // coverage by the plate, alpha = (F - B) . (P - B) / |P - B|^2 clamped to [0, 1] (F the
    // frame, B the background, P the plate's colour), within 3 px of the blob's opened
    // outline (the opening cut its corners; the links' dark grey gets alpha 0). The
    // centroid is the coverage-weighted mean, the descriptor that of the alpha = 0.5
    // boundary traced on the coverage upsampled 4 x (bilinear). False when it fails.
    bool refine(Blob &b) {
        if (!have_colour_) return true;
        cv::Mat region, alpha(b.roi.size(), CV_32F, cv::Scalar(0));
        cv::dilate(b.mask, region, cv::getStructuringElement(cv::MORPH_ELLIPSE, {7, 7}));
        double s = 0, sx = 0, sy = 0;
        for (int y = 0; y < b.roi.height; ++y)
            for (int x = 0; x < b.roi.width; ++x) {
                if (!region.at<uint8_t>(y, x)) continue;
                const cv::Vec3b f = b.crop.at<cv::Vec3b>(y, x), g = bg_.at<cv::Vec3b>(b.roi.y + y, b.roi.x + x);
                double dot = 0, nn = 0;
                for (int c = 0; c < 3; ++c) {
                    const double d = plate_[c] - g[c];
                    dot += (f[c] - g[c]) * d;
                    nn += d * d;
                }
                // where the table has the plate's colour, coverage is the opened mask's
                const double a = nn < 400 ? (b.mask.at<uint8_t>(y, x) ? 1.0 : 0.0) : std::clamp(dot / nn, 0.0, 1.0);
                alpha.at<float>(y, x) = float(a);
                s += a;
                sx += a * (b.roi.x + x);
                sy += a * (b.roi.y + y);
            }
        if (s < 100) return false;
        cv::Mat up, bin;
        cv::resize(alpha, up, b.roi.size() * kUp, 0, 0, cv::INTER_LINEAR);
        cv::compare(up, 0.5, bin, cv::CMP_GT);
        sub_ws_.resize(sbr_contour_workspace_size(uint32_t(bin.cols), uint32_t(bin.rows)));
        sbr_image_t v{uint32_t(bin.cols), uint32_t(bin.rows), uint32_t(bin.step[0]), SBR_PIXEL_GRAY8, bin.data};
        uint32_t n = 0;
        const sbr_status_t st = sbr_contour_find_external(&v, sub_ws_.data(), sub_ws_.size(), pts_.data(),
                                                          uint32_t(pts_.size()), cont_.data(), uint32_t(cont_.size()), &n);
        if ((st != SBR_OK && st != SBR_ERR_CAPACITY) || n == 0) return false;
        const sbr_contour_t *longest = &cont_[0];
        for (uint32_t k = 1; k < n; ++k)
            if (cont_[k].length > longest->length) longest = &cont_[k];
        std::vector<sbr_pointf_t> fp;  // back to frame pixels (the resize's pixel-centre mapping)
        for (uint32_t i = 0; i < longest->length; ++i) {
            const sbr_point_t &p = pts_[longest->first + i];
            fp.push_back({float(b.roi.x + (p.x + 0.5) / kUp - 0.5), float(b.roi.y + (p.y + 0.5) / kUp - 0.5)});
        }
        std::vector<sbr_complex_t> work(128);
        if (sbr_fd_from_pointsf(&fft_n_, fp.data(), uint32_t(fp.size()), 12, work.data(), 128, &b.fd) != SBR_OK)
            return false;
        b.area = s;
        b.cx = sx / s;
        b.cy = sy / s;
        return true;
    }
    // The prototype: the medoid of the largest cluster of blobs by invariant match error;
    // the plate's colour: the per-channel median of the cluster's interiors (2 px inside
    // their outlines); then the cluster refined with it and its medoid again.
    bool learn_prototype(std::vector<Blob> all) {
        if (all.empty()) return false;
        std::vector<size_t> members;
        proto_ = all[medoid(all, members)].fd;
        cluster_ = members.size();
        std::vector<double> ch[3];
        for (size_t i : members) {
            cv::Mat inner;
            cv::erode(all[i].mask, inner, cv::getStructuringElement(cv::MORPH_ELLIPSE, {5, 5}));
            if (cv::countNonZero(inner) == 0) continue;
            const cv::Scalar m = cv::mean(all[i].crop, inner);
            for (int c = 0; c < 3; ++c) ch[c].push_back(m[c]);
        }
        if (ch[0].empty()) return true;  // the opened outlines then
        for (int c = 0; c < 3; ++c) {
            std::nth_element(ch[c].begin(), ch[c].begin() + long(ch[c].size() / 2), ch[c].end());
            plate_[c] = ch[c][ch[c].size() / 2];
        }
        have_colour_ = true;
        std::vector<Blob> refined;
        for (size_t i : members)
            if (refine(all[i])) refined.push_back(all[i]);
        if (!refined.empty()) proto_ = refined[medoid(refined, members)].fd;
        return true;
    }
    size_t cluster_size() const { return cluster_; }
    // The orientation of an exact outline (image polygon, any direction): the rotation of
    // its descriptor against the prototype, the same measure as find()'s without pixels,
    // noise or the opening. NaN when it cannot be computed.
    double outline_rotation(std::vector<cv::Point2d> poly) {
        double cx, cy;
        if (shoelace(poly.data(), poly.size(), cx, cy) > 0) std::reverse(poly.begin(), poly.end());  // traced contours run this way
        std::vector<sbr_pointf_t> dense;
        for (size_t i = 0; i < poly.size(); ++i)
            for (int k = 0; k < 64; ++k) {
                const cv::Point2d p = poly[i] + (poly[(i + 1) % poly.size()] - poly[i]) * (k / 64.0);
                dense.push_back({float(p.x), float(p.y)});
            }
        std::vector<sbr_complex_t> work(128);
        sbr_fd_t fd;
        if (sbr_fd_from_pointsf(&fft_n_, dense.data(), uint32_t(dense.size()), 12, work.data(), 128, &fd) != SBR_OK)
            return NAN;
        sbr_fd_match_config_t cfg;
        sbr_fd_match_config_default(&cfg);
        cfg.mode = SBR_FD_ROTATION_INVARIANT;
        sbr_fd_match_t r;
        if (sbr_fd_match(&fft_p_, &cfg, &fd, &proto_, work.data(), 64, &r) != SBR_OK) return NAN;
        return r.rotation;
    }
    // The gripper's features in a frame: the blob that matches the prototype best
    // (rotation invariant, error < 0.35: a tilted plate is foreshortened): centroid and rotation. False when none does.
    bool find(const cv::Mat &frame, X &x) {
        const auto bl = blobs(frame);
        sbr_fd_match_config_t cfg;
        sbr_fd_match_config_default(&cfg);
        cfg.mode = SBR_FD_ROTATION_INVARIANT;  // the rotation is the feature: any is allowed
        std::vector<sbr_complex_t> work(64);
        double best = 0.35;
        bool found = false;
        for (auto b : bl) {
            if (!refine(b)) continue;
            sbr_fd_match_t r;
            if (sbr_fd_match(&fft_p_, &cfg, &b.fd, &proto_, work.data(), 64, &r) != SBR_OK) continue;
            if (r.error < best) {
                best = r.error;
                x = {b.cx, b.cy, r.rotation};
                found = true;
            }
        }
        return found;
    }

private:
    static constexpr int kMargin = 6, kUp = 4;
    // The blob with the most others within invariant match error 0.1 (ties: the smaller
    // sum of errors); `members` gets those others.
    size_t medoid(const std::vector<Blob> &all, std::vector<size_t> &members) {
        sbr_fd_match_config_t cfg;
        sbr_fd_match_config_default(&cfg);
        cfg.mode = SBR_FD_ROTATION_INVARIANT;
        std::vector<sbr_fd_t> table;
        for (const auto &b : all) table.push_back(b.fd);
        std::vector<sbr_fd_match_t> res(table.size());
        std::vector<sbr_complex_t> work(SBR_FD_TABLE_WORK_LEN(64));
        size_t best = 0, best_n = 0;
        double best_sum = 1e30;
        for (size_t i = 0; i < all.size(); ++i) {
            uint32_t bi = 0;
            sbr_fd_match_table(&fft_p_, &cfg, &table[i], table.data(), uint32_t(table.size()), work.data(),
                               uint32_t(work.size()), res.data(), &bi);
            size_t n = 0;
            double sum = 0;
            for (const auto &r : res)
                if (r.error < 0.1f) ++n, sum += r.error;
            if (n > best_n || (n == best_n && sum < best_sum)) best = i, best_n = n, best_sum = sum;
        }
        uint32_t bi0 = 0;
        sbr_fd_match_table(&fft_p_, &cfg, &table[best], table.data(), uint32_t(table.size()), work.data(),
                           uint32_t(work.size()), res.data(), &bi0);
        members.clear();
        for (size_t i = 0; i < res.size(); ++i)
            if (res[i].error < 0.1f) members.push_back(i);
        return best;
    }

    sbr_fft_t fft_n_{}, fft_p_{};
    std::vector<uint8_t> ws_;
    std::vector<sbr_point_t> pts_;
    std::vector<sbr_contour_t> cont_;
    cv::Mat bg_;
    sbr_fd_t proto_{};
    size_t cluster_ = 0;
    double plate_[3] = {0, 0, 0};
    bool have_colour_ = false;
    std::vector<uint8_t> sub_ws_;
};

using Mat35 = std::array<std::array<double, kJ>, kF>;  // an image Jacobian (3 x 5)
using Mat53 = std::array<std::array<double, kF>, kJ>;  // an inverse (5 x 3)

// Right pseudo-inverse A^T (A A^T + damping I)^-1 of a 3 x 5 image Jacobian.
Mat53 pinv(const Mat35 &a) {
    double m[3][3];
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) {
            m[i][k] = (i == k) ? 1e-9 : 0.0;
            for (int j = 0; j < kJ; ++j) m[i][k] += a[i][j] * a[k][j];
        }
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    double inv[3][3];
    inv[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
    inv[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    inv[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    inv[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
    inv[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    inv[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    inv[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
    inv[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    inv[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
    Mat53 r{};
    for (int j = 0; j < kJ; ++j)
        for (int k = 0; k < 3; ++k)
            for (int i = 0; i < 3; ++i) r[j][k] += a[i][j] * inv[i][k];
    return r;
}

// The image Jacobian of a model (its features of a command) by central differences.
Mat35 model_jacobian(const Arm &arm, const Q &c) {
    Mat35 a{};
    const double h = 1e-4;
    for (int j = 0; j < kJ; ++j) {
        Q p = c, m = c;
        p[j] += h;
        m[j] -= h;
        const X xp = true_features(arm, arm.angles(p)), xm = true_features(arm, arm.angles(m));
        for (int i = 0; i < kF; ++i) a[i][j] = (i == 2 ? wrap(xp[i] - xm[i]) : xp[i] - xm[i]) / (2 * h);
    }
    return a;
}

struct Options {
    int learn = 2000, trials = 200;
    uint32_t seed = 1;
    bool csv = false, curve = false;
    std::string save;
};

constexpr double kGain = 0.9, kMaxStep = 0.2, kTolPx = 0.35, kTolRad = 0.5 * kPi / 180;
constexpr int kMaxIter = 30;

enum Method { kLearned, kOracle, kMiscal, kBroyden };
const char *kNames[] = {"learned", "oracle", "miscalibrated", "broyden"};

struct Result {
    bool success = false, lost = false;
    double err_px = 0, err_deg = 0;
    int iters = 0;
};

// The world of one seed: the true arm, its servos, the scene, the recogniser.
class World {
public:
    explicit World(uint32_t seed) : scene_(seed), rng_(seed * 7919u + 13u) {
        std::uniform_real_distribution<double> u(-1, 1);
        truth_.l1 *= 1 + 0.08 * u(rng_);
        truth_.l2 *= 1 + 0.08 * u(rng_);
        truth_.l3 *= 1 + 0.08 * u(rng_);
        for (int j = 0; j < kJ; ++j) {
            truth_.offset[j] = 0.06 * u(rng_);
            truth_.gain_err[j] = 0.04 * u(rng_);
            truth_.gain_slope[j] = 0.02 * u(rng_);
        }
        servos_.band = truth_.backlash;
        mis_ = truth_;  // the miscalibrated model: links +-10 %, offsets +-5 deg, no servo errors
        mis_.l1 = truth_.l1 * (1 + (u(rng_) < 0 ? -0.1 : 0.1));
        mis_.l2 = truth_.l2 * (1 + (u(rng_) < 0 ? -0.1 : 0.1));
        mis_.l3 = truth_.l3 * (1 + (u(rng_) < 0 ? -0.1 : 0.1));
        for (int j = 0; j < kJ; ++j) {
            mis_.offset[j] = truth_.offset[j] + (u(rng_) < 0 ? -1 : 1) * 5 * kPi / 180;
            mis_.gain_err[j] = mis_.gain_slope[j] = 0;
        }
    }
    const Arm &truth() const { return truth_; }
    const Arm &miscalibrated() const { return mis_; }
    std::mt19937 &rng() { return rng_; }

    // A random configuration whose plate is in view, facing the camera within 15 deg (the
    // gripper looking down, as for picking from the table).
    Q random_config() {
        for (;;) {
            Q q;
            for (int j = 0; j < kJ; ++j) q[j] = std::uniform_real_distribution<double>(kMin[j], kMax[j])(rng_);
            std::vector<Vec3> jn;
            Vec3 axis, jaw;
            truth_.pose(truth_.angles(q), jn, axis, jaw);
            if (axis.z > -std::cos(kPi / 12) || jn.back().z < 0.03) continue;
            bool inside = true;
            for (const auto &p : plate_image(truth_, truth_.angles(q)))
                inside = inside && p.x > 30 && p.y > 30 && p.x < kW - 30 && p.y < kH - 30;
            if (inside) return q;
        }
    }
    // Move the servos to a command (or reset them there) and look.
    cv::Mat move(const Q &c, bool reset = false) {
        if (reset) servos_.eff = c;
        servos_.set(c);
        return scene_.render(truth_, truth_.angles(servos_.eff));
    }
    // The truth trials are judged by: the exact projected plate's area centroid, and the
    // orientation of its exact outline (finder().outline_rotation()).
    X truth_now() {
        const Q a = truth_.angles(servos_.eff);
        X t = true_features(truth_, a);
        t[2] = finder_.outline_rotation(plate_image(truth_, a));
        return t;
    }
    bool look(const cv::Mat &frame, X &x) {
        ++looks_;
        const bool f = finder_.find(frame, x);
        if (f) {
            const X t = truth_now();
            if (std::hypot(x[0] - t[0], x[1] - t[1]) <= 2.0) ++recognised_;
        }
        return f;
    }
    GripperFinder &finder() { return finder_; }
    double recognition_rate() const { return looks_ ? double(recognised_) / looks_ : 0.0; }
    long looks() const { return looks_; }
    long recognised() const { return recognised_; }

private:
    Arm truth_, mis_;
    Servos servos_;
    Scene scene_;
    GripperFinder finder_;
    std::mt19937 rng_;
    long looks_ = 0, recognised_ = 0;
};

// Recognition by motion: background from frames of random configurations, then the
// prototype from the moving blobs of more.
bool learn_gripper(World &w) {
    std::vector<cv::Mat> frames;
    for (int k = 0; k < 41; ++k) frames.push_back(w.move(w.random_config(), true));
    w.finder().set_background(frames);
    std::vector<Blob> all;
    for (int k = 0; k < 120; ++k)
        for (const Blob &b : w.finder().blobs(w.move(w.random_config(), true))) all.push_back(b);
    return w.finder().learn_prototype(all);
}

sbr_servo_config_t learner_config() {
    sbr_servo_config_t cfg;
    sbr_servo_config_default(&cfg, kJ, kF);
    cfg.max_fields = 256;
    cfg.angle_mask = 4u;  // theta
    const float width[kJ] = {0.32f, 0.25f, 0.25f, 0.32f, 2.5f};  // roll barely changes J
    for (int j = 0; j < kJ; ++j) {
        cfg.width[j] = width[j];
        cfg.max_step[j] = float(kMaxStep);
        cfg.joint_min[j] = float(kMin[j]);
        cfg.joint_max[j] = float(kMax[j]);
    }
    cfg.gain = float(kGain);
    cfg.tolerance[0] = cfg.tolerance[1] = float(kTolPx);
    cfg.tolerance[2] = float(kTolRad);
    cfg.max_iterations = kMaxIter;
    return cfg;
}

struct Timing {
    double learn_s = 0, step_s = 0;
    long learn_n = 0, step_n = 0;
};

void learn_fl(sbr_servo_t &s, const Q &y, const Q &dy, const X &dx, Timing &tm) {
    float fy[kJ], fdy[kJ], fdx[kF];
    for (int j = 0; j < kJ; ++j) fy[j] = float(y[j]), fdy[j] = float(dy[j]);
    fdx[0] = float(dx[0]);
    fdx[1] = float(dx[1]);
    fdx[2] = float(wrap(dx[2]));
    const auto t0 = std::chrono::steady_clock::now();
    (void)sbr_servo_learn(&s, fy, fdy, fdx);  // CAPACITY: learned by the fields that reach it
    tm.learn_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++tm.learn_n;
}

// N random motions (random walks of 20 from random configurations) into the learner.
void babble(World &w, sbr_servo_t &s, int n, Timing &tm) {
    std::uniform_real_distribution<double> step(-0.08, 0.08);
    Q q{};
    X x{};
    bool have = false;
    for (int k = 0; k < n; ++k) {
        if (k % 20 == 0 || !have) {
            q = w.random_config();
            have = w.look(w.move(q, true), x);
            if (!have) continue;
        }
        Q q2;
        for (int j = 0; j < kJ; ++j) q2[j] = std::clamp(q[j] + step(w.rng()), kMin[j], kMax[j]);
        X x2;
        if (!w.look(w.move(q2), x2)) {
            have = false;
            continue;
        }
        Q dy;
        for (int j = 0; j < kJ; ++j) dy[j] = q2[j] - q[j];
        learn_fl(s, q, dy, {x2[0] - x[0], x2[1] - x[1], x2[2] - x[2]}, tm);
        q = q2;
        x = x2;
    }
}


// One trial of one method from the home configuration to the target features xw.
Result servo_run(World &w, Method m, sbr_servo_t *s, const X &xw, const X &xw_true, Timing &tm,
                 std::vector<cv::Point2d> *path) {
    Result r;
    const sbr_servo_config_t cfg = learner_config();
    Q y = kHome;
    cv::Mat frame = w.move(y, true);
    X x{};
    Mat35 broyden{};
    broyden[0][1] = 100;  // a scaled identity: shoulder -> v, base -> u (px per rad), roll -> theta
    broyden[1][0] = 100;
    broyden[2][4] = 1;
    sbr_servo_run_t run;
    sbr_servo_run_start(&run);
    r.lost = !w.look(frame, x);
    while (!r.lost) {
        if (path) path->emplace_back(x[0], x[1]);
        // every method steps by the core's rule (trust bound, joint limits, stopping rule)
        float fy[kJ], fx[kF], fw[kF], fn[kJ];
        for (int j = 0; j < kJ; ++j) fy[j] = float(y[j]);
        for (int i = 0; i < kF; ++i) fx[i] = float(x[i]), fw[i] = float(xw[i]);
        sbr_servo_result_t res;
        sbr_status_t st;
        if (m == kLearned) {
            const auto t0 = std::chrono::steady_clock::now();
            st = sbr_servo_step(s, &run, fy, fx, fw, fn, &res);
            tm.step_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            ++tm.step_n;
        } else {
            const Mat53 jinv = pinv(m == kOracle   ? model_jacobian(w.truth(), y)
                                    : m == kMiscal ? model_jacobian(w.miscalibrated(), y)
                                                   : broyden);
            float fj[kJ * kF];
            for (int j = 0; j < kJ; ++j)
                for (int i = 0; i < kF; ++i) fj[j * kF + i] = float(jinv[size_t(j)][size_t(i)]);
            st = sbr_servo_step_with(&cfg, &run, fj, fy, fx, fw, fn, &res);
        }
        if (st != SBR_OK || res != SBR_SERVO_STEP) break;
        Q yn;
        for (int j = 0; j < kJ; ++j) yn[j] = fn[j];
        frame = w.move(yn);
        ++r.iters;
        X xn{};
        if (!w.look(frame, xn)) {
            r.lost = true;
            break;
        }
        Q dy;
        double dd = 0;
        for (int j = 0; j < kJ; ++j) dy[j] = yn[j] - y[j], dd += dy[j] * dy[j];
        const X dx = {xn[0] - x[0], xn[1] - x[1], wrap(xn[2] - x[2])};
        if (m == kLearned) learn_fl(*s, y, dy, dx, tm);
        if (m == kBroyden && dd > 0)
            for (int i = 0; i < kF; ++i) {
                double pred = 0;
                for (int j = 0; j < kJ; ++j) pred += broyden[i][j] * dy[j];
                for (int j = 0; j < kJ; ++j) broyden[i][j] += (dx[i] - pred) * dy[j] / dd;
            }
        y = yn;
        x = xn;  // the next step starts from what this frame showed
    }
    const X t = w.truth_now();
    r.err_px = std::hypot(t[0] - xw_true[0], t[1] - xw_true[1]);
    r.err_deg = std::fabs(wrap(t[2] - xw_true[2])) * 180 / kPi;
    r.success = !r.lost && r.err_px <= 1.0 && r.err_deg <= 2.0 && r.iters <= kMaxIter;
    return r;
}

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[size_t(std::min<double>(double(v.size() - 1), std::floor(q * double(v.size() - 1) + 0.5)))];
}

struct Summary {
    double success = 0, median_err = 0, p95_err = 0, median_iters = 0;
};

Summary summarise(const std::vector<Result> &rs) {
    Summary s;
    std::vector<double> e, it;
    for (const auto &r : rs) {
        s.success += r.success ? 1 : 0;
        e.push_back(r.err_px);
        it.push_back(r.iters);
    }
    s.success /= double(std::max<size_t>(1, rs.size()));
    s.median_err = quantile(e, 0.5);
    s.p95_err = quantile(e, 0.95);
    s.median_iters = quantile(it, 0.5);
    return s;
}

// The targets of a run: recognised features and the truth of random configurations.
struct Target {
    X x, truth;
    Q q;
};
std::vector<Target> make_targets(World &w, int n) {
    std::vector<Target> t;
    while (int(t.size()) < n) {
        Target g;
        g.q = w.random_config();
        const cv::Mat f = w.move(g.q, true);
        if (!w.look(f, g.x)) continue;
        g.truth = w.truth_now();
        t.push_back(g);
    }
    return t;
}

void save_frame(World &w, const Target &t, const std::vector<cv::Point2d> &path, const std::string &file) {
    cv::Mat img = w.move(t.q, true);  // the target pose, then the path drawn on it
    for (size_t k = 1; k < path.size(); ++k) cv::line(img, path[k - 1], path[k], cv::Scalar(255, 255, 0), 1, cv::LINE_AA);
    for (const auto &p : path) cv::circle(img, p, 2, cv::Scalar(255, 255, 0), -1, cv::LINE_AA);
    cv::drawMarker(img, cv::Point2d(t.x[0], t.x[1]), cv::Scalar(0, 0, 255), cv::MARKER_CROSS, 16, 2);
    cv::imwrite(file, img);
}

// The learned method's success against the number of motions learned (fresh worlds of
// the same seed).
void print_curve(const Options &o, const sbr_servo_config_t &cfg, size_t ws_bytes) {
    for (int n : {250, 500, 1000, 2000}) {
        World wc(o.seed);
        learn_gripper(wc);
        std::vector<uint32_t> wsc(ws_bytes / 4 + 1);
        sbr_servo_t lc;
        sbr_servo_init(&lc, &cfg, wsc.data(), ws_bytes);
        Timing tc;
        babble(wc, lc, n, tc);
        const std::vector<Target> tg = make_targets(wc, o.trials);
        std::vector<Result> rc;
        for (const auto &t : tg) rc.push_back(servo_run(wc, kLearned, &lc, t.x, t.truth, tc, nullptr));
        const Summary sc = summarise(rc);
        std::printf("curve: N=%d success=%.3f median_err_px=%.3f median_iters=%.1f\n", n, sc.success,
                    sc.median_err, sc.median_iters);
    }
}

}  // namespace

int main(int argc, char **argv) {
    Options o;
    CLI::App app{"sbr_servo: visual servoing of a simulated 5-joint arm with a learned inverse Jacobian "
                 "(docs/usage/servo.md)"};
    app.add_option("--learn", o.learn, "random motions to learn from")->check(CLI::Range(1, 1000000))->capture_default_str();
    app.add_option("--trials", o.trials, "servo targets")->check(CLI::Range(1, 100000))->capture_default_str();
    app.add_option("--seed", o.seed, "random seed (arm, scene, motions, targets)")->capture_default_str();
    app.add_flag("--csv", o.csv, "the table as CSV");
    app.add_flag("--curve", o.curve, "the learned method's success for N = 250, 500, 1000, 2000");
    app.add_option("--save", o.save, "folder for frames of the first runs (target, path)");
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;

    World w(o.seed);
    if (!learn_gripper(w)) {
        std::fprintf(stderr, "sbr_servo: no moving blob seen: the gripper could not be learned\n");
        return 1;
    }
    const sbr_servo_config_t cfg = learner_config();
    const size_t ws_bytes = sbr_servo_workspace_size(&cfg);
    std::vector<uint32_t> ws(ws_bytes / 4 + 1);
    sbr_servo_t learner;
    if (sbr_servo_init(&learner, &cfg, ws.data(), ws_bytes) != SBR_OK) return 1;
    Timing tm;
    babble(w, learner, o.learn, tm);
    uint32_t fields = 0, samples = 0;
    sbr_servo_stats(&learner, &fields, &samples);
    const std::vector<Target> targets = make_targets(w, o.trials);

    std::vector<Result> res[4];
    for (int t = 0; t < o.trials; ++t)
        for (int m = 0; m < 4; ++m) {
            std::vector<cv::Point2d> path;
            res[m].push_back(servo_run(w, Method(m), &learner, targets[size_t(t)].x, targets[size_t(t)].truth, tm,
                                       o.save.empty() ? nullptr : &path));
            if (!o.save.empty() && t < 4)
                save_frame(w, targets[size_t(t)], path, o.save + "/servo_" + std::to_string(t) + "_" + kNames[m] + ".png");
        }
    Summary sm[4];
    for (int m = 0; m < 4; ++m) sm[m] = summarise(res[m]);
    if (o.csv) std::printf("method,success_rate,median_err_px,p95_err_px,median_iters\n");
    else std::printf("%-14s %8s %10s %10s %8s\n", "method", "success", "median px", "p95 px", "iters");
    for (int m = 0; m < 4; ++m)
        std::printf(o.csv ? "%s,%.3f,%.3f,%.3f,%.1f\n" : "%-14s %8.3f %10.3f %10.3f %8.1f\n", kNames[m], sm[m].success,
                    sm[m].median_err, sm[m].p95_err, sm[m].median_iters);
    std::printf("learned from %u motions (of --learn %d; frames where the gripper was not found are skipped): "
                "%u fields, workspace %zu bytes\n",
                samples, o.learn, fields, ws_bytes);
    std::printf("gripper prototype: the largest cluster of moving blobs (%zu blobs); recognised in %ld of %ld "
                "frames within 2 px (%.3f)\n",
                w.finder().cluster_size(), w.recognised(), w.looks(), w.recognition_rate());
    std::printf("time per call: sbr_servo_learn %.2f us, sbr_servo_step %.2f us (this machine, mean)\n",
                tm.learn_n ? 1e6 * tm.learn_s / double(tm.learn_n) : 0.0,
                tm.step_n ? 1e6 * tm.step_s / double(tm.step_n) : 0.0);
    if (o.curve) print_curve(o, cfg, ws_bytes);
    const bool met = sm[0].success >= 0.95 && sm[0].median_err <= 0.5 && sm[0].median_iters <= 10 &&
                     sm[0].success > sm[2].success && sm[0].success > sm[3].success &&
                     sm[0].success >= sm[1].success - 0.05 && ws_bytes <= 65536;
    // the ctest's guard on a small seeded run (40 trials: one trial is 2.5 %)
    const bool small = sm[0].success >= 0.9 && sm[0].median_err <= 0.5 && sm[0].median_iters <= 10 &&
                       sm[0].success >= sm[3].success + 0.2 && w.recognition_rate() >= 0.99 && ws_bytes <= 65536;
    std::printf("servo_checks=%s (learned: success >= 0.9, median error <= 0.5 px, median iterations <= 10, "
                "0.2 above Broyden; recognition >= 0.99; workspace <= 64 kB)\n",
                small ? "met" : "missed");
    std::printf("servo_targets=%s (learned: success >= 0.95, median error <= 0.5 px, median iterations <= 10, "
                "better than miscalibrated and Broyden, within 0.05 of the oracle; workspace <= 64 kB)\n",
                met ? "met" : "missed");
    return 0;
}
