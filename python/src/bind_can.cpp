// SPDX-License-Identifier: MIT
// sbr._sbr: the CAN messages of dbc/sbr.dbc (include/sbr/can.h): pack/unpack by message
// name with the core's field names, and the E2E sender and receiver.
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <cstring>
#include <string>
#include <vector>

#include "bind_common.hpp"

extern "C" {
#include "sbr/can.h"
}

namespace nb = nanobind;

namespace sbr_py {
namespace {

struct Field {
    const char *name;
    bool is_float;
    size_t offset;
};
struct Message {
    const char *name;
    uint32_t id;
    std::vector<Field> fields;
};

#define F(type, f) {#f, true, offsetof(type, f)}
#define U(type, f) {#f, false, offsetof(type, f)}
const std::vector<Message> &messages() {
    static const std::vector<Message> m = {
        {"SBR_ConfirmedSign",
         SBR_CAN_ID_CONFIRMED_SIGN,
         {U(sbr_can_confirmed_sign_t, slot), U(sbr_can_confirmed_sign_t, count), U(sbr_can_confirmed_sign_t, class_id),
          U(sbr_can_confirmed_sign_t, track_id), U(sbr_can_confirmed_sign_t, speed_kmh),
          F(sbr_can_confirmed_sign_t, confidence), U(sbr_can_confirmed_sign_t, age_frames)}},
        {"SBR_EcuStatus",
         SBR_CAN_ID_ECU_STATUS,
         {U(sbr_can_ecu_status_t, frame_counter), F(sbr_can_ecu_status_t, processing_ms),
          U(sbr_can_ecu_status_t, region_count), U(sbr_can_ecu_status_t, detection_count),
          U(sbr_can_ecu_status_t, overload), U(sbr_can_ecu_status_t, error), U(sbr_can_ecu_status_t, capacity_hit)}},
        {"SBR_Detection",
         SBR_CAN_ID_DETECTION,
         {U(sbr_can_detection_t, class_id), F(sbr_can_detection_t, confidence), F(sbr_can_detection_t, center_x),
          F(sbr_can_detection_t, center_y), F(sbr_can_detection_t, width), F(sbr_can_detection_t, height),
          U(sbr_can_detection_t, track_id)}},
        {"SBR_TrackedObject",
         SBR_CAN_ID_TRACKED_OBJECT,
         {U(sbr_can_object_t, index), U(sbr_can_object_t, track_id), F(sbr_can_object_t, x), F(sbr_can_object_t, y),
          F(sbr_can_object_t, vx), F(sbr_can_object_t, vy), F(sbr_can_object_t, certainty)}},
        {"SBR_Restrictions",
         SBR_CAN_ID_RESTRICTIONS,
         {U(sbr_can_restrictions_t, speed_limit_kmh), U(sbr_can_restrictions_t, no_overtaking),
          U(sbr_can_restrictions_t, no_overtaking_trucks), U(sbr_can_restrictions_t, priority_road),
          U(sbr_can_restrictions_t, speed_age_s)}},
    };
    return m;
}
#undef F
#undef U

const Message &by_name(const std::string &name) {
    for (const Message &m : messages())
        if (name == m.name) return m;
    throw nb::value_error(("unknown message: " + name +
                           " (SBR_ConfirmedSign, SBR_EcuStatus, SBR_Restrictions, SBR_Detection, SBR_TrackedObject)")
                              .c_str());
}

const Message &by_id(uint32_t id) {
    for (const Message &m : messages())
        if (id == m.id) return m;
    throw nb::value_error(("frame id " + std::to_string(id) + ": not an sbr message").c_str());
}

sbr_can_frame_t frame_of(uint32_t id, const nb::bytes &data) {
    if (data.size() > 8) throw nb::value_error("data: at most 8 bytes");
    sbr_can_frame_t f{};
    f.id = id;
    f.dlc = uint8_t(data.size());
    std::memcpy(f.data, data.c_str(), data.size());
    return f;
}

nb::bytes bytes_of(const sbr_can_frame_t &f) { return nb::bytes(reinterpret_cast<const char *>(f.data), f.dlc); }

// The message's struct, every field from `values` (all are required, none unknown).
template <typename T>
T fill(const Message &m, nb::dict values) {
    T s{};
    unsigned char *base = reinterpret_cast<unsigned char *>(&s);
    for (const Field &f : m.fields) {
        if (!values.contains(f.name)) throw nb::value_error((std::string(m.name) + ": " + f.name + " is missing").c_str());
        nb::handle v = values[f.name];
        if (f.is_float) {
            if (!nb::isinstance<nb::float_>(v) && !nb::isinstance<nb::int_>(v))
                throw nb::value_error((std::string(f.name) + ": a number is needed").c_str());
            const float x = float(nb::cast<double>(v));
            std::memcpy(base + f.offset, &x, sizeof x);
        } else {
            if (!nb::isinstance<nb::int_>(v) || nb::isinstance<nb::bool_>(v))
                throw nb::value_error((std::string(f.name) + ": an integer is needed").c_str());
            const long long x = nb::cast<long long>(v);
            if (x < 0 || x > 0xFFFFFFFFll)
                throw nb::value_error((std::string(f.name) + ": out of its signal's range").c_str());
            const uint32_t u = uint32_t(x);
            std::memcpy(base + f.offset, &u, sizeof u);
        }
    }
    if (values.size() != m.fields.size())  // every field is there: the rest are unknown
        for (auto kv : values) {
            const std::string k = nb::cast<std::string>(kv.first);
            bool known = false;
            for (const Field &f : m.fields) known = known || k == f.name;
            if (!known) throw nb::value_error((std::string(m.name) + ": unknown signal " + k).c_str());
        }
    return s;
}

template <typename T>
nb::dict dict_of(const Message &m, const T &s) {
    nb::dict d;
    const unsigned char *base = reinterpret_cast<const unsigned char *>(&s);
    for (const Field &f : m.fields) {
        if (f.is_float) {
            float x;
            std::memcpy(&x, base + f.offset, sizeof x);
            d[f.name] = double(x);
        } else {
            uint32_t u;
            std::memcpy(&u, base + f.offset, sizeof u);
            d[f.name] = u;
        }
    }
    return d;
}

// (frame id, 8 bytes) of a message, E2E bytes zero.
nb::tuple pack(const std::string &name, nb::dict values) {
    const Message &m = by_name(name);
    sbr_can_frame_t f{};
    sbr_status_t st;
    switch (m.id) {
    case SBR_CAN_ID_CONFIRMED_SIGN: {
        const auto s = fill<sbr_can_confirmed_sign_t>(m, values);
        st = sbr_can_pack_confirmed_sign(&s, &f);
        break;
    }
    case SBR_CAN_ID_ECU_STATUS: {
        const auto s = fill<sbr_can_ecu_status_t>(m, values);
        st = sbr_can_pack_ecu_status(&s, &f);
        break;
    }
    case SBR_CAN_ID_DETECTION: {
        const auto s = fill<sbr_can_detection_t>(m, values);
        st = sbr_can_pack_detection(&s, &f);
        break;
    }
    case SBR_CAN_ID_RESTRICTIONS: {
        const auto s = fill<sbr_can_restrictions_t>(m, values);
        st = sbr_can_pack_restrictions(&s, &f);
        break;
    }
    default: {
        const auto s = fill<sbr_can_object_t>(m, values);
        st = sbr_can_pack_object(&s, &f);
        break;
    }
    }
    if (st != SBR_OK) raise_status((std::string("pack ") + m.name + " (a value outside its signal's range)").c_str(), st);
    return nb::make_tuple(f.id, bytes_of(f));
}

// (message name, values) of a frame.
nb::tuple unpack(uint32_t id, const nb::bytes &data) {
    const Message &m = by_id(id);
    const sbr_can_frame_t f = frame_of(id, data);
    nb::dict d;
    sbr_status_t st;
    switch (m.id) {
    case SBR_CAN_ID_CONFIRMED_SIGN: {
        sbr_can_confirmed_sign_t s{};
        st = sbr_can_unpack_confirmed_sign(&f, &s);
        if (st == SBR_OK) d = dict_of(m, s);
        break;
    }
    case SBR_CAN_ID_ECU_STATUS: {
        sbr_can_ecu_status_t s{};
        st = sbr_can_unpack_ecu_status(&f, &s);
        if (st == SBR_OK) d = dict_of(m, s);
        break;
    }
    case SBR_CAN_ID_DETECTION: {
        sbr_can_detection_t s{};
        st = sbr_can_unpack_detection(&f, &s);
        if (st == SBR_OK) d = dict_of(m, s);
        break;
    }
    case SBR_CAN_ID_RESTRICTIONS: {
        sbr_can_restrictions_t s{};
        st = sbr_can_unpack_restrictions(&f, &s);
        if (st == SBR_OK) d = dict_of(m, s);
        break;
    }
    default: {
        sbr_can_object_t s{};
        st = sbr_can_unpack_object(&f, &s);
        if (st == SBR_OK) d = dict_of(m, s);
        break;
    }
    }
    if (st == SBR_ERR_SIZE) raise_status((std::string("unpack ") + m.name + " (8 data bytes are needed)").c_str(), st);
    if (st != SBR_OK)
        raise_status((std::string("unpack ") + m.name + " (a signal outside its range: corrupted or foreign)").c_str(),
                     st);
    return nb::make_tuple(std::string(m.name), d);
}

class E2ESender {
public:
    E2ESender() { check("e2e", sbr_can_e2e_tx_init(&tx_)); }
    nb::bytes protect(uint32_t id, const nb::bytes &data) {
        sbr_can_frame_t f = frame_of(id, data);
        check("protect", sbr_can_e2e_protect(&tx_, &f));
        return bytes_of(f);
    }

private:
    sbr_can_e2e_tx_t tx_{};
};

class E2EReceiver {
public:
    explicit E2EReceiver(uint32_t id) { check("e2e receiver (an sbr message id)", sbr_can_e2e_rx_init(&rx_, id)); }
    // The check's result code (sbr_can_e2e_result_t); the Python layer raises for the bad ones.
    int check_frame(uint32_t id, const nb::bytes &data) {
        const sbr_can_frame_t f = frame_of(id, data);
        sbr_can_e2e_result_t r = SBR_E2E_OK;
        const sbr_status_t st = sbr_can_e2e_check(&rx_, &f, &r);
        if (st != SBR_OK && st != SBR_ERR_CORRUPT) raise_status("e2e check", st);
        return int(r);
    }
    uint32_t id() const { return rx_.id; }

private:
    sbr_can_e2e_rx_t rx_{};
};

}  // namespace

void bind_can(nb::module_ &m) {
    m.def("can_pack", &pack, nb::arg("name"), nb::arg("values"));
    m.def("can_unpack", &unpack, nb::arg("frame_id"), nb::arg("data"));
    m.def("can_messages", []() {
        nb::dict d;
        for (const Message &msg : messages()) {
            std::vector<std::string> names;
            for (const Field &f : msg.fields) names.push_back(f.name);
            d[msg.name] = nb::make_tuple(msg.id, names);
        }
        return d;
    });
    m.def("crc8_j1850", [](const nb::bytes &b) {
        if (b.size() > 0xFFFFFFFFu) throw nb::value_error("data: too long");
        return sbr_crc8_j1850(reinterpret_cast<const uint8_t *>(b.c_str()), uint32_t(b.size()));
    });
    nb::class_<E2ESender>(m, "E2ESender").def(nb::init<>()).def("protect", &E2ESender::protect, nb::arg("frame_id"),
                                                                 nb::arg("data"));
    nb::class_<E2EReceiver>(m, "E2EReceiver")
        .def(nb::init<uint32_t>(), nb::arg("frame_id"))
        .def("check", &E2EReceiver::check_frame, nb::arg("frame_id"), nb::arg("data"))
        .def_prop_ro("frame_id", &E2EReceiver::id);
}

}  // namespace sbr_py
