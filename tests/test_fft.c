/* SPDX-License-Identifier: MIT */
/* Unity tests of the fixed-size FFT (include/sbr/fft.h). */
#include "unity.h"
#include "sbr/fft.h"
#include "fft_tables.h"
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define NMAX 1024u
#define GUARD_CPLX (TSUP_GUARD_BYTES / sizeof(sbr_complex_t))

static const uint32_t k_sizes[] = {16u, 32u, 64u, 128u, 256u, 512u, 1024u};
#define NSIZES (sizeof(k_sizes) / sizeof(k_sizes[0]))

/* Buffers with a guard tail; static because 8 KiB arrays are large for an MCU stack. */
static sbr_complex_t g_in[NMAX + GUARD_CPLX];
static sbr_complex_t g_out[NMAX + GUARD_CPLX];
static sbr_complex_t g_tmp[NMAX + GUARD_CPLX];
static double g_ref_re[NMAX];
static double g_ref_im[NMAX];
static double g_cos[NMAX];
static double g_sin[NMAX];

void setUp(void) {}
void tearDown(void) {}

static void fill_random(sbr_complex_t *x, uint32_t n, uint32_t seed)
{
    tsup_rng_t r = {seed};
    uint32_t i;
    for (i = 0; i < n; i++) {
        x[i].re = tsup_uniform(&r, -1.0f, 1.0f);
        x[i].im = tsup_uniform(&r, -1.0f, 1.0f);
    }
}

/* Double-precision DFT of x; sign -1 forward, +1 inverse (the inverse scaled by 1/n). */
static void ref_dft(const sbr_complex_t *x, uint32_t n, int sign)
{
    uint32_t k;
    uint32_t t;
    const double pi = 3.14159265358979323846;
    for (k = 0; k < n; k++) {
        g_cos[k] = cos(2.0 * pi * (double)k / (double)n);
        g_sin[k] = sin(2.0 * pi * (double)k / (double)n);
    }
    for (k = 0; k < n; k++) {
        double re = 0.0;
        double im = 0.0;
        for (t = 0; t < n; t++) {
            const uint32_t idx = (uint32_t)(((uint64_t)k * t) % n);
            const double c = g_cos[idx];
            const double s = (double)sign * g_sin[idx];
            re += (double)x[t].re * c - (double)x[t].im * s;
            im += (double)x[t].re * s + (double)x[t].im * c;
        }
        if (sign > 0) {
            re /= (double)n;
            im /= (double)n;
        }
        g_ref_re[k] = re;
        g_ref_im[k] = im;
    }
}

static double snr_db(const sbr_complex_t *y, uint32_t n)
{
    double sig = 0.0;
    double err = 0.0;
    uint32_t k;
    for (k = 0; k < n; k++) {
        const double dr = (double)y[k].re - g_ref_re[k];
        const double di = (double)y[k].im - g_ref_im[k];
        sig += g_ref_re[k] * g_ref_re[k] + g_ref_im[k] * g_ref_im[k];
        err += dr * dr + di * di;
    }
    if (err == 0.0) {
        return 400.0;
    }
    return 10.0 * log10(sig / err);
}

static void test_snr_against_double_dft(int inverse)
{
    uint32_t i;
    for (i = 0; i < NSIZES; i++) {
        const uint32_t n = k_sizes[i];
        sbr_fft_t fft;
        double snr;
        char msg[64];
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init(&fft, n));
        fill_random(g_in, n, 1000u + n);
        tsup_guard_fill(&g_out[n], TSUP_GUARD_BYTES);
        if (inverse) {
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_inverse(&fft, g_in, g_out));
        } else {
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_forward(&fft, g_in, g_out));
        }
        TEST_ASSERT_TRUE_MESSAGE(tsup_guard_intact(&g_out[n], TSUP_GUARD_BYTES),
                                 "guard after output overwritten");
        ref_dft(g_in, n, inverse ? 1 : -1);
        snr = snr_db(g_out, n);
        snprintf(msg, sizeof msg, "%s N=%u SNR %.1f dB", inverse ? "inverse" : "forward",
                 (unsigned)n, snr);
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(snr >= 120.0, msg);
    }
}

static void test_forward_snr(void) { test_snr_against_double_dft(0); }
static void test_inverse_snr(void) { test_snr_against_double_dft(1); }

/* In place runs the same arithmetic as out of place, so the results are identical. */
static void test_in_place_equals_out_of_place(void)
{
    uint32_t i;
    for (i = 0; i < NSIZES; i++) {
        const uint32_t n = k_sizes[i];
        sbr_fft_t fft;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init(&fft, n));
        fill_random(g_in, n, 7u * n);
        memcpy(g_tmp, g_in, n * sizeof(sbr_complex_t));
        tsup_guard_fill(&g_tmp[n], TSUP_GUARD_BYTES);
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_forward(&fft, g_in, g_out));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_forward(&fft, g_tmp, g_tmp));
        TEST_ASSERT_EQUAL_MEMORY(g_out, g_tmp, n * sizeof(sbr_complex_t));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_inverse(&fft, g_in, g_out));
        memcpy(g_tmp, g_in, n * sizeof(sbr_complex_t));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_inverse(&fft, g_tmp, g_tmp));
        TEST_ASSERT_EQUAL_MEMORY(g_out, g_tmp, n * sizeof(sbr_complex_t));
        TEST_ASSERT_TRUE(tsup_guard_intact(&g_tmp[n], TSUP_GUARD_BYTES));
    }
}

static void test_roundtrip_is_identity(void)
{
    uint32_t i;
    uint32_t k;
    for (i = 0; i < NSIZES; i++) {
        const uint32_t n = k_sizes[i];
        sbr_fft_t fft;
        float maxerr = 0.0f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init(&fft, n));
        fill_random(g_in, n, 99u + n);
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_forward(&fft, g_in, g_out));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_inverse(&fft, g_out, g_tmp));
        for (k = 0; k < n; k++) {
            maxerr = fmaxf(maxerr, fabsf(g_tmp[k].re - g_in[k].re));
            maxerr = fmaxf(maxerr, fabsf(g_tmp[k].im - g_in[k].im));
        }
        /* inputs are in [-1, 1]: a few float ulps of error, growing with log N */
        TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, maxerr);
    }
}

static void test_linearity(void)
{
    static sbr_complex_t x[NMAX];
    static sbr_complex_t y[NMAX];
    static sbr_complex_t fx[NMAX];
    static sbr_complex_t fy[NMAX];
    const float a = 0.75f;
    const float b = -1.5f;
    uint32_t i;
    uint32_t k;
    for (i = 0; i < NSIZES; i++) {
        const uint32_t n = k_sizes[i];
        sbr_fft_t fft;
        double err = 0.0;
        double mag = 0.0;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init(&fft, n));
        fill_random(x, n, 3u);
        fill_random(y, n, 4u);
        for (k = 0; k < n; k++) {
            g_in[k].re = a * x[k].re + b * y[k].re;
            g_in[k].im = a * x[k].im + b * y[k].im;
        }
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_forward(&fft, x, fx));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_forward(&fft, y, fy));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_forward(&fft, g_in, g_out));
        for (k = 0; k < n; k++) {
            const double er = (double)g_out[k].re - ((double)a * fx[k].re + (double)b * fy[k].re);
            const double ei = (double)g_out[k].im - ((double)a * fx[k].im + (double)b * fy[k].im);
            err += er * er + ei * ei;
            mag += (double)g_out[k].re * g_out[k].re + (double)g_out[k].im * g_out[k].im;
        }
        TEST_ASSERT_TRUE(sqrt(err / mag) < 1e-6);
    }
}

static void test_parseval(void)
{
    uint32_t i;
    uint32_t k;
    for (i = 0; i < NSIZES; i++) {
        const uint32_t n = k_sizes[i];
        sbr_fft_t fft;
        double et = 0.0;
        double ef = 0.0;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init(&fft, n));
        fill_random(g_in, n, 11u * n);
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_forward(&fft, g_in, g_out));
        for (k = 0; k < n; k++) {
            et += (double)g_in[k].re * g_in[k].re + (double)g_in[k].im * g_in[k].im;
            ef += (double)g_out[k].re * g_out[k].re + (double)g_out[k].im * g_out[k].im;
        }
        /* sum |X|^2 = N sum |x|^2 for the unscaled forward transform */
        TEST_ASSERT_DOUBLE_WITHIN(1e-5 * ef, (double)n * et, ef);
    }
}

/* Analytic cases: an impulse has a flat spectrum, a pure tone a single line. */
static void test_impulse_and_tone(void)
{
    uint32_t i;
    uint32_t k;
    const double pi = 3.14159265358979323846;
    for (i = 0; i < NSIZES; i++) {
        const uint32_t n = k_sizes[i];
        const uint32_t k0 = n / 4u + 3u;
        sbr_fft_t fft;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init(&fft, n));
        memset(g_in, 0, n * sizeof(sbr_complex_t));
        g_in[0].re = 1.0f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_forward(&fft, g_in, g_out));
        for (k = 0; k < n; k++) {
            TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, g_out[k].re);
            TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, g_out[k].im);
        }
        for (k = 0; k < n; k++) {
            const double a = 2.0 * pi * (double)((k0 * k) % n) / (double)n;
            g_in[k].re = (float)cos(a);
            g_in[k].im = (float)sin(a);
        }
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_forward(&fft, g_in, g_out));
        for (k = 0; k < n; k++) {
            const float expect = (k == k0) ? (float)n : 0.0f;
            TEST_ASSERT_FLOAT_WITHIN(2e-6f * (float)n, expect, g_out[k].re);
            TEST_ASSERT_FLOAT_WITHIN(2e-6f * (float)n, 0.0f, g_out[k].im);
        }
    }
}

/* The generated tables agree with double-precision cos/sin to float rounding. */
static void test_twiddle_tables_exact(void)
{
    static const struct { const sbr_complex_t *t; uint32_t span; } tabs[] = {
        {sbr_fft_tw_4, 4u}, {sbr_fft_tw_8, 8u}, {sbr_fft_tw_16, 16u}, {sbr_fft_tw_32, 32u},
        {sbr_fft_tw_64, 64u}, {sbr_fft_tw_128, 128u}, {sbr_fft_tw_256, 256u}};
    const double pi = 3.14159265358979323846;
    uint32_t i;
    uint32_t j;
    uint32_t m;
    for (i = 0; i < sizeof(tabs) / sizeof(tabs[0]); i++) {
        for (j = 0; j < tabs[i].span; j++) {
            for (m = 1; m <= 3; m++) {
                const double a = -2.0 * pi * (double)(m * j) / (4.0 * (double)tabs[i].span);
                const sbr_complex_t w = tabs[i].t[3u * j + (m - 1u)];
                TEST_ASSERT_DOUBLE_WITHIN(6e-8, cos(a), (double)w.re);
                TEST_ASSERT_DOUBLE_WITHIN(6e-8, sin(a), (double)w.im);
            }
        }
    }
    for (i = 0; i < 16u; i++) {
        /* bit reversal of 4 bits */
        const uint32_t r = ((i & 1u) << 3) | ((i & 2u) << 1) | ((i & 4u) >> 1) | ((i & 8u) >> 3);
        TEST_ASSERT_EQUAL_UINT16(r, sbr_fft_bitrev_16[i]);
    }
}

static void test_per_size_init_matches_generic(void)
{
    typedef sbr_status_t (*init_fn)(sbr_fft_t *);
    static const init_fn fns[NSIZES] = {sbr_fft_init_16, sbr_fft_init_32, sbr_fft_init_64,
                                        sbr_fft_init_128, sbr_fft_init_256, sbr_fft_init_512,
                                        sbr_fft_init_1024};
    uint32_t i;
    for (i = 0; i < NSIZES; i++) {
        sbr_fft_t a;
        sbr_fft_t b;
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        TEST_ASSERT_EQUAL_INT(SBR_OK, fns[i](&a));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init(&b, k_sizes[i]));
        TEST_ASSERT_EQUAL_UINT32(k_sizes[i], a.n);
        TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
        TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, fns[i](NULL));
    }
}

static void test_unsupported_sizes(void)
{
    static const uint32_t bad[] = {0u, 1u, 2u, 8u, 15u, 17u, 48u, 96u, 1000u, 2048u, 4096u,
                                   0x80000000u, 0xFFFFFFFFu};
    uint32_t i;
    for (i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
        sbr_fft_t fft;
        memset(&fft, 0x5A, sizeof fft);
        TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_fft_init(&fft, bad[i]));
        TEST_ASSERT_EQUAL_INT(0, sbr_fft_size_supported(bad[i]));
        /* the rejected instance cannot be used by accident */
        TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_fft_forward(&fft, g_in, g_out));
    }
    for (i = 0; i < NSIZES; i++) {
        TEST_ASSERT_EQUAL_INT(1, sbr_fft_size_supported(k_sizes[i]));
    }
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fft_init(NULL, 64u));
}

static void test_bad_arguments_leave_output_untouched(void)
{
    sbr_fft_t fft;
    sbr_fft_t bad;
    const uint32_t n = 64u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init_64(&fft));
    fill_random(g_in, n, 5u);
    memset(g_out, 0x3C, sizeof g_out);
    memcpy(g_tmp, g_out, sizeof g_out);

    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fft_forward(NULL, g_in, g_out));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fft_forward(&fft, NULL, g_out));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fft_forward(&fft, g_in, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fft_inverse(NULL, g_in, g_out));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fft_inverse(&fft, NULL, g_out));

    memset(&bad, 0, sizeof bad); /* never initialised */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_fft_forward(&bad, g_in, g_out));
    bad = fft;
    bad.n = 128u; /* length overwritten: the integrity word no longer matches */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_fft_forward(&bad, g_in, g_out));
    bad = fft;
    bad.check ^= 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_fft_inverse(&bad, g_in, g_out));
    bad = fft;
    bad.twiddle[1] = NULL;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_fft_forward(&bad, g_in, g_out));
    bad = fft;
    bad.bitrev = sbr_fft_bitrev_32; /* table of another length */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_fft_forward(&bad, g_in, g_out));
    bad = fft;
    bad.stages = 7u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_fft_forward(&bad, g_in, g_out));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_fft_check(&bad));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fft_check(NULL));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_check(&fft));

    /* partial overlap is rejected; identical buffers are fine */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_OVERLAP, sbr_fft_forward(&fft, g_out, g_out + 1));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_OVERLAP, sbr_fft_inverse(&fft, g_out + 63, g_out));
    TEST_ASSERT_EQUAL_MEMORY(g_tmp, g_out, sizeof g_out);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_forward(&fft, g_in, g_out + 64));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_forward(&fft, g_out, g_out));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_forward_snr);
    RUN_TEST(test_inverse_snr);
    RUN_TEST(test_in_place_equals_out_of_place);
    RUN_TEST(test_roundtrip_is_identity);
    RUN_TEST(test_linearity);
    RUN_TEST(test_parseval);
    RUN_TEST(test_impulse_and_tone);
    RUN_TEST(test_twiddle_tables_exact);
    RUN_TEST(test_per_size_init_matches_generic);
    RUN_TEST(test_unsupported_sizes);
    RUN_TEST(test_bad_arguments_leave_output_untouched);
    return UNITY_END();
}
