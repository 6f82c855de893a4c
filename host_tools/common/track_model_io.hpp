// SPDX-License-Identifier: MIT
// The tracker's motion model on the host: its text file form (sbr_train_track
// --model-out, sbr_track --model).
//
// Text form, version 2:
//   sbr_track_model 2
//   order O | period P | extent W H | regions RX RY | vel_count V | vel_spacing S
//   transition N, then N values | birth N, then N values
//   crc32 XXXXXXXX   (CRC-32/IEEE of every byte before this line, hexadecimal)
// The loader refuses a file whose magic, version, CRC, sizes or values fail, naming the
// check; a loaded model also passes sbr_track_model_check().
#pragma once

#include <string>
#include <vector>

extern "C" {
#include "sbr/track.h"
}

namespace sbr_host {

struct TrackModel {
    sbr_track_model_t m{};
    std::vector<float> trans, birth;
    void bind()
    {
        m.transition = trans.data();
        m.birth = birth.data();
    }
};

// Return "" on success, else the reason (naming the check that failed).
std::string save_track_model(const TrackModel &d, const std::string &path);
std::string track_model_bytes(const TrackModel &d, std::string &bytes);
std::string load_track_model(const std::string &path, TrackModel &d);
// The same from the file's bytes (`name` for messages).
std::string parse_track_model(const std::string &bytes, const std::string &name, TrackModel &d);

}  // namespace sbr_host
