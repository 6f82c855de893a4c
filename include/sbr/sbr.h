/* SPDX-License-Identifier: MIT */
/**
 * @file sbr.h
 * @brief Umbrella header: every public sbr module.
 */
#ifndef SBR_SBR_H
#define SBR_SBR_H

#include "sbr/status.h"
#include "sbr/types.h"
#include "sbr/fft.h"
#include "sbr/channel.h"
#include "sbr/image.h"
#include "sbr/contour.h"
#include "sbr/fd.h"
#include "sbr/map.h"
#include "sbr/mser.h"
#include "sbr/can.h"
#include "sbr/parts.h"
#include "sbr/part_model.h"
#include "sbr/recog.h"
#include "sbr/recog_strips.h"
#include "sbr/bike.h"
#include "sbr/conic.h"
#include "sbr/track.h"
#include "sbr/rules.h"
#include "sbr/signs.h"
#include "sbr/ecu.h"
#include "sbr/servo.h"
#include "sbr/models.h"

/** Library version. */
#define SBR_VERSION_MAJOR 0
#define SBR_VERSION_MINOR 1
#define SBR_VERSION_PATCH 0

#endif /* SBR_SBR_H */
