// SPDX-License-Identifier: MIT
// sbr._sbr: the recogniser for Python (nanobind). Thin: the core's configuration, models
// and detections; statuses become exceptions (ValueError for bad input, MemoryError never:
// the workspace is allocated here, RuntimeError for the rest), the GIL is released while
// the core runs. The Python layer (sbr/__init__.py) adds the documentation and names.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <chrono>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <sstream>
#include <string>
#include <vector>

#include "bind_common.hpp"
#include "classes.hpp"
#include "model_io.hpp"

extern "C" {
#include "sbr/recog.h"
#include "sbr/status.h"
#include "sbr/models.h"
#include "sbr/recog_strips.h"
}

namespace nb = nanobind;
using sbr_py::raise_status;

namespace {

// The configuration's fields come from the core's table (recog.h, sbr_recog_field_at()):
// names, kinds, ranges and meanings are not repeated here.
sbr_field_t field(const std::string &name) {
    sbr_field_t f;
    if (sbr_recog_field_at(sbr_recog_field_find(name.c_str()), &f) != SBR_OK)
        throw nb::value_error(("unknown configuration field: " + name).c_str());
    return f;
}

std::string range_of(const sbr_field_t &f) {
    std::ostringstream s;
    if (f.kind == SBR_FIELD_F32)
        s << f.lo_f << " .. " << f.hi_f;
    else
        s << f.lo_u << " .. " << f.hi_u;
    return s.str();
}

uint32_t to_u32(const sbr_field_t &f, nb::handle value) {
    if (!nb::isinstance<nb::int_>(value) || nb::isinstance<nb::bool_>(value))
        throw nb::value_error((std::string(f.name) + ": an integer is needed").c_str());
    const long long v = nb::cast<long long>(value);
    if (v < 0 || v > 0xFFFFFFFFll)
        throw nb::value_error((std::string(f.name) + ": out of range " + range_of(f) + " (" + f.help + ")").c_str());
    return static_cast<uint32_t>(v);
}

// Writes one field from a Python value (a number; for a per-map-kind field a sequence of
// 1..4 integers, intensity, red, blue, yellow); ValueError naming the field for a wrong type.
void set_field(sbr_recog_config_t &cfg, const std::string &name, nb::handle value) {
    const sbr_field_t f = field(name);
    unsigned char *base = reinterpret_cast<unsigned char *>(&cfg) + f.offset;
    if (f.count > 1) {
        if (!nb::isinstance<nb::list>(value) && !nb::isinstance<nb::tuple>(value))
            throw nb::value_error((name + ": a list of 1 to 4 integers is needed (intensity, red, blue, yellow)").c_str());
        const nb::sequence seq = nb::borrow<nb::sequence>(value);
        const size_t n = nb::len(seq);
        if (n < 1 || n > f.count)
            throw nb::value_error((name + ": a list of 1 to 4 integers is needed (intensity, red, blue, yellow)").c_str());
        for (size_t k = 0; k < n; ++k) {
            const uint32_t u = to_u32(f, seq[k]);
            std::memcpy(base + 4u * k, &u, sizeof u);
        }
    } else if (f.kind == SBR_FIELD_F32) {
        if (!nb::isinstance<nb::float_>(value) && !nb::isinstance<nb::int_>(value))
            throw nb::value_error((name + ": a number is needed").c_str());
        const float v = static_cast<float>(nb::cast<double>(value));
        std::memcpy(base, &v, sizeof v);
    } else {
        const uint32_t u = to_u32(f, value);
        std::memcpy(base, &u, sizeof u);
    }
}

nb::object get_field(const sbr_recog_config_t &cfg, const sbr_field_t &f) {
    const unsigned char *base = reinterpret_cast<const unsigned char *>(&cfg) + f.offset;
    if (f.kind == SBR_FIELD_F32) {
        float v;
        std::memcpy(&v, base, sizeof v);
        return nb::float_(double(v));
    }
    std::vector<uint32_t> u(f.count);
    std::memcpy(u.data(), base, 4u * f.count);
    if (f.count == 1) return nb::int_(u[0]);
    nb::list l;
    for (uint32_t x : u) l.append(x);
    return l;
}

// The table as Python data: name -> (kind 'int'/'float', count, low, high, default, meaning).
nb::dict field_table() {
    nb::dict d;
    std::vector<sbr_field_t> all = sbr_host::recog_fields();
    for (const sbr_field_t &f : sbr_host::look_fields()) all.push_back(f);
    for (const sbr_field_t &f : all) {
        nb::object lo, hi, def;
        if (f.kind == SBR_FIELD_F32) {
            lo = nb::float_(double(f.lo_f));
            hi = nb::float_(double(f.hi_f));
            def = nb::float_(double(f.def_f));
        } else {
            lo = nb::int_(f.lo_u);
            hi = nb::int_(f.hi_u);
            if (f.count == 1) {
                def = nb::int_(f.def_u[0]);
            } else {
                nb::list l;
                for (uint32_t k = 0; k < f.count; ++k) l.append(f.def_u[k]);
                def = l;
            }
        }
        d[f.name] = nb::make_tuple(f.kind == SBR_FIELD_F32 ? "float" : "int", f.count, lo, hi, def,
                                   std::string(f.help));
    }
    return d;
}

uint32_t host_clock(void *) {
    return static_cast<uint32_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                                     std::chrono::steady_clock::now().time_since_epoch())
                                     .count());
}

const char *kStageNames[SBR_RECOG_STAGES] = {"parts", "votes", "group", "verify", "nms", "class"};

using Image = nb::ndarray<const uint8_t, nb::device::cpu>;

// The core's view of a numpy image: H x W x 3 (RGB or BGR) or H x W / H x W x 1 (grey),
// uint8, each row's pixels contiguous (any row stride). ValueError otherwise.
sbr_image_t image_view(const Image &a, bool bgr) {
    sbr_image_t v{};
    if (a.ndim() != 2 && a.ndim() != 3) throw nb::value_error("image: an H x W or H x W x C uint8 array is needed");
    const size_t h = a.shape(0), w = a.shape(1), c = a.ndim() == 3 ? a.shape(2) : 1;
    if (c != 1 && c != 3) throw nb::value_error("image: 1 or 3 channels are needed");
    if (h == 0 || w == 0) throw nb::value_error("image: an empty image");
    if (h > SBR_IMAGE_MAX_DIM || w > SBR_IMAGE_MAX_DIM)
        throw nb::value_error("image: larger than the core's largest side (16384)");
    const int64_t s0 = a.stride(0), s1 = a.stride(1), s2 = (a.ndim() == 3 && c > 1) ? a.stride(2) : 1;
    if (s1 != int64_t(c) || s2 != 1 || s0 < int64_t(w * c))
        throw nb::value_error("image: each row's pixels must be contiguous (use numpy.ascontiguousarray)");
    v.width = uint32_t(w);
    v.height = uint32_t(h);
    v.stride = uint32_t(s0);
    v.format = c == 1 ? SBR_PIXEL_GRAY8 : (bgr ? SBR_PIXEL_BGR888 : SBR_PIXEL_RGB888);
    v.data = a.data();
    return v;
}

class Recognizer {
public:
    Recognizer(nb::dict config, const std::string &model_path, const std::string &picto_path, bool no_picto,
               bool strips)
        : strips_(strips) {
        sbr_model_gtsdb(&builtin_);
        sbr_picto_gtsdb(&builtin_picto_);
        model_ = builtin_;
        class_stage_ = &builtin_picto_;
        if (!model_path.empty()) {
            const std::string e = sbr_host::load_model(model_path, loaded_);
            if (!e.empty()) throw nb::value_error(("model: " + e).c_str());
            model_ = loaded_.view;
            class_stage_ = loaded_.picto_view();
        }
        if (!picto_path.empty()) {
            const std::string e = sbr_host::load_picto(picto_path, picto_);
            if (!e.empty()) throw nb::value_error(("picto: " + e).c_str());
            class_stage_ = &picto_.view;
        } else if (no_picto) {
            class_stage_ = nullptr;
        }
        threshold_ = class_stage_ != nullptr ? class_stage_->threshold : model_.score_threshold;
        if (class_stage_ != nullptr) {  // a copy whose looks the configuration may set
            stage_ = *class_stage_;
            class_stage_ = &stage_;
        }
        if (strips_)
            sbr_recog_config_strips(&cfg_);  // a band's bounds (fields given below still apply)
        else
            sbr_recog_config_default(&cfg_);
        // as sbr_detect: the operating point, unless the configuration gives min_score (the
        // core's default floor, 0.3, is below the class stage's operating point)
        cfg_.min_score = std::min(threshold_, 0.999999f);
        for (auto kv : config) {
            const std::string name = nb::cast<std::string>(kv.first);
            if (sbr_recog_field_find(name.c_str()) == SBR_FIELD_NONE && look(name) != nullptr)
                set_look(name, kv.second);
            else
                set_field(cfg_, name, kv.second);
        }
        check_config();
        cfg_.clock = host_clock;
        // the models against the configuration, once (sbr_recog_init() on a token workspace)
        uint64_t token = 0;
        sbr_recog_t probe;
        const sbr_status_t st = sbr_recog_init(&probe, &cfg_, &model_, class_stage_, &token, sizeof token);
        if (st != SBR_OK) raise_status("the models with this configuration", st);
    }

    // Every detection with score >= min_score: (class, x, y, w, h, score, share, parts).
    std::vector<nb::tuple> detect(const Image &image, bool bgr, nb::object roi) {
        const sbr_image_t v = image_view(image, bgr);
        sbr_rect_t r{};
        const bool use_roi = !roi.is_none();
        if (use_roi && strips_) throw nb::value_error("roi: not with strips (the bands cover the whole frame)");
        if (use_roi) {
            const auto t = nb::cast<std::vector<long long>>(roi);
            if (t.size() != 4) throw nb::value_error("roi: (x, y, width, height)");
            for (long long x : t)
                if (x < 0 || x > 0xFFFFFFFFll) throw nb::value_error("roi: values out of range");
            r = {uint32_t(t[0]), uint32_t(t[1]), uint32_t(t[2]), uint32_t(t[3])};
        }
        const size_t need = strips_ ? sbr_recog_strip_workspace_size(&cfg_, v.width, v.height, SBR_RECOG_STRIP_ROWS)
                                    : sbr_recog_workspace_size(&cfg_, use_roi ? r.width : v.width,
                                                               use_roi ? r.height : v.height);
        if (need == 0) throw nb::value_error("image: too small for the configuration's maps");
        Workspace ws = acquire(need);
        std::vector<sbr_detection_t> dets(256);
        uint32_t n = 0;
        sbr_recog_stats_t stats{};
        sbr_status_t st;
        {
            nb::gil_scoped_release release;
            if (strips_)
                st = sbr_recog_detect_strips(&ws.rec, &v, SBR_RECOG_STRIP_ROWS, SBR_RECOG_STRIP_OVERLAP, dets.data(),
                                             uint32_t(dets.size()), &n, &stats);
            else
                st = sbr_recog_detect(&ws.rec, &v, use_roi ? &r : nullptr, dets.data(), uint32_t(dets.size()), &n,
                                      &stats);
        }
        release(std::move(ws));
        if (st != SBR_OK && st != SBR_ERR_CAPACITY) raise_status("detect", st);
        last_ = stats;
        std::vector<nb::tuple> out;
        for (uint32_t k = 0; k < n; ++k) {
            const sbr_detection_t &d = dets[k];
            out.push_back(nb::make_tuple(int(d.class_id), d.box.x, d.box.y, d.box.width, d.box.height,
                                         double(d.score), double(d.class_share), int(d.parts)));
        }
        return out;
    }

    size_t workspace_size(uint32_t width, uint32_t height) const {
        return strips_ ? sbr_recog_strip_workspace_size(&cfg_, width, height, SBR_RECOG_STRIP_ROWS)
                       : sbr_recog_workspace_size(&cfg_, width, height);
    }
    float threshold() const { return threshold_; }
    nb::dict config() const {
        nb::dict d;
        for (const sbr_field_t &f : sbr_host::recog_fields()) d[f.name] = get_field(cfg_, f);
        if (class_stage_ != nullptr)
            for (const sbr_field_t &f : sbr_host::look_fields()) {
                float v;
                std::memcpy(&v, reinterpret_cast<const unsigned char *>(&stage_) + f.offset, sizeof v);
                d[f.name] = double(v);
            }
        return d;
    }
    // The last call's counters and per-stage times in milliseconds (the core's clock).
    nb::dict stats() const {
        nb::dict d, ms;
        d["parts"] = last_.parts;
        d["votes"] = last_.votes;
        d["hypotheses"] = last_.hypotheses;
        d["classified"] = last_.classified;
        d["outlines"] = last_.outlines;
        d["capacity_hit"] = last_.capacity_hit;
        for (unsigned s = 0; s < SBR_RECOG_STAGES; ++s) ms[kStageNames[s]] = last_.stage_ticks[s] / 1000.0;
        d["stage_ms"] = ms;
        return d;
    }
    uint32_t classes() const { return model_.class_count; }

private:
    // Workspaces are kept for the next call (the core touches most of one: a fresh one
    // per call would cost its page faults each time); each concurrent call has its own.
    struct Workspace {
        std::unique_ptr<uint64_t[]> data;
        size_t bytes = 0;
        sbr_recog_t rec{};  // the recogniser set up on data (sbr_recog_init() once per workspace)
    };
    Workspace acquire(size_t need) {
        {
            std::lock_guard<std::mutex> lock(pool_mutex_);
            for (size_t i = 0; i < pool_.size(); ++i)
                if (pool_[i].bytes >= need) {
                    Workspace w = std::move(pool_[i]);
                    pool_.erase(pool_.begin() + long(i));
                    return w;
                }
        }
        Workspace w;
        w.data.reset(new uint64_t[need / 8 + 1]);
        w.bytes = (need / 8 + 1) * 8;
        const sbr_status_t st = sbr_recog_init(&w.rec, &cfg_, &model_, class_stage_, w.data.get(), w.bytes);
        if (st != SBR_OK) raise_status("detect", st);
        return w;
    }
    void release(Workspace w) {
        std::lock_guard<std::mutex> lock(pool_mutex_);
        if (pool_.size() < 8) pool_.push_back(std::move(w));
    }
    std::mutex pool_mutex_;
    std::vector<Workspace> pool_;

    // The core's verdict on the whole configuration, naming the field it blames
    // (sbr_recog_config_check_field()) with its range and meaning from the table.
    void check_config() {
        sbr_field_t bad;
        const sbr_field_t *f = sbr_recog_field_at(sbr_recog_config_check_field(&cfg_), &bad) == SBR_OK ? &bad : nullptr;
        if (f != nullptr)
            throw nb::value_error((std::string(f->name) + ": refused by the recogniser: out of range " + range_of(*f) +
                                   " or its rule with other fields (" + f->help + ")")
                                      .c_str());
        const sbr_status_t st = sbr_recog_config_check(&cfg_);
        if (st != SBR_OK) raise_status("the configuration", st);
    }

    sbr_model_t builtin_{}, model_{};
    // The look field named so (picto.h's table), or nullptr.
    static const sbr_field_t *look(const std::string &name) {
        static const std::vector<sbr_field_t> looks = sbr_host::look_fields();
        for (const sbr_field_t &f : looks)
            if (name == f.name) return &f;
        return nullptr;
    }
    // A look of the class stage in use (its copy), checked against the table's range.
    void set_look(const std::string &name, nb::handle value) {
        const sbr_field_t &f = *look(name);
        if (class_stage_ == nullptr) throw nb::value_error((name + ": a look of the class stage, and there is none").c_str());
        if (!nb::isinstance<nb::float_>(value) && !nb::isinstance<nb::int_>(value))
            throw nb::value_error((name + ": a number is needed").c_str());
        const float v = static_cast<float>(nb::cast<double>(value));
        if (!(v >= f.lo_f && v <= f.hi_f))
            throw nb::value_error((name + ": out of range " + range_of(f) + " (" + f.help + ")").c_str());
        std::memcpy(reinterpret_cast<unsigned char *>(&stage_) + f.offset, &v, sizeof v);
    }

    sbr_picto_model_t builtin_picto_{};
    sbr_picto_model_t stage_{};  // the class stage in use (tables borrowed), its looks as configured
    const sbr_picto_model_t *class_stage_ = nullptr;  // nullptr: none
    sbr_host::Model loaded_;
    sbr_host::Picto picto_;
    sbr_recog_config_t cfg_{};
    sbr_recog_stats_t last_{};
    float threshold_ = 0.5f;
    bool strips_ = false;  // the strip configuration (sbr_recog_config_strips, sbr_recog_detect_strips)
};

}  // namespace

NB_MODULE(_sbr, m) {
    m.doc() = "sbr's C core (see the sbr package for the documented API)";
    nb::class_<Recognizer>(m, "Recognizer")
        .def(nb::init<nb::dict, const std::string &, const std::string &, bool, bool>(), nb::arg("config"),
             nb::arg("model"), nb::arg("picto"), nb::arg("no_picto"), nb::arg("strips"))
        .def("detect", &Recognizer::detect, nb::arg("image").noconvert(), nb::arg("bgr"), nb::arg("roi").none())
        .def("workspace_size", &Recognizer::workspace_size)
        .def_prop_ro("threshold", &Recognizer::threshold)
        .def_prop_ro("config", &Recognizer::config)
        .def_prop_ro("stats", &Recognizer::stats)
        .def_prop_ro("classes", &Recognizer::classes);
    m.def("class_name", [](int c) { return std::string(sbr_host::class_name(c)); });
    m.def("superclass", &sbr_host::superclass_of);
    sbr_py::bind_tracker(m);
    sbr_py::bind_shapes(m);
    sbr_py::bind_can(m);
    sbr_py::bind_signs(m);
    sbr_py::bind_eval(m);
    m.def("field_names", []() {
        std::vector<std::string> n;
        for (const sbr_field_t &f : sbr_host::recog_fields()) n.push_back(f.name);
        for (const sbr_field_t &f : sbr_host::look_fields()) n.push_back(f.name);
        return n;
    });
    m.def("field_table", &field_table);
}
