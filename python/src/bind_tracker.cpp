// SPDX-License-Identifier: MIT
// sbr._sbr.Tracker: the channel-representation tracker (include/sbr/track.h) with the
// built-in KITTI model or a constant-velocity model; the GIL is released while a step runs.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "bind_common.hpp"

extern "C" {
#include "sbr/track.h"
#include "sbr/models.h"
}

namespace nb = nanobind;

namespace sbr_py {
namespace {

const ConfigField kTrackFields[] = {
    {"max_targets", false, offsetof(sbr_track_config_t, max_targets)},
    {"window", false, offsetof(sbr_track_config_t, window)},
    {"meas_sigma", true, offsetof(sbr_track_config_t, meas_sigma)},
    {"gate", true, offsetof(sbr_track_config_t, gate)},
    {"confirm_hits", false, offsetof(sbr_track_config_t, confirm_hits)},
    {"max_misses", false, offsetof(sbr_track_config_t, max_misses)},
};

void set_track_field(sbr_track_config_t &cfg, const std::string &name, double value) {
    set_config_field(&cfg, kTrackFields, name, value, "tracker");
}

using Dets = nb::ndarray<const float, nb::ndim<2>, nb::c_contig, nb::device::cpu>;

class Tracker {
public:
    // model "kitti" (the built-in learned model; width/height ignored) or "cv" (constant
    // velocity over a width x height frame at `period` seconds per frame).
    Tracker(const std::string &model, float width, float height, float period, uint32_t vel_count,
            float vel_spacing, float accel_sigma, float birth_sigma, nb::dict fields) {
        if (model == "kitti") {
            check("model", sbr_track_model_kitti(&model_));
        } else if (model == "cv") {
            if (vel_count > SBR_TRACK_MAX_VEL) throw nb::value_error("vel_count: at most 127");
            trans_.resize(SBR_TRACK_MODEL_TRANSITION_LEN(3, 3, vel_count));
            birth_.resize(SBR_TRACK_MODEL_BIRTH_LEN(3, 3, vel_count));
            const sbr_status_t st = sbr_track_model_cv(&model_, width, height, period, vel_count, vel_spacing,
                                                       accel_sigma, birth_sigma, trans_.data(), trans_.size(),
                                                       birth_.data(), birth_.size());
            if (st != SBR_OK)
                raise_status("constant-velocity model (width, height, period, vel_count, vel_spacing, accel_sigma, "
                             "birth_sigma)",
                             st);
        } else {
            throw nb::value_error(("model: 'kitti' or 'cv', not '" + model + "'").c_str());
        }
        const bool kitti = model == "kitti";
        auto defaults = [this, kitti](sbr_track_config_t &c) {
            sbr_track_config_default(&c);
            if (kitti) c.window = 25;  // the window the KITTI model was learned for
            c.model = &model_;
        };
        auto set = [](sbr_track_config_t &c, const std::string &name, nb::handle v) {
            set_track_field(c, name, nb::cast<double>(v));
        };
        defaults(cfg_);
        for (auto kv : fields) set(cfg_, nb::cast<std::string>(kv.first), kv.second);
        const sbr_status_t st = sbr_track_config_check(&cfg_);
        if (st != SBR_OK)
            refuse_config<sbr_track_config_t>(fields, st, "the tracker", "include/sbr/track.h", defaults, set,
                                              [](const sbr_track_config_t &c) { return sbr_track_config_check(&c); });
        bytes_ = sbr_track_workspace_size(&cfg_);
        ws_.reset(new uint64_t[bytes_ / 8 + 1]);
        check("tracker", sbr_track_init(&trk_, &cfg_, ws_.get(), bytes_));
    }

    // (id, x, y, vx, vy, certainty, hits, misses, age, detection, flags) per live target.
    std::vector<nb::tuple> step(const Dets &dets, uint32_t dt_us) {
        if (dets.shape(1) != 3) throw nb::value_error("detections: an N x 3 array (x, y, certainty) is needed");
        if (dets.shape(0) > SBR_TRACK_MAX_DETECTIONS) throw nb::value_error("detections: at most 256 per step");
        const uint32_t n = uint32_t(dets.shape(0));
        std::vector<sbr_track_detection_t> in(n);
        for (uint32_t i = 0; i < n; ++i) in[i] = {dets(i, 0), dets(i, 1), dets(i, 2)};
        sbr_track_target_t out[SBR_TRACK_MAX_TARGETS];
        uint32_t count = 0;
        sbr_status_t st;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            nb::gil_scoped_release release;
            st = sbr_track_step(&trk_, dt_us, n ? in.data() : nullptr, n, out, SBR_TRACK_MAX_TARGETS, &count);
        }
        if (st != SBR_OK && st != SBR_ERR_CAPACITY) raise_status("step", st);
        capacity_hit_ = st == SBR_ERR_CAPACITY;
        std::vector<nb::tuple> r;
        for (uint32_t i = 0; i < count; ++i) {
            const sbr_track_target_t &t = out[i];
            r.push_back(nb::make_tuple(t.id, double(t.x), double(t.y), double(t.vx), double(t.vy),
                                       double(t.certainty), t.hits, t.misses, t.age, int(t.detection), t.flags));
        }
        return r;
    }

    void reset() {
        std::lock_guard<std::mutex> lock(mutex_);
        check("reset", sbr_track_reset(&trk_));
        capacity_hit_ = false;
    }

    nb::dict config() const { return config_dict(&cfg_, kTrackFields); }
    size_t workspace_size() const { return bytes_; }
    bool capacity_hit() const { return capacity_hit_; }
    float period() const { return model_.period; }
    nb::tuple extent() const { return nb::make_tuple(double(model_.extent[0]), double(model_.extent[1])); }

private:
    sbr_track_model_t model_{};
    std::vector<float> trans_, birth_;
    sbr_track_config_t cfg_{};
    sbr_track_t trk_{};
    std::unique_ptr<uint64_t[]> ws_;
    size_t bytes_ = 0;
    bool capacity_hit_ = false;
    std::mutex mutex_;
};

}  // namespace

void bind_tracker(nb::module_ &m) {
    nb::class_<Tracker>(m, "Tracker")
        .def(nb::init<const std::string &, float, float, float, uint32_t, float, float, float, nb::dict>(),
             nb::arg("model"), nb::arg("width"), nb::arg("height"), nb::arg("period"), nb::arg("vel_count"),
             nb::arg("vel_spacing"), nb::arg("accel_sigma"), nb::arg("birth_sigma"), nb::arg("fields"))
        .def("step", &Tracker::step, nb::arg("detections"), nb::arg("dt_us"))
        .def("reset", &Tracker::reset)
        .def_prop_ro("config", &Tracker::config)
        .def_prop_ro("workspace_size", &Tracker::workspace_size)
        .def_prop_ro("capacity_hit", &Tracker::capacity_hit)
        .def_prop_ro("period", &Tracker::period)
        .def_prop_ro("extent", &Tracker::extent);
    m.attr("TRACK_CONFIRMED") = SBR_TRACK_CONFIRMED;
    m.attr("TRACK_UPDATED") = SBR_TRACK_UPDATED;
    m.attr("TRACK_BORN") = SBR_TRACK_BORN;
    m.attr("TRACK_MAX_DETECTIONS") = SBR_TRACK_MAX_DETECTIONS;
}

}  // namespace sbr_py
