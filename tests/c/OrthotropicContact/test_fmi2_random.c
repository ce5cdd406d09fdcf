/* Random FMI 2.0 call sequences with random and hostile values (NaN, inf,
 * huge, unknown references, wrong states).  Whatever happens, a call returns
 * a defined status, a successful read never yields a non-finite number, and
 * under the sanitizers nothing reads or writes out of bounds.  The sequences
 * are random_calls.h's, FMI 3.0's too; here the FMI 2.0 calls. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fmi2Functions.h"
#include "host_support.h"
#include "models/OrthotropicContact/table.h"
#include "random_values.h"

#define RANDOM_FMI 2
#define RANDOM_SEED 0x9e3779b97f4a7c15ull
#define RANDOM_OPS                                                                                 \
    OP_INPUTS, OP_INPUTS, OP_INPUTS, OP_INPUTS, OP_REAL, OP_INTEGER, OP_STEP, OP_STEP,             \
        OP_GET_STATE, OP_SET_STATE, OP_MODE, OP_RESET, OP_DERIVATIVE, OP_READ
#include "random_calls.h"

static inst instantiate(void) {
    return fmi2Instantiate("fuzz", fmi2CoSimulation, FMU_GUID, "", &host_quiet2_cb, 0, 0);
}
static void free_instance(inst c) { fmi2FreeInstance(c); }
static status set_inputs(inst c, const double v[3]) {
    const fmi2ValueReference vr[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
    return fmi2SetReal(c, vr, 3, v);
}
static status set_real(inst c, fmi2ValueReference vr, double v) {
    return fmi2SetReal(c, &vr, 1, &v);
}
static status set_integer(inst c, fmi2ValueReference vr) {
    const fmi2Integer v = (fmi2Integer)pick(5) - 1;
    return fmi2SetInteger(c, &vr, 1, &v);
}
static status do_step(inst c, double t, double h) { return fmi2DoStep(c, t, h, fmi2True); }
static status get_state(inst c, fmu_state *st) { return fmi2GetFMUstate(c, st); }
static status set_state(inst c, fmu_state st) { return fmi2SetFMUstate(c, st); }
static void free_state(inst c, fmu_state *st) { fmi2FreeFMUstate(c, st); }
static status change_mode(inst c, double *t) {
    switch (pick(4)) {
    case 0: *t = 0; return fmi2SetupExperiment(c, 0, 0, 0, 0, 0);
    case 1: return fmi2EnterInitializationMode(c);
    case 2: return fmi2ExitInitializationMode(c);
    default: return fmi2Terminate(c);
    }
}
static status reset(inst c) { return fmi2Reset(c); }
static status derivative(inst c, const fmi2ValueReference u[], const fmi2ValueReference kn[],
                         size_t n, const double dk[], double du[]) {
    return fmi2GetDirectionalDerivative(c, u, n, kn, n, dk, du);
}
static status read_outputs(inst c, const fmi2ValueReference outs[5], double y[5]) {
    return fmi2GetReal(c, outs, 5, y);
}
