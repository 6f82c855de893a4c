/* SPDX-License-Identifier: MIT */
/* Private to lib/recog: what the class stage's looks (picto_look.c) share with the
   classifier (pictogram.c). Not installed. */
#ifndef SBR_PICTO_INTERNAL_H
#define SBR_PICTO_INTERNAL_H

#include "sbr/picto.h"

/* sbr_picto_refine() from the last layer's inputs `in` instead of the features: the
   rectified hidden units that sbr_picto_classify() leaves at the start of its workspace
   (or the features themselves when the model has no hidden layer), of the model's size.
   Returns ::SBR_ERR_CORRUPT for a bad model header, ::SBR_ERR_RANGE for a box outside
   sbr_picto_refine()'s domain or a regression that overflows. */
sbr_status_t sbr_picto_priv_refine_from(const sbr_picto_model_t *model, const float *in,
                                        const float box[4], float refined[4]);

#endif /* SBR_PICTO_INTERNAL_H */
