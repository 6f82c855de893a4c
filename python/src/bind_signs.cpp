// SPDX-License-Identifier: MIT
// sbr._sbr.SignTracker: the core's sign tracking (include/sbr/signs.h): detections of
// consecutive frames in, confirmed signs (class by summed evidence, once per pass) out.
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "bind_common.hpp"

extern "C" {
#include "sbr/signs.h"
}

namespace nb = nanobind;

namespace sbr_py {
namespace {

const ConfigField kSignsFields[] = {
    {"width", true, offsetof(sbr_signs_config_t, width)},
    {"height", true, offsetof(sbr_signs_config_t, height)},
    {"period_us", false, offsetof(sbr_signs_config_t, period_us)},
    {"class_count", false, offsetof(sbr_signs_config_t, class_count)},
    {"max_tracks", false, offsetof(sbr_signs_config_t, max_tracks)},
    {"confirm_hits", false, offsetof(sbr_signs_config_t, confirm_hits)},
    {"confirm_share", true, offsetof(sbr_signs_config_t, confirm_share)},
    {"max_misses", false, offsetof(sbr_signs_config_t, max_misses)},
    {"meas_sigma", true, offsetof(sbr_signs_config_t, meas_sigma)},
    {"min_certainty", true, offsetof(sbr_signs_config_t, min_certainty)},
};

void set_signs_field(sbr_signs_config_t &cfg, const std::string &name, nb::handle value) {
    set_config_field(&cfg, kSignsFields, name, nb::cast<double>(value), "sign-tracking");
}

class SignTracker {
public:
    explicit SignTracker(nb::dict fields) {
        auto defaults = [](sbr_signs_config_t &c) { sbr_signs_config_default(&c); };
        defaults(cfg_);
        for (auto kv : fields) set_signs_field(cfg_, nb::cast<std::string>(kv.first), kv.second);
        const sbr_status_t st = sbr_signs_config_check(&cfg_);
        if (st != SBR_OK)
            refuse_config<sbr_signs_config_t>(
                fields, st, "the sign tracking", "include/sbr/signs.h", defaults,
                [](sbr_signs_config_t &c, const std::string &n, nb::handle v) { set_signs_field(c, n, v); },
                [](const sbr_signs_config_t &c) { return sbr_signs_config_check(&c); });
        bytes_ = sbr_signs_workspace_size(&cfg_);
        ws_.reset(new uint64_t[bytes_ / 8 + 1]);
        check("sign tracking", sbr_signs_init(&s_, &cfg_, ws_.get(), bytes_));
    }

    // detections: (x, y, width, height, class_id, score) each; returns (signs, det_sign) with
    // signs as (id, class_id, flags, x, y, width, height, score, share, hits, frames).
    nb::tuple update(const std::vector<std::vector<double>> &dets, uint64_t now_us) {
        std::vector<sbr_detection_t> in(dets.size());
        for (size_t i = 0; i < dets.size(); ++i) {
            const std::vector<double> &d = dets[i];
            if (d.size() != 6) throw nb::value_error("a detection is (x, y, width, height, class_id, score)");
            for (int k = 0; k < 4; ++k)
                if (!(d[size_t(k)] >= 0.0 && d[size_t(k)] <= 4294967295.0))
                    throw nb::value_error("a detection's box: whole pixels >= 0 are needed");
            if (!(d[4] >= 0.0 && d[4] <= 65535.0)) throw nb::value_error("a detection's class_id is out of range");
            in[i].box = {uint32_t(d[0]), uint32_t(d[1]), uint32_t(d[2]), uint32_t(d[3])};
            in[i].class_id = uint16_t(d[4]);
            in[i].score = float(d[5]);
            in[i].class_share = 1.0f;
        }
        std::vector<uint32_t> det_sign(in.size());
        std::vector<sbr_sign_t> out(cfg_.max_tracks);
        uint32_t n = 0;
        sbr_status_t st;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            st = sbr_signs_update(&s_, now_us, in.empty() ? nullptr : in.data(), uint32_t(in.size()),
                                  det_sign.empty() ? nullptr : det_sign.data(), out.data(), uint32_t(out.size()), &n);
        }
        if (st != SBR_OK && st != SBR_ERR_CAPACITY)
            raise_status("update (a time not after the previous frame's, a score outside 0..1 or a class outside "
                         "class_count)",
                         st);
        capacity_hit_ = st == SBR_ERR_CAPACITY;
        std::vector<nb::tuple> signs;
        for (uint32_t i = 0; i < n; ++i) {
            const sbr_sign_t &g = out[i];
            signs.push_back(nb::make_tuple(g.id, int(g.class_id), int(g.flags), double(g.x), double(g.y),
                                           double(g.width), double(g.height), double(g.score), double(g.share),
                                           g.hits, g.frames));
        }
        return nb::make_tuple(signs, det_sign);
    }

    void reset() {
        std::lock_guard<std::mutex> lock(mutex_);
        check("reset", sbr_signs_reset(&s_));
    }

    nb::dict config() const { return config_dict(&cfg_, kSignsFields); }
    size_t workspace_size() const { return bytes_; }
    bool capacity_hit() const { return capacity_hit_; }

private:
    sbr_signs_config_t cfg_{};
    sbr_signs_t s_{};
    std::unique_ptr<uint64_t[]> ws_;
    size_t bytes_ = 0;
    bool capacity_hit_ = false;
    std::mutex mutex_;
};

}  // namespace

void bind_signs(nb::module_ &m) {
    nb::class_<SignTracker>(m, "SignTracker")
        .def(nb::init<nb::dict>(), nb::arg("fields"))
        .def("update", &SignTracker::update, nb::arg("detections"), nb::arg("now_us"))
        .def("reset", &SignTracker::reset)
        .def_prop_ro("config", &SignTracker::config)
        .def_prop_ro("workspace_size", &SignTracker::workspace_size)
        .def_prop_ro("capacity_hit", &SignTracker::capacity_hit);
    m.attr("SIGN_NEW") = SBR_SIGN_NEW;
    m.attr("SIGN_RENAMED") = SBR_SIGN_RENAMED;
    m.attr("SIGN_SEEN") = SBR_SIGN_SEEN;
}

}  // namespace sbr_py
