// SPDX-License-Identifier: MIT
// sbr_bench_fft: times sbr's FFT against FFTW (SIMD and scalar) and KissFFT in one run.
//
// For each N it runs rounds; in every round each method transforms the same input a fixed
// number of times (interleaved, so drift of the machine hits all methods alike), and the
// median over rounds of the time per transform is reported.
#include <fftw3.h>
#include <kissfft/kiss_fft.h>

#include "cli_core.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

extern "C" {
#include "sbr/fft.h"
}

namespace {

struct Options {
    bool csv = false;
    int rounds = 41;
    double round_ms = 4.0;
    std::vector<unsigned> sizes{64, 128, 256, 512, 1024};
};


using Clock = std::chrono::steady_clock;

template <class F>
double time_batch(F &&fn, int reps) {
    const auto t0 = Clock::now();
    for (int i = 0; i < reps; ++i) fn();
    const auto t1 = Clock::now();
    return std::chrono::duration<double, std::nano>(t1 - t0).count() / reps;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

volatile float g_sink;  // keeps results observable so no transform is optimised away

struct Row {
    unsigned n;
    double sbr, fftw, nosimd, kiss;
};

// -1: go on; otherwise the exit status.
int parse_options(int argc, char **argv, Options &opt) {
    CLI::App app{"sbr_bench_fft: complex float32 out-of-place forward FFTs of sbr, FFTW with SIMD "
                 "(FFTW_MEASURE), FFTW restricted to scalar code (FFTW_NO_SIMD) and KissFFT, interleaved "
                 "in one run; the median ns per transform over the rounds (docs/usage/bench_fft.md)"};
    app.add_flag("--csv", opt.csv, "print exactly 'n,sbr_ns,fftw_ns,fftw_nosimd_ns,kissfft_ns' and one row per length");
    app.add_option("--rounds", opt.rounds, "rounds per method")->check(CLI::Range(3, 100000))->capture_default_str();
    app.add_option("--round-ms", opt.round_ms, "milliseconds per round")
        ->check(sbr_host::finite_range(0.1, 10000.0))
        ->capture_default_str();
    app.add_option("--sizes", opt.sizes, "transform lengths")
        ->delimiter(',')
        ->check(CLI::IsMember({16u, 32u, 64u, 128u, 256u, 512u, 1024u}))
        ->type_name("N[,N...]");
    return sbr_host::parse_cli(app, argc, argv);
}

// One length: the four FFTs planned, cross-checked on the same random input (a benchmark
// of a wrong FFT would be worthless) and timed in interleaved rounds. 0, or the exit
// status.
int measure(unsigned n, const Options &opt, std::mt19937 &rng, Row &row) {
    std::uniform_real_distribution<float> dist(-1.0f, 1.0f);
    sbr_fft_t sf;
    if (sbr_fft_init(&sf, n) != SBR_OK) {
        std::fprintf(stderr, "sbr_bench_fft: unsupported length %u\n", n);
        return 2;
    }
    fftwf_complex *fin = fftwf_alloc_complex(n), *fout = fftwf_alloc_complex(n);
    fftwf_complex *gin = fftwf_alloc_complex(n), *gout = fftwf_alloc_complex(n);
    fftwf_plan p_simd = fftwf_plan_dft_1d(static_cast<int>(n), fin, fout, FFTW_FORWARD, FFTW_MEASURE);
    fftwf_plan p_scalar = fftwf_plan_dft_1d(static_cast<int>(n), gin, gout, FFTW_FORWARD,
                                            FFTW_MEASURE | FFTW_NO_SIMD);
    kiss_fft_cfg kcfg = kiss_fft_alloc(static_cast<int>(n), 0, nullptr, nullptr);
    if (!p_simd || !p_scalar || !kcfg) {
        std::fprintf(stderr, "sbr_bench_fft: could not plan N=%u\n", n);
        return 1;
    }
    std::vector<sbr_complex_t> sin_(n), sout(n);
    std::vector<kiss_fft_cpx> kin(n), kout(n);
    for (unsigned i = 0; i < n; ++i) {
        const float re = dist(rng), im = dist(rng);
        sin_[i] = {re, im};
        fin[i][0] = gin[i][0] = re;
        fin[i][1] = gin[i][1] = im;
        kin[i].r = re;
        kin[i].i = im;
    }
    auto run_sbr = [&] { (void)sbr_fft_forward(&sf, sin_.data(), sout.data()); };
    auto run_fftw = [&] { fftwf_execute(p_simd); };
    auto run_nosimd = [&] { fftwf_execute(p_scalar); };
    auto run_kiss = [&] { kiss_fft(kcfg, kin.data(), kout.data()); };

    // Sanity: every method computes the same transform (a benchmark of a wrong FFT
    // would be worthless).
    run_sbr(); run_fftw(); run_nosimd(); run_kiss();
    double err = 0.0, ref = 0.0;
    for (unsigned i = 0; i < n; ++i) {
        const double r0 = fout[i][0], i0 = fout[i][1];
        ref += r0 * r0 + i0 * i0;
        err += std::pow(sout[i].re - r0, 2) + std::pow(sout[i].im - i0, 2) +
               std::pow(gout[i][0] - r0, 2) + std::pow(gout[i][1] - i0, 2) +
               std::pow(kout[i].r - r0, 2) + std::pow(kout[i].i - i0, 2);
    }
    if (err > 1e-8 * ref) {
        std::fprintf(stderr, "sbr_bench_fft: results disagree at N=%u\n", n);
        return 1;
    }

    // Calibrate repetitions so one batch of the slowest method lasts about round_ms.
    const double est = time_batch(run_kiss, 200);
    const int reps = std::max(10, static_cast<int>(opt.round_ms * 1e6 / std::max(est, 1.0)));
    std::vector<double> ts, tf, tn, tk;
    for (int r = 0; r < opt.rounds; ++r) {
        ts.push_back(time_batch(run_sbr, reps));
        tf.push_back(time_batch(run_fftw, reps));
        tn.push_back(time_batch(run_nosimd, reps));
        tk.push_back(time_batch(run_kiss, reps));
    }
    g_sink = sout[1].re + fout[1][0] + gout[1][0] + kout[1].r;
    row = {n, median(ts), median(tf), median(tn), median(tk)};

    fftwf_destroy_plan(p_simd);
    fftwf_destroy_plan(p_scalar);
    fftwf_free(fin); fftwf_free(fout); fftwf_free(gin); fftwf_free(gout);
    kiss_fft_free(kcfg);
    return 0;
}

void report(const Options &opt, const std::vector<Row> &rows) {
    bool ok = true;
    if (opt.csv) {
        std::printf("n,sbr_ns,fftw_ns,fftw_nosimd_ns,kissfft_ns\n");
        for (const Row &r : rows)
            std::printf("%u,%.1f,%.1f,%.1f,%.1f\n", r.n, r.sbr, r.fftw, r.nosimd, r.kiss);
        std::printf("# ratios: n,sbr/fftw_nosimd (target <= 1.2),sbr/kissfft (target <= 0.8),sbr/fftw_simd (information)\n");
    } else {
        std::printf("%6s %12s %12s %16s %12s %14s %12s\n", "N", "sbr ns", "FFTW ns", "FFTW scalar ns",
                    "KissFFT ns", "sbr/FFTWsc", "sbr/Kiss");
    }
    for (const Row &r : rows) {
        const double q1 = r.sbr / r.nosimd, q2 = r.sbr / r.kiss, q3 = r.sbr / r.fftw;
        const bool met = q1 <= 1.2 && q2 <= 0.8;
        ok = ok && met;
        if (opt.csv)
            std::printf("# %u,%.2f,%.2f,%.2f%s\n", r.n, q1, q2, q3, met ? "" : ",TARGET MISSED");
        else
            std::printf("%6u %12.1f %12.1f %16.1f %12.1f %14.2f %12.2f%s\n", r.n, r.sbr, r.fftw, r.nosimd,
                        r.kiss, q1, q2, met ? "" : "  (target missed)");
    }
    std::printf("# targets %s: sbr <= 1.2x FFTW scalar and <= 0.8x KissFFT at every N\n",
                ok ? "met" : "NOT met");
}

}  // namespace

int main(int argc, char **argv) {
    Options opt;
    const int parsed = parse_options(argc, argv, opt);
    if (parsed >= 0) return parsed;
    std::vector<Row> rows;
    std::mt19937 rng(12345);
    for (unsigned n : opt.sizes) {
        Row row{};
        const int st = measure(n, opt, rng, row);
        if (st != 0) return st;
        rows.push_back(row);
        if (!opt.csv) std::fprintf(stderr, "\rN=%u done", n);
    }
    if (!opt.csv) std::fprintf(stderr, "\n");
    report(opt, rows);
    return 0;
}
