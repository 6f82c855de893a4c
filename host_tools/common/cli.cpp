// SPDX-License-Identifier: MIT
#include "cli.hpp"

#include <cstring>
#include <sstream>

namespace sbr_host {

CLI::Option *add_range_option(CLI::App &app, ImageRanges &out, const std::string &what, const std::string &name) {
    return app
        .add_option_function<std::string>(
            name,
            [&out, name](const std::string &s) {
                if (!parse_image_ranges(s, out))
                    throw CLI::ValidationError(name, "wants A-B[,C-D...] with 0 <= A <= B <= " +
                                                              std::to_string(kMaxImageNumber) + ", got '" + s + "'");
            },
            what)
        ->type_name("A-B[,C-D]");
}

namespace {

// "max_extra_looks" -> "--max-extra-looks"
std::string option_name(const char *field) {
    std::string o = std::string("--") + field;
    for (char &c : o)
        if (c == '_') c = '-';
    return o;
}

std::string number(float v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// One value per map kind, in the order intensity, red, blue, yellow: the first 1..4 given.
CLI::Option *add_list(CLI::App &app, const sbr_field_t &f, std::vector<unsigned> &values) {
    std::string def;
    for (uint32_t k = 0; k < f.count; ++k) def += (k ? "," : "") + std::to_string(f.def_u[k]);
    return app.add_option(option_name(f.name), values, std::string(f.help) + "; per map kind: intensity, red, blue, yellow")
        ->delimiter(',')
        ->expected(1, int(f.count))
        ->check(CLI::Range(f.lo_u, f.hi_u))
        ->type_name("I[,R[,B[,Y]]]")
        ->default_str(def);
}

// One scalar field's option: its callback writes the field and records that it was given
// (after the parse, and the App, are gone, RecogCli::given() still answers).
template <typename T>
CLI::Option *add_field(CLI::App &app, const sbr_field_t &f, T *at, RecogCli &r, const CLI::Validator &range,
                       const std::string &def) {
    const std::string name = f.name;
    return app
        .add_option_function<T>(
            option_name(f.name),
            [at, name, &r](const T &v) {
                *at = v;
                r.given_fields.insert(name);
            },
            f.help)
        ->check(range)
        ->default_str(def);
}

}  // namespace

std::string field_range(const sbr_field_t &f) {
    if (f.kind == SBR_FIELD_F32) return number(f.lo_f) + " .. " + number(f.hi_f);
    return std::to_string(f.lo_u) + " .. " + std::to_string(f.hi_u);
}

std::string config_problem(const sbr_recog_config_t &cfg) {
    sbr_field_t field;
    if (sbr_recog_field_at(sbr_recog_config_check_field(&cfg), &field) != SBR_OK)
        return sbr_recog_config_check(&cfg) == SBR_OK ? "" : "the configuration is refused";
    const sbr_field_t *f = &field;
    std::string v;
    const unsigned char *base = reinterpret_cast<const unsigned char *>(&cfg) + f->offset;
    for (uint32_t k = 0; k < f->count; ++k) {
        if (f->kind == SBR_FIELD_F32) {
            float x;
            std::memcpy(&x, base, sizeof x);
            v += number(x);
        } else {
            uint32_t x;
            std::memcpy(&x, base + 4u * k, sizeof x);
            v += (k ? "," : "") + std::to_string(x);
        }
    }
    return option_name(f->name) + " " + v + ": outside " + field_range(*f) + " or its rule with other fields (" +
           f->help + ")";
}

void add_recog_options(CLI::App &app, sbr_recog_config_t &cfg, RecogCli &r) {
    const std::string g = "Recogniser (docs/usage/configuration.md; defaults of sbr_recog_config_default())";
    unsigned char *const base = reinterpret_cast<unsigned char *>(&cfg);
    for (const sbr_field_t &f : recog_fields()) {
        CLI::Option *o;
        if (f.count > 1) {
            o = add_list(app, f, r.front_end.lists[f.name]);
        } else if (f.kind == SBR_FIELD_F32) {
            float *at = reinterpret_cast<float *>(base + f.offset);
            o = add_field(app, f, at, r, finite_range(f.lo_f, f.hi_f), number(*at));
        } else {
            uint32_t *at = reinterpret_cast<uint32_t *>(base + f.offset);
            o = add_field(app, f, at, r, CLI::Range(f.lo_u, f.hi_u), std::to_string(*at));
        }
        o->group(g);
        r.options[f.name] = o;
    }
}

void add_front_end_options(CLI::App &app, FrontEnd &fe, const std::string &group) {
    for (const sbr_field_t &f : recog_fields())
        if (f.count > 1) add_list(app, f, fe.lists[f.name])->group(group);
}

void apply_recog_cli(const RecogCli &r, sbr_recog_config_t &cfg) { apply_front_end(r.front_end, cfg.parts); }

void add_look_options(CLI::App &app, LooksCli &l, bool written) {
    const std::string g = written ? "The looks written into the class stage (docs/usage/configuration.md)"
                                  : "The class stage's looks (docs/usage/configuration.md; default: the class stage's own)";
    for (const sbr_field_t &f : look_fields()) {
        const std::string name = f.name;
        app.add_option_function<float>(
               option_name(f.name), [name, &l](const float &v) { l.given[name] = v; }, f.help)
            ->check(finite_range(f.lo_f, f.hi_f))
            ->default_str(written ? number(f.def_f) : "the class stage's (trained: " + number(f.def_f) + ")")
            ->group(g);
    }
}

void apply_looks(const LooksCli &l, sbr_picto_model_t &stage) {
    unsigned char *base = reinterpret_cast<unsigned char *>(&stage);
    for (const sbr_field_t &f : look_fields()) {
        const auto v = l.given.find(f.name);
        if (v != l.given.end()) std::memcpy(base + f.offset, &v->second, sizeof v->second);
    }
}

}  // namespace sbr_host
