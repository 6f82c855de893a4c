// SPDX-License-Identifier: MIT
// sbr_train_picto's synthetic copies of a sign (picto_augment.hpp).
#include "picto_augment.hpp"

#include <opencv2/imgcodecs.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace sbr_host::picto_train {

namespace {

// The shape of a sign of GTSDB class c: the danger signs (superclass 2) are triangles,
// the yield sign an inverted triangle, the priority road a diamond, the stop sign an
// octagon, every other class a disc.
enum class Shape { triangle, inverted, diamond, octagon, disc };
Shape sign_shape(int c) {
    if (superclass_of(c) == 2) return Shape::triangle;
    if (c == 13) return Shape::inverted;
    if (c == 12) return Shape::diamond;
    if (c == 14) return Shape::octagon;
    return Shape::disc;
}

// That shape's outline in the sign's box, in units of the box (0..1 across and down).
std::vector<cv::Point2f> sign_outline(int c) {
    switch (sign_shape(c)) {
    case Shape::triangle: return {{0.5f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
    case Shape::inverted: return {{0.0f, 0.0f}, {1.0f, 0.0f}, {0.5f, 1.0f}};
    case Shape::diamond: return {{0.5f, 0.0f}, {1.0f, 0.5f}, {0.5f, 1.0f}, {0.0f, 0.5f}};
    case Shape::octagon: {
        const float a = 0.2929f;  // 1 - 1/sqrt(2): a regular octagon's corner cut
        return {{a, 0.0f}, {1.0f - a, 0.0f}, {1.0f, a}, {1.0f, 1.0f - a},
                {1.0f - a, 1.0f}, {a, 1.0f}, {0.0f, 1.0f - a}, {0.0f, a}};
    }
    case Shape::disc: break;
    }
    std::vector<cv::Point2f> disc;
    for (int k = 0; k < 32; ++k) {
        const float t = 6.2831853f * float(k) / 32.0f;
        disc.push_back({0.5f + 0.5f * std::cos(t), 0.5f + 0.5f * std::sin(t)});
    }
    return disc;
}

// Whether mode m applies to a sign of class c.
bool bg_applies(BgSwap m, int c) {
    const Shape s = sign_shape(c);
    return m == BgSwap::all || (m == BgSwap::round && s == Shape::disc) ||
           (m == BgSwap::triangle && (s == Shape::triangle || s == Shape::inverted));
}

// img through gamma `gam` and contrast `con` about mid-grey, into out (may be img).
void expose(const cv::Mat &img, float gam, float con, cv::Mat &out) {
    cv::Mat lut(1, 256, CV_8U);
    for (int k = 0; k < 256; ++k) {
        const float t = 255.0f * std::pow(float(k) / 255.0f, gam);
        lut.at<uint8_t>(k) = cv::saturate_cast<uint8_t>(128.0f + con * (t - 128.0f));
    }
    cv::LUT(img, lut, out);
}

// img under one of a camera's degradations, drawn from rng: motion blur (a line of 5 to
// 11 px at any angle), defocus (a disc of radius 1 to 3 px), sensor noise (sigma 0.02 to
// 0.08 of the range), JPEG compression (quality 10 to 40) or haze (a grey veil of 0.2 to
// 0.5 and a slight blur). Into out (not img).
void degrade(const cv::Mat &img, std::mt19937 &rng, cv::Mat &out) {
    std::uniform_real_distribution<float> V(0.0f, 1.0f);
    const int kind = int(V(rng) * 5.0f) % 5;
    if (kind == 0) {
        const int len = 5 + 2 * int(V(rng) * 3.999f);
        cv::Mat k = cv::Mat::zeros(len, len, CV_32F);
        const float a = 3.1415927f * V(rng), c = 0.5f * float(len - 1);
        cv::line(k, cv::Point2f(c - c * std::cos(a), c - c * std::sin(a)), cv::Point2f(c + c * std::cos(a), c + c * std::sin(a)),
                 cv::Scalar(1.0), 1, cv::LINE_AA);
        k /= std::max(1e-6, cv::sum(k)[0]);
        cv::filter2D(img, out, -1, k, cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT);
    } else if (kind == 1) {
        const int r = 1 + int(V(rng) * 2.999f);
        cv::Mat k = cv::Mat::zeros(2 * r + 1, 2 * r + 1, CV_32F);
        cv::circle(k, cv::Point(r, r), r, cv::Scalar(1.0), cv::FILLED, cv::LINE_AA);
        k /= std::max(1e-6, cv::sum(k)[0]);
        cv::filter2D(img, out, -1, k, cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT);
    } else if (kind == 2) {
        cv::Mat n(img.size(), CV_32FC3);
        cv::RNG cvr{static_cast<uint64_t>(rng())};
        cvr.fill(n, cv::RNG::NORMAL, 0.0, 255.0 * (0.02 + 0.06 * double(V(rng))));
        cv::Mat f;
        img.convertTo(f, CV_32FC3);
        f += n;
        f.convertTo(out, CV_8UC3);
    } else if (kind == 3) {
        std::vector<uint8_t> buf;
        cv::imencode(".jpg", img, buf, {cv::IMWRITE_JPEG_QUALITY, 10 + int(V(rng) * 30.0f)});
        out = cv::imdecode(buf, cv::IMREAD_COLOR);
    } else {
        const float veil = 0.2f + 0.3f * V(rng);
        cv::Mat b;
        cv::GaussianBlur(img, b, cv::Size(0, 0), 1.0);
        cv::addWeighted(b, double(1.0f - veil), cv::Mat(img.size(), img.type(), cv::Scalar(200, 200, 200)), double(veil),
                        0.0, out);
    }
}

}  // namespace

// The class a GTSDB sign of class c shows in a mirror, -1 when no class does (digits,
// text, vehicles and other pictograms that are not left-right symmetric).
int mirror_class(int c) {
    switch (c) {
    case 11: case 12: case 13: case 15: case 17: case 18: case 22: case 26: case 30: case 35:
        return c;  // symmetric
    case 19: return 20;  // dangerous curve left <-> right
    case 20: return 19;
    case 33: return 34;  // turn right ahead <-> turn left ahead
    case 34: return 33;
    case 36: return 37;  // straight or right <-> straight or left
    case 37: return 36;
    case 38: return 39;  // keep right <-> keep left
    case 39: return 38;
    default: return -1;
    }
}

// The order of a GTSDB class's rotational symmetry (its sign looks the same turned by
// 360 / order degrees about its centre), 1 when it has none: the roundabout's three
// arrows, the yield sign's plain inverted triangle, the priority road's diamond, the
// no-vehicles sign's plain disc (any angle; 4 is used), the no-entry bar and the
// end-of-limits stripes (a half turn).
int symmetry_order(int c) {
    switch (c) {
    case 40: case 13: return 3;
    case 12: case 15: return 4;
    case 17: case 32: return 2;
    default: return 1;
    }
}

// One synthetic copy of the sign b (paper D built its prototypes from synthetic sign
// images): its neighbourhood `near` (at mx0, my0 in img) warped by a random perspective
// (each corner of the sign moved up to 7 % of its size), a random exposure (gamma 0.6 to
// 1.7, contrast 0.6 to 1), a Gaussian blur (sigma up to 1.5 px) and with a third chance
// a piece of another place of the frame (no sign in it) over up to a fifth of the sign's
// area from one side; then, half the time, shrunk 1.5 to 3 times (while the sign stays
// >= 12 px). Returns the image and the sign's box in it (qs); empty if nothing fit.
cv::Mat synth_copy(const cv::Mat &img, const cv::Mat &near, const Box &b, const std::vector<Box> &gts, int mx0,
                   int my0, std::mt19937 &rng, Box &qs) {
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    const float w = float(b.x1 - b.x0), h = float(b.y1 - b.y0);
    const cv::Point2f src[4] = {{float(b.x0) - float(mx0), float(b.y0) - float(my0)},
                                {float(b.x1) - float(mx0), float(b.y0) - float(my0)},
                                {float(b.x1) - float(mx0), float(b.y1) - float(my0)},
                                {float(b.x0) - float(mx0), float(b.y1) - float(my0)}};
    cv::Point2f dst[4];
    for (int k = 0; k < 4; ++k) dst[k] = src[k] + cv::Point2f(0.07f * w * U(rng), 0.07f * h * U(rng));
    cv::Mat seen;
    cv::warpPerspective(near, seen, cv::getPerspectiveTransform(src, dst), near.size(), cv::INTER_LINEAR,
                        cv::BORDER_REFLECT);
    float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
    for (const auto &d : dst) {
        x0 = std::min(x0, d.x); y0 = std::min(y0, d.y);
        x1 = std::max(x1, d.x); y1 = std::max(y1, d.y);
    }
    x0 = std::max(0.0f, x0); y0 = std::max(0.0f, y0);
    x1 = std::min(float(seen.cols), x1); y1 = std::min(float(seen.rows), y1);
    if (x1 - x0 < 8.0f || y1 - y0 < 8.0f) return {};
    qs = {x0, y0, x1, y1};
    const float gam = std::exp(0.5f * U(rng)), con = 0.8f + 0.2f * U(rng);
    expose(seen, gam, con, seen);
    const float sigma = 0.75f * (U(rng) + 1.0f);
    if (sigma > 0.3f) cv::GaussianBlur(seen, seen, cv::Size(), double(sigma));
    if (U(rng) < -1.0f / 3.0f) {
        // occluder: a strip from one side of the sign over up to a fifth of its area,
        // filled from a sign-free place of the frame
        const int side = int(2.0f * (U(rng) + 1.0f)) & 3;
        const float frac = 0.1f + 0.05f * (U(rng) + 1.0f);
        cv::Rect r;
        const int iw = int(x1 - x0), ih = int(y1 - y0);
        if (side == 0) r = cv::Rect(int(x0), int(y0), std::max(1, int(frac * float(iw))), ih);
        else if (side == 1) r = cv::Rect(int(x1) - std::max(1, int(frac * float(iw))), int(y0), std::max(1, int(frac * float(iw))), ih);
        else if (side == 2) r = cv::Rect(int(x0), int(y1) - std::max(1, int(frac * float(ih))), iw, std::max(1, int(frac * float(ih))));
        else r = cv::Rect(int(x0), int(y0), iw, std::max(1, int(frac * float(ih))));
        r &= cv::Rect(0, 0, seen.cols, seen.rows);
        for (int t = 0; t < 20 && r.area() > 0 && r.width < img.cols && r.height < img.rows; ++t) {
            const int bx = int(float(img.cols - r.width) * 0.5f * (U(rng) + 1.0f));
            const int by = int(float(img.rows - r.height) * 0.5f * (U(rng) + 1.0f));
            bool clear = true;
            for (const Box &o : gts)
                if (float(bx) < o.x1 && o.x0 < float(bx + r.width) && float(by) < o.y1 && o.y0 < float(by + r.height))
                    clear = false;
            if (!clear) continue;
            img(cv::Rect(bx, by, r.width, r.height)).copyTo(seen(r));
            break;
        }
    }
    const float shrink = 1.5f + 0.75f * (U(rng) + 1.0f);
    if (U(rng) > 0.0f && (x1 - x0) / shrink >= 12.0f) {
        cv::Mat small;
        cv::resize(seen, small, cv::Size(), 1.0 / shrink, 1.0 / shrink, cv::INTER_AREA);
        const float fx = float(small.cols) / float(seen.cols), fy = float(small.rows) / float(seen.rows);
        qs = {qs.x0 * fx, qs.y0 * fy, qs.x1 * fx, qs.y1 * fy};
        return small;
    }
    return seen;
}

Site make_site(const cv::Mat &img, const sbr_image_t &v, const std::vector<Box> &gts, size_t g, int cls) {
    Site st{&img, &v, &gts, gts[g], 0.0f, 0.0f, 0, 0, 0, 0, cv::Mat(), cls};
    const Box &b = st.b;
    st.w = float(b.x1 - b.x0);
    st.h = float(b.y1 - b.y0);
    st.mx0 = std::max(0, int(b.x0 - st.w));
    st.my0 = std::max(0, int(b.y0 - st.h));
    st.mx1 = std::min(img.cols, int(b.x1 + st.w) + 1);
    st.my1 = std::min(img.rows, int(b.y1 + st.h) + 1);
    st.near = img(cv::Rect(st.mx0, st.my0, st.mx1 - st.mx0, st.my1 - st.my0));
    return st;
}

// Copy j of a sign (j = 0: the annotated box itself), drawn from rng in a fixed order.
Copy make_copy(const Options &o, const Site &site, int j, std::mt19937 &rng) {
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    const Box &b = site.b;
    const float w = site.w, h = site.h;
    const int mx0 = site.mx0, my0 = site.my0, mx1 = site.mx1, my1 = site.my1;
    const cv::Mat &near = site.near;
    const cv::Mat &img = *site.img;
    const std::vector<Box> &gts = *site.gts;
    Box q = b;
    if (j > 0) {
        const float cx = 0.5f * float(b.x0 + b.x1) + 0.08f * w * U(rng);
        const float cy = 0.5f * float(b.y0 + b.y1) + 0.08f * h * U(rng);
        const float s = 1.0f + 0.08f * U(rng);
        const float hw = 0.5f * w * s * (1.0f + 0.04f * U(rng)), hh = 0.5f * h * s * (1.0f + 0.04f * U(rng));
        q = {cx - hw, cy - hh, cx + hw, cy + hh};
    }
    // the copy: box qs of image `seen` (the frame, or a transformed
    // neighbourhood), with that class; mirrored copies flip the target's
    // horizontal shift
    cv::Mat seen;
    Box qs = q;
    int label = site.cls;
    bool mirrored = false;
    // every other copy as a farther sign: the neighbourhood shrunk (area
    // averaging) so the sign is 1.5 to 4 times smaller, at least 12 px
    const float shrink = 1.5f + 1.25f * (U(rng) + 1.0f);
    if (j % 2 == 1 && w / shrink >= 12.0f) {
        cv::resize(near, seen, cv::Size(), 1.0 / shrink, 1.0 / shrink, cv::INTER_AREA);
        const float fx = float(seen.cols) / float(mx1 - mx0), fy = float(seen.rows) / float(my1 - my0);
        qs = {(float(q.x0) - float(mx0)) * fx, (float(q.y0) - float(my0)) * fy,
              (float(q.x1) - float(mx0)) * fx, (float(q.y1) - float(my0)) * fy};
    } else if (j % 4 == 2 && o.exposure) {
        // another exposure: the neighbourhood's values through a random
        // gamma (0.5 to 2) and contrast (0.5 to 1) about mid-grey
        const float gam = std::exp(0.6931472f * U(rng)), con = 0.75f + 0.25f * U(rng);
        expose(near, gam, con, seen);
        qs = {q.x0 - float(mx0), q.y0 - float(my0), q.x1 - float(mx0), q.y1 - float(my0)};
    } else if (j % 4 == 2 && (bg_applies(o.bg_swap, site.cls) || bg_applies(o.bg_fill, site.cls))) {
        // the sign in front of another background: the neighbourhood outside
        // the sign's outline (grown by 5 %) replaced, so the box's corners
        // (clutter behind the sign) are not part of what a class looks like.
        // --bg-swap: by an equally large piece of the same frame that
        // overlaps no annotated sign (no such piece in 20 draws: the plain
        // copy); --bg-fill: by a plain random colour (sky to night) with a
        // vertical gradient and a little noise. A sign both apply to
        // alternates between them.
        const int nw = mx1 - mx0, nh = my1 - my0;
        cv::Mat mask = cv::Mat::zeros(nh, nw, CV_8U);
        std::vector<cv::Point> poly;
        for (const cv::Point2f &u : sign_outline(site.cls)) {
            const float gx = 0.5f + 1.05f * (u.x - 0.5f), gy = 0.5f + 1.05f * (u.y - 0.5f);
            poly.emplace_back(int(std::lround(b.x0 - float(mx0) + gx * w)),
                              int(std::lround(b.y0 - float(my0) + gy * h)));
        }
        cv::fillConvexPoly(mask, poly, cv::Scalar(255));
        const bool fill = bg_applies(o.bg_fill, site.cls) && (!bg_applies(o.bg_swap, site.cls) || j % 8 == 6);
        if (fill) {
            const float level = 127.5f * (U(rng) + 1.0f), slope = 40.0f * U(rng);
            const float tint[3] = {25.0f * U(rng), 25.0f * U(rng), 25.0f * U(rng)};
            seen.create(nh, nw, CV_8UC3);
            for (int y = 0; y < nh; ++y) {
                const float base = level + slope * (float(y) / float(std::max(1, nh - 1)) - 0.5f);
                for (int x = 0; x < nw; ++x)
                    for (int k = 0; k < 3; ++k)
                        seen.at<cv::Vec3b>(y, x)[k] = cv::saturate_cast<uint8_t>(base + tint[k] + 3.0f * U(rng));
            }
            near.copyTo(seen, mask);
        }
        for (int t = 0; t < 20 && seen.empty() && nw < img.cols && nh < img.rows; ++t) {
            const int bx = int(float(img.cols - nw) * 0.5f * (U(rng) + 1.0f));
            const int by = int(float(img.rows - nh) * 0.5f * (U(rng) + 1.0f));
            const Box piece{float(bx), float(by), float(bx + nw), float(by + nh)};
            bool clear = true;
            for (const Box &o : gts)
                if (piece.x0 < o.x1 && o.x0 < piece.x1 && piece.y0 < o.y1 && o.y0 < piece.y1) clear = false;
            if (!clear) continue;
            seen = img(cv::Rect(bx, by, nw, nh)).clone();
            near.copyTo(seen, mask);
        }
        qs = {q.x0 - float(mx0), q.y0 - float(my0), q.x1 - float(mx0), q.y1 - float(my0)};
        if (seen.empty()) qs = q;
    } else if (j > 0 && j % 4 == 0 && o.rotate && symmetry_order(site.cls) > 1 &&
               (!o.mirror || j % 8 == 0)) {
        // the sign turned by a multiple of its symmetry angle about its
        // centre: the same class and the same box target (the outline
        // stays, the jittered box q is not turned)
        const int order = symmetry_order(site.cls);
        const int turns = 1 + int(std::floor(0.5f * (U(rng) + 1.0f) * float(order - 1) * 0.9999f));
        const cv::Point2f centre(0.5f * (b.x0 + b.x1) - float(mx0), 0.5f * (b.y0 + b.y1) - float(my0));
        const cv::Mat rot = cv::getRotationMatrix2D(centre, 360.0 * turns / order, 1.0);
        cv::warpAffine(near, seen, rot, near.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
        qs = {q.x0 - float(mx0), q.y0 - float(my0), q.x1 - float(mx0), q.y1 - float(my0)};
    } else if (j > 0 && j % 4 == 0 && o.mirror && mirror_class(site.cls) >= 0) {
        // the mirror image: the neighbourhood flipped left to right, the
        // class its mirror class (keep right <-> keep left, ...)
        cv::flip(near, seen, 1);
        const float W = float(mx1 - mx0);
        qs = {W - (q.x1 - float(mx0)), q.y0 - float(my0), W - (q.x0 - float(mx0)), q.y1 - float(my0)};
        label = mirror_class(site.cls);
        mirrored = true;
    }
    if (o.degrade && j % 5 == 3) {
        // --degrade: this copy as a degraded camera sees it (degrade()); a copy taken
        // from the frame itself becomes its neighbourhood, degraded
        if (seen.empty()) {
            seen = near;
            qs = {q.x0 - float(mx0), q.y0 - float(my0), q.x1 - float(mx0), q.y1 - float(my0)};
        }
        cv::Mat d;
        degrade(seen, rng, d);
        seen = d;
    }
    return Copy{q, seen, qs, label, mirrored};
}

}  // namespace sbr_host::picto_train
