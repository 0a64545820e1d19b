/* SPDX-License-Identifier: MIT */
/* hy_ode_steppers.h (internal, not installed): the GSL stepper type of a
 * stepper name of hy_ode.h, for the core's other GSL integrations (the
 * Jiles-Atherton model integrates in H with the stepper its caller names). */
#ifndef HY_ODE_STEPPERS_H
#define HY_ODE_STEPPERS_H

#include <gsl/gsl_odeiv2.h>

/* The stepper called name (hy_ode_stepper_names()), or NULL. */
const gsl_odeiv2_step_type *hy_ode_step_type(const char *name);

#endif
