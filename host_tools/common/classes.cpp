// SPDX-License-Identifier: MIT
#include "classes.hpp"

extern "C" {
#include "sbr/picto.h"
}

namespace sbr_host {

const char *const kSuperclassNames[4] = {"prohibitory", "mandatory", "danger", "other"};

uint8_t class_outline_of(int c) {
    switch (c) {
    case 12: case 14:  // priority road (a diamond), stop (an octagon)
        return uint8_t(SBR_PICTO_RIM_NONE);
    case 13:  // yield
        return uint8_t(SBR_PICTO_RIM_TRIANGLE_DOWN);
    default:
        return superclass_of(c) == 2 ? uint8_t(SBR_PICTO_RIM_TRIANGLE) : uint8_t(SBR_PICTO_RIM_DISC);
    }
}

int superclass_of(int c) {
    switch (c) {
    case 0: case 1: case 2: case 3: case 4: case 5: case 7: case 8: case 9: case 10: case 15: case 16:
        return 0;
    case 33: case 34: case 35: case 36: case 37: case 38: case 39: case 40:
        return 1;
    case 11: case 18: case 19: case 20: case 21: case 22: case 23: case 24: case 25: case 26: case 27:
    case 28: case 29: case 30: case 31:
        return 2;
    default:
        return 3;
    }
}

// The one table of class names (the value names of SBR_Sign_Class and SBR_Det_Class in
// dbc/sbr.dbc, which the dashboard shows; host_annotate checks that the two agree).
const char *class_name(int c) {
    static const char *const names[43] = {
        "SpeedLimit20", "SpeedLimit30", "SpeedLimit50", "SpeedLimit60", "SpeedLimit70", "SpeedLimit80",
        "RestrictionEnds80", "SpeedLimit100", "SpeedLimit120", "NoOvertaking", "NoOvertakingTrucks",
        "PriorityNextIntersection", "PriorityRoad", "GiveWay", "Stop", "NoTrafficBothWays", "NoTrucks",
        "NoEntry", "Danger", "BendLeft", "BendRight", "Bend", "UnevenRoad", "SlipperyRoad", "RoadNarrows",
        "Construction", "TrafficSignal", "PedestrianCrossing", "SchoolCrossing", "CyclesCrossing", "Snow",
        "Animals", "RestrictionEnds", "GoRight", "GoLeft", "GoStraight", "GoRightOrStraight",
        "GoLeftOrStraight", "KeepRight", "KeepLeft", "Roundabout", "RestrictionEndsOvertaking",
        "RestrictionEndsOvertakingTrucks"};
    return (c >= 0 && c < 43) ? names[c] : "?";
}

}  // namespace sbr_host
