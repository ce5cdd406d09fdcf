/* What test_fmi2_glue.c and test_fmi3_glue.c check of the initial slip,
 * written once over each version's first step.  Absolute positions wired
 * from t0 (inputs set in initialization mode): by default the contact starts
 * unloaded there, for every rule; the explicit initial slip 0 gives the
 * behaviour of the earlier versions, a full slide (8.55 J for the default
 * coupled rule), bit for bit what inputs set only after initialization
 * give. */
#ifndef OC_INITIAL_SLIP_H
#define OC_INITIAL_SLIP_H
#include <math.h>
#include <string.h>

#include "check.h"

/* A fresh instance's first step of 1 ms to the inputs (u1, u2, N) = (1,
 * 0.5, 18.39) with the sliding rule `rule`, initialSlip `initial`, (s1Start,
 * s2Start) = (s0, s0/2), the inputs also set in initialization mode if
 * inputs_in_init: its T1, T2, s1, s2, dissipatedEnergy y and contactState. */
typedef void (*first_step_fn)(int rule, int initial, double s0, int inputs_in_init, double y[5],
                              int *state);

static void check_initial_slip(first_step_fn first_step) {
    for (int rule = 1; rule <= 3; ++rule) {
        double y[5], old[5], expl[5];
        int state, old_state, expl_state;
        first_step(rule, 1, 0.0, 1, y, &state);
        CHECK(state == 1 && y[0] == 0 && y[1] == 0 && y[2] == 1.0 && y[3] == 0.5 && y[4] == 0,
              "rule %d, atInputs: state %d T (%g, %g) s (%g, %g) energy %g", rule, state, y[0],
              y[1], y[2], y[3], y[4]);
        first_step(rule, 2, 1.0, 1, y, &state); /* explicit, at the inputs: the same */
        CHECK(state == 1 && y[0] == 0 && y[4] == 0, "rule %d, explicit s = u", rule);
        first_step(rule, 1, 0.0, 0, old, &old_state); /* inputs only after initialization */
        first_step(rule, 2, 0.0, 1, expl, &expl_state);
        CHECK(old_state == 2 && expl_state == 2 && memcmp(old, expl, sizeof old) == 0,
              "rule %d: explicit s = 0 differs from the start at u = 0", rule);
        if (rule == 2) CHECK(fabs(expl[4] - 8.55) < 0.005, "8.55 J, got %.4f", expl[4]);
    }
}
#endif
