// SPDX-License-Identifier: MIT
// sbr._sbr.evaluate: the evaluation of sbr_eval (host_tools/common/evaluation.hpp) for
// sbr.evaluate and sbr.regress, so an installed package reports without the checkout's
// tools. The report's text is sbr_eval's, byte for byte.
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "bind_common.hpp"
#include "evaluation.hpp"

namespace nb = nanobind;

namespace sbr_py {

namespace {

nb::list curves(const std::array<std::vector<std::pair<double, double>>, 4> &c) {
    nb::list out;
    for (const auto &curve : c) {
        nb::list one;
        for (const auto &p : curve) one.append(nb::make_tuple(p.first, p.second));
        out.append(one);
    }
    return out;
}

template <class T>
nb::list four(const std::array<T, 4> &a) {
    nb::list out;
    for (const T &v : a) out.append(v);
    return out;
}

nb::dict evaluate(const std::string &detections, const std::string &gt, const std::string &baseline,
                  const std::vector<int> &images, double iou, double threshold, size_t confusion, size_t list,
                  double max_drop, const std::string &plot_path) {
    sbr_host::EvalRequest q;
    q.detections = detections;
    q.gt = gt;
    q.baseline = baseline;
    q.images = images;
    q.iou = iou;
    q.threshold = threshold;
    q.confusion = confusion;
    q.list = list;
    q.max_drop = max_drop;
    q.plot_path = plot_path;
    sbr_host::EvalReport r;
    std::string error;
    bool ok = false;
    {
        nb::gil_scoped_release unlocked;
        ok = sbr_host::evaluate_files(q, r, error);
    }
    if (!ok) throw std::invalid_argument(error);
    nb::dict d;
    d["text"] = r.text;
    d["json"] = r.json;
    d["curve_op"] = curves(r.curve_op);
    d["curve_all"] = curves(r.curve_all);
    d["op_precision"] = four(r.op_precision);
    d["op_recall"] = four(r.op_recall);
    d["ap"] = four(r.ap);
    d["n_gt"] = four(r.n_gt);
    d["worst_drop"] = r.worst_drop;
    d["regression"] = r.regression;
    return d;
}

}  // namespace

void bind_eval(nb::module_ &m) {
    m.def("evaluate", &evaluate, nb::arg("detections"), nb::arg("gt"), nb::arg("baseline"), nb::arg("images"),
          nb::arg("iou"), nb::arg("threshold"), nb::arg("confusion"), nb::arg("list"), nb::arg("max_drop"),
          nb::arg("plot_path"));
}

}  // namespace sbr_py
