// SPDX-License-Identifier: MIT
// GTSDB's sign classes for the host tools and the Python package: superclasses, names and
// outlines. No OpenCV (gtsdb.hpp includes it for its image helpers).
#pragma once

#include <cstdint>

namespace sbr_host {

// GTSDB's sign classes (ids 0..42): the class count and each class's sign outline
// (::sbr_picto_rim_t: discs for the prohibitory and mandatory signs and the round "other"
// ones, upward triangles for the danger signs, the yield sign's downward triangle, none for
// the priority-road diamond and the stop octagon) that the trainers put into the models
// (sbr_model_t::class_count, class_outline; sbr_picto_model_t::classes).
constexpr uint32_t kGtsdbClasses = 43;
uint8_t class_outline_of(int class_id);

// Superclass of a GTSDB class (0 prohibitory, 1 mandatory, 2 danger, 3 other; GTSDB's
// ReadMe), the superclass names, and the class names (dbc/sbr.dbc's value names, such as
// "SpeedLimit70"; "?" outside 0..42).
int superclass_of(int class_id);
extern const char *const kSuperclassNames[4];
const char *class_name(int class_id);

}  // namespace sbr_host
