// SPDX-License-Identifier: MIT
// sbr._sbr: Fourier descriptors and their matching (include/sbr/fd.h), the ellipse fit
// (include/sbr/conic.h). Points come as N x 2 float32 arrays (the Python layer converts).
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/vector.h>

#include <complex>
#include <cstring>
#include <string>
#include <vector>

#include "bind_common.hpp"

extern "C" {
#include "sbr/conic.h"
#include "sbr/fd.h"
#include "sbr/fft.h"
}

namespace nb = nanobind;

namespace sbr_py {
namespace {

using Points = nb::ndarray<const float, nb::shape<-1, 2>, nb::c_contig, nb::device::cpu>;
using Coeffs = nb::ndarray<const std::complex<float>, nb::ndim<1>, nb::c_contig, nb::device::cpu>;

std::vector<sbr_pointf_t> to_points(const Points &p) {
    if (p.shape(0) > 0xFFFFFFFFu) throw nb::value_error("points: too many");
    std::vector<sbr_pointf_t> v(p.shape(0));
    for (size_t i = 0; i < v.size(); ++i) v[i] = {p(i, 0), p(i, 1)};
    return v;
}

sbr_fft_t make_fft(uint32_t n, const char *what) {
    sbr_fft_t fft;
    const sbr_status_t st = sbr_fft_init(&fft, n);
    if (st != SBR_OK)
        throw nb::value_error((std::string(what) + ": a power of two in 16 .. 1024 is needed (" +
                               sbr_status_str(st) + ")")
                                  .c_str());
    return fft;
}

// A descriptor: the core's struct, validated on every way in.
struct FD {
    sbr_fd_t fd{};

    uint32_t m() const { return fd.m; }
    double scale() const { return double(fd.scale); }
    nb::tuple centroid() const { return nb::make_tuple(double(fd.cx), double(fd.cy)); }
    // C(-M) .. C(M) as complex64 (a copy; C(0) is 0).
    nb::ndarray<nb::numpy, std::complex<float>> coefficients() const {
        const size_t n = 2u * fd.m + 1u;
        auto *data = new std::complex<float>[n];
        std::memcpy(data, fd.c, n * sizeof(sbr_complex_t));
        nb::capsule owner(data, [](void *p) noexcept { delete[] static_cast<std::complex<float> *>(p); });
        return nb::ndarray<nb::numpy, std::complex<float>>(data, {n}, owner);
    }
    FD mirror() const {
        FD r;
        check("mirror", sbr_fd_mirror(&fd, &r.fd));
        return r;
    }
    FD smooth(float sigma) const {
        FD r;
        check("smooth (sigma 0 .. 0.5)", sbr_fd_smooth(&fd, sigma, &r.fd));
        return r;
    }
};

static_assert(sizeof(sbr_complex_t) == sizeof(std::complex<float>), "complex layout");

FD fd_from_coefficients(const Coeffs &c, float scale, float cx, float cy) {
    const size_t n = c.shape(0);
    if (n < 3 || n % 2 == 0 || n > 2u * SBR_FD_MAX_M + 1u)
        throw nb::value_error("coefficients: 2M + 1 values with M in 1 .. 32 are needed");
    FD r;
    r.fd.m = uint32_t(n / 2);
    r.fd.scale = scale;
    r.fd.cx = cx;
    r.fd.cy = cy;
    std::memcpy(r.fd.c, c.data(), n * sizeof(sbr_complex_t));
    check("descriptor", sbr_fd_check(&r.fd, nullptr));
    return r;
}

FD fd_descriptor(const Points &p, uint32_t m, uint32_t samples) {
    const std::vector<sbr_pointf_t> pts = to_points(p);
    const sbr_fft_t fft = make_fft(samples, "samples");
    std::vector<sbr_complex_t> work(samples);
    FD r;
    sbr_status_t st;
    {
        nb::gil_scoped_release release;
        st = sbr_fd_from_pointsf(&fft, pts.data(), uint32_t(pts.size()), m, work.data(), samples, &r.fd);
    }
    check("descriptor", st);
    return r;
}

// (errors, rotations, shifts, scale ratios) as lists, and the best index.
nb::tuple fd_match(const FD &query, const std::vector<const FD *> &protos, int mode, float max_rotation,
                   bool refine, float max_error, uint32_t lags) {
    if (protos.empty()) throw nb::value_error("prototypes: at least one is needed");
    if (protos.size() > 0xFFFFFFFFu) throw nb::value_error("prototypes: too many");
    sbr_fd_match_config_t cfg;
    sbr_fd_match_config_default(&cfg);
    cfg.mode = mode ? SBR_FD_ROTATION_COVARIANT : SBR_FD_ROTATION_INVARIANT;
    cfg.max_rotation = max_rotation;
    cfg.refine = refine ? 1 : 0;
    cfg.max_error = max_error;
    check("match options", sbr_fd_match_config_check(&cfg));
    const sbr_fft_t fft = make_fft(lags, "lags");
    std::vector<sbr_fd_t> table(protos.size());
    for (size_t i = 0; i < protos.size(); ++i) {
        if (protos[i] == nullptr) throw nb::value_error("prototypes: None is not a descriptor");
        table[i] = protos[i]->fd;
    }
    std::vector<sbr_complex_t> work(SBR_FD_TABLE_WORK_LEN(lags));
    std::vector<sbr_fd_match_t> res(table.size());
    uint32_t best = 0;
    sbr_status_t st;
    {
        nb::gil_scoped_release release;
        st = sbr_fd_match_table(&fft, &cfg, &query.fd, table.data(), uint32_t(table.size()), work.data(),
                                uint32_t(work.size()), res.data(), &best);
    }
    check("match", st);
    std::vector<double> e, r, s, k;
    for (const sbr_fd_match_t &x : res) {
        e.push_back(double(x.error));
        r.push_back(double(x.rotation));
        s.push_back(double(x.shift));
        k.push_back(double(x.scale_ratio));
    }
    return nb::make_tuple(e, r, s, k, best);
}

// (conic a, b, c, d, e, f), (cx, cy, semi_major, semi_minor, angle), rms, max residual.
nb::tuple ellipse_fit(const Points &p) {
    const std::vector<sbr_pointf_t> pts = to_points(p);
    sbr_conic_t c{};
    sbr_ellipse_t e{};
    float rms = 0.0f, mx = 0.0f;
    sbr_status_t st;
    {
        nb::gil_scoped_release release;
        st = sbr_ellipse_fit(pts.data(), uint32_t(pts.size()), &c, &e);
        if (st == SBR_OK) st = sbr_conic_residual(&c, pts.data(), uint32_t(pts.size()), &rms, &mx);
    }
    check("ellipse_fit", st);
    return nb::make_tuple(nb::make_tuple(double(c.a), double(c.b), double(c.c), double(c.d), double(c.e), double(c.f)),
                          nb::make_tuple(double(e.cx), double(e.cy), double(e.semi_major), double(e.semi_minor),
                                         double(e.angle)),
                          double(rms), double(mx));
}

}  // namespace

void bind_shapes(nb::module_ &m) {
    nb::class_<FD>(m, "FD")
        .def_prop_ro("m", &FD::m)
        .def_prop_ro("scale", &FD::scale)
        .def_prop_ro("centroid", &FD::centroid)
        .def_prop_ro("coefficients", &FD::coefficients, nb::rv_policy::move)
        .def("mirror", &FD::mirror)
        .def("smooth", &FD::smooth, nb::arg("sigma"));
    m.def("fd_from_coefficients", &fd_from_coefficients, nb::arg("coefficients"), nb::arg("scale"), nb::arg("cx"),
          nb::arg("cy"));
    m.def("fd_descriptor", &fd_descriptor, nb::arg("points"), nb::arg("m"), nb::arg("samples"));
    m.def("fd_match", &fd_match, nb::arg("query"), nb::arg("protos"), nb::arg("mode"), nb::arg("max_rotation"),
          nb::arg("refine"), nb::arg("max_error"), nb::arg("lags"));
    m.def("ellipse_fit", &ellipse_fit, nb::arg("points"));
    m.attr("FD_MAX_M") = SBR_FD_MAX_M;
}

}  // namespace sbr_py
