// SPDX-License-Identifier: MIT
// sbr_config: the core's configuration tables as documentation. Prints the recogniser's
// fields (recog.h, sbr_recog_field_at()) and the class stage's looks (picto.h,
// sbr_picto_look_field_at()) as Markdown tables; --check FILE fails (exit 1) when the
// tables in FILE (between the markers below) are not exactly these, --write FILE puts
// them there. docs/usage/configuration.md is made so, and a test checks it.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "cli.hpp"
#include "model_io.hpp"

using namespace sbr_host;

namespace {

const char *kBegin = "<!-- tables: written by sbr_config --write; do not edit by hand -->";
const char *kEnd = "<!-- end of tables -->";

std::string num(float v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::string def_of(const sbr_field_t &f) {
    if (f.kind == SBR_FIELD_F32) return num(f.def_f);
    std::string d;
    for (uint32_t k = 0; k < f.count; ++k) d += (k ? ", " : "") + std::to_string(f.def_u[k]);
    return d;
}

std::string table(const std::vector<sbr_field_t> &fields, const char *option_of) {
    std::ostringstream o;
    o << "| field | " << option_of << " | type | range | default | what it does |\n"
      << "| --- | --- | --- | --- | --- | --- |\n";
    for (const sbr_field_t &f : fields) {
        std::string opt = std::string("--") + f.name;
        for (char &c : opt)
            if (c == '_') c = '-';
        const std::string type = f.kind == SBR_FIELD_F32 ? "float"
                                 : f.count > 1           ? "uint32 x " + std::to_string(f.count)
                                                         : "uint32";
        o << "| `" << f.name << "` | `" << opt << "` | " << type << " | " << field_range(f)
          << ((f.flags & SBR_FIELD_LINKED) != 0u ? " (and its rule)" : "") << " | " << def_of(f) << " | " << f.help
          << " |\n";
    }
    return o.str();
}

std::string tables() {
    return std::string(kBegin) + "\n\n## The recogniser's configuration (`sbr_recog_config_t`, `recog.h`)\n\n" +
           table(recog_fields(), "option") +
           "\n## The class stage's looks (`sbr_picto_looks_t`, `picto.h`): the model's, trained with it\n\n" +
           table(look_fields(), "option (overrides the model's)") + "\n" + kEnd;
}

}  // namespace

int main(int argc, char **argv) {
    std::string check, write;
    CLI::App app{"sbr_config: the core's configuration tables as Markdown (docs/usage/configuration.md)"};
    app.add_option("--check", check, "exit 1 when FILE's tables are not the core's");
    app.add_option("--write", write, "put the core's tables into FILE (between its markers)");
    const int rc = parse_cli(app, argc, argv);
    if (rc >= 0) return rc;
    const std::string now = tables();
    const std::string path = !check.empty() ? check : write;
    if (path.empty()) {
        std::printf("%s\n", now.c_str());
        return 0;
    }
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    const size_t a = text.find(kBegin), b = text.find(kEnd);
    if (!in || a == std::string::npos || b == std::string::npos || b < a) {
        std::fprintf(stderr, "sbr_config: %s: no tables between the markers\n", path.c_str());
        return 1;
    }
    const std::string there = text.substr(a, b + std::string(kEnd).size() - a);
    if (!check.empty()) {
        if (there == now) return 0;
        std::fprintf(stderr,
                     "sbr_config: %s: its tables are not the core's (a field's range, default or meaning "
                     "changed): run sbr_config --write %s\n",
                     path.c_str(), path.c_str());
        return 1;
    }
    std::ofstream out(path);
    out << text.substr(0, a) << now << text.substr(b + std::string(kEnd).size());
    return out ? 0 : 1;
}
