// SPDX-License-Identifier: MIT
// Exact references for the harnesses' postconditions: a conic's determinants, centre,
// value at the centre and ellipse geometry in long double (64-bit mantissa on x86-64,
// where the fuzzers run), so that an SBR_OK result of the float32 core can be confirmed
// where float32 itself cannot decide.
#ifndef SBR_FUZZ_EXACT_HPP
#define SBR_FUZZ_EXACT_HPP

#include <cmath>

extern "C" {
#include "sbr/conic.h"
}

struct ExactConic {
    long double a, b, c, d, e, f;
    long double q;      // max(|a|, |b|, |c|)
    long double d22;    // ac - b^2
    long double xc, yc; // centre (when d22 != 0)
    long double f0;     // value at the centre
    long double terms;  // |d xc| + |e yc| + |f|
    bool centre = false;
};

// flush: conic.h's rule that entries below 2^-33 of the quadratic part's scale (its
// largest entry rounded up to a power of two) count as zero
inline ExactConic exact_conic(const sbr_conic_t &c, bool flush = false)
{
    ExactConic x;
    x.a = c.a;
    x.b = c.b;
    x.c = c.c;
    x.d = c.d;
    x.e = c.e;
    x.f = c.f;
    if (flush) {
        int ex = 0;
        (void)std::frexp(std::fmax(std::fabs(x.a), std::fmax(std::fabs(x.b), std::fabs(x.c))), &ex);
        const long double lim = std::ldexp(1.0L, ex - 33);
        long double *v[6] = {&x.a, &x.b, &x.c, &x.d, &x.e, &x.f};
        for (long double *p : v) {
            if (std::fabs(*p) < lim) {
                *p = 0.0L;
            }
        }
    }
    x.q = std::fmax(std::fabs(x.a), std::fmax(std::fabs(x.b), std::fabs(x.c)));
    x.d22 = x.a * x.c - x.b * x.b;
    x.xc = x.yc = x.f0 = x.terms = 0.0L;
    if (x.d22 != 0.0L) {
        x.centre = true;
        x.xc = (x.b * x.e - x.c * x.d) / x.d22;
        x.yc = (x.b * x.d - x.a * x.e) / x.d22;
        // det(C) / det(C22), det(C) expanded (its terms cancel less than d xc + e yc + f)
        const long double det = x.a * (x.c * x.f - x.e * x.e) - x.b * (x.b * x.f - x.d * x.e) +
                                x.d * (x.b * x.e - x.c * x.d);
        x.f0 = det / x.d22;
        x.terms = std::fabs(x.d * x.xc) + std::fabs(x.e * x.yc) + std::fabs(x.f);
    }
    return x;
}

// The exact geometry of a conic that is a real ellipse (false otherwise).
inline bool exact_ellipse(const ExactConic &x, long double &major, long double &minor)
{
    if (!x.centre || x.d22 <= 0.0L) {
        return false;
    }
    const long double s = (x.a + x.c) < 0.0L ? -1.0L : 1.0L;
    const long double a = s * x.a, c = s * x.c, b = s * x.b, f0 = s * x.f0;
    if (!(f0 < 0.0L)) {
        return false;
    }
    const long double h = 0.5L * (a - c);
    const long double r = std::sqrt(h * h + b * b);
    const long double lmax = 0.5L * (a + c) + r;
    const long double lmin = x.d22 / lmax;
    major = std::sqrt(-f0 / lmin);
    minor = std::sqrt(-f0 / lmax);
    return std::isfinite(major) && std::isfinite(minor) && minor > 0.0L;
}

// |got - want| <= rel * scale
inline bool near_rel(long double got, long double want, long double scale, long double rel)
{
    return std::fabs(got - want) <= rel * scale;
}

// The conic is, exactly, a real ellipse with e's centre and semi-axes within `rel` (of
// each semi-axis; of the semi-major for the centre).
inline bool exact_is_ellipse(const sbr_conic_t &c, const sbr_ellipse_t &e, long double rel)
{
    const ExactConic x = exact_conic(c);
    long double major = 0.0L, minor = 0.0L;
    return exact_ellipse(x, major, minor) && near_rel(major, e.semi_major, e.semi_major, rel) &&
           near_rel(minor, e.semi_minor, e.semi_minor, rel) && near_rel(x.xc, e.cx, e.semi_major, rel) &&
           near_rel(x.yc, e.cy, e.semi_major, rel);
}

#endif // SBR_FUZZ_EXACT_HPP
