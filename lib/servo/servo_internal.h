/* SPDX-License-Identifier: MIT */
/* Private to lib/servo: what the servo step (servo_step.c) uses of the learner
   (servo.c). Not installed. */
#ifndef SBR_SERVO_INTERNAL_H
#define SBR_SERVO_INTERNAL_H

#include "sbr/servo.h"

/* Integrity words of a learner and a run; the bound of every value. */
#define SERVO_MAGIC 0x5345524Fu
#define RUN_MAGIC 0x52554E53u
#define SERVO_MAX_VALUE 1.0e6f

/* An initialised learner whose integrity word still holds. */
int sbr_servo_priv_valid(const sbr_servo_t *s);
/* Every value finite and within +-1e6. */
int sbr_servo_priv_values_ok(const float *v, uint32_t n);
/* The angle features of a difference wrapped to (-pi, pi]. */
void sbr_servo_priv_wrap_features(const sbr_servo_config_t *c, float *d);
/* J(y) into jac (m x n) from the fields reaching y, or from the nearest field when none
   does; returns the summed activation of the fields used (0 with no field at all). */
float sbr_servo_priv_predict(const sbr_servo_t *s, const float *y, float *jac);

#endif /* SBR_SERVO_INTERNAL_H */
