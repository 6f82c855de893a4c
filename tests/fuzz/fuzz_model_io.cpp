// SPDX-License-Identifier: MIT
// Fuzz harness: the host model loaders (--model .sbrm, --picto .sbrp, sbr_track --model
// text form). The first byte picks the loader, the rest is the file. A file the loader
// accepts must pass the core's check, and saving it again must give a file that loads to
// the same bytes; a refusal must name its check.
#include "fuzz_common.hpp"

#include <string>

#include "model_io.hpp"
#include "track_model_io.hpp"

namespace {

bool names_a_check(const std::string &e)
{
    for (const char *k : {": magic:", ": version:", ": crc:", ": sizes:", ": values:", ": format:"}) {
        if (e.find(k) != std::string::npos) {
            return true;
        }
    }
    std::fprintf(stderr, "sbr fuzz: refusal without a named check: %s\n", e.c_str());
    return false;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1u) {
        return 0;
    }
    const std::string file(reinterpret_cast<const char *>(data + 1), size - 1u);
    switch (data[0] % 3u) {
    case 0: {
        sbr_host::Model m;
        const std::string e = sbr_host::parse_model(file, "fuzz", m);
        if (!e.empty()) {
            FZ_CHECK(names_a_check(e));
            break;
        }
        FZ_STATUS(sbr_model_check(&m.view), SBR_OK);
        std::string again;
        FZ_CHECK(sbr_host::model_bytes(m, again).empty());
        sbr_host::Model m2;
        FZ_CHECK(sbr_host::parse_model(again, "again", m2).empty());
        std::string third;
        FZ_CHECK(sbr_host::model_bytes(m2, third).empty());
        FZ_CHECK(third == again);
        break;
    }
    case 1: {
        sbr_host::Picto p;
        const std::string e = sbr_host::parse_picto(file, "fuzz", p);
        if (!e.empty()) {
            FZ_CHECK(names_a_check(e));
            break;
        }
        FZ_STATUS(sbr_picto_check(&p.view), SBR_OK);
        std::string again;
        FZ_CHECK(sbr_host::picto_bytes(p, again).empty());
        FZ_CHECK(again == file); // the binary form is canonical
        break;
    }
    default: {
        sbr_host::TrackModel t;
        const std::string e = sbr_host::parse_track_model(file, "fuzz", t);
        if (!e.empty()) {
            FZ_CHECK(names_a_check(e));
            break;
        }
        FZ_STATUS(sbr_track_model_check(&t.m), SBR_OK);
        std::string again;
        FZ_CHECK(sbr_host::track_model_bytes(t, again).empty());
        sbr_host::TrackModel t2;
        FZ_CHECK(sbr_host::parse_track_model(again, "again", t2).empty());
        FZ_CHECK(t2.trans.size() == t.trans.size() && t2.birth.size() == t.birth.size());
        break;
    }
    }
    return 0;
}
