/* Random FMI 3.0 call sequences with random and hostile values (NaN, inf,
 * huge, unknown references, wrong states, mismatched array sizes, corrupted
 * serialized states).  Whatever happens, a call returns a defined status, a
 * successful read never yields a non-finite number, and under the
 * sanitizers nothing reads or writes out of bounds.  The sequences are
 * random_calls.h's, FMI 2.0's too; here the FMI 3.0 calls. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fmi3Functions.h"
#include "host_support.h"
#include "models/OrthotropicContact/table.h"
#include "random_values.h"

#define RANDOM_FMI 3
#define RANDOM_SEED 0x2545f4914f6cdd1dull
#define RANDOM_OPS                                                                                 \
    OP_INPUTS, OP_INPUTS, OP_INPUTS, OP_INPUTS, OP_REAL, OP_INTEGER, OP_STEP, OP_STEP,             \
        OP_GET_STATE, OP_SET_STATE, OP_SERIALIZED, OP_MODE, OP_RESET, OP_DERIVATIVE,               \
        OP_GET_INTEGER, OP_READ
#include "random_calls.h"

static inst instantiate(void) {
    return fmi3InstantiateCoSimulation("fuzz", FMU_GUID, "", 0, 0, 0, 0, NULL, 0, NULL, host_quiet3,
                                       NULL);
}
static void free_instance(inst c) { fmi3FreeInstance(c); }
/* a wrong number of values now and then */
static status set_inputs(inst c, const double v[3]) {
    const fmi3ValueReference vr[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
    return fmi3SetFloat64(c, vr, 3, v, pick(10) ? 3 : pick(5));
}
static status set_real(inst c, fmi3ValueReference vr, double v) {
    return fmi3SetFloat64(c, &vr, 1, &v, 1);
}
static status set_integer(inst c, fmi3ValueReference vr) {
    const fmi3Int64 v = (fmi3Int64)pick(5) - 1;
    const fmi3Int32 w = (fmi3Int32)pick(5) - 1;
    return pick(2) ? fmi3SetInt64(c, &vr, 1, &v, 1) : fmi3SetInt32(c, &vr, 1, &w, 1);
}
static status do_step(inst c, double t, double h) {
    fmi3Boolean ev, term, early;
    double last;
    return fmi3DoStep(c, t, h, fmi3True, &ev, &term, &early, &last);
}
static status get_state(inst c, fmu_state *st) { return fmi3GetFMUState(c, st); }
static status set_state(inst c, fmu_state st) { return fmi3SetFMUState(c, st); }
static void free_state(inst c, fmu_state *st) { fmi3FreeFMUState(c, st); }
/* serialize, maybe corrupt, deserialize (maybe short), restore */
static status serialized_round_trip(inst c, fmu_state st) {
    size_t n = 0;
    status s = fmi3SerializedFMUStateSize(c, st, &n);
    if (s != fmi3OK || n == 0 || n > 4096) return s;
    unsigned char buf[4096];
    s = fmi3SerializeFMUState(c, st, buf, n);
    if (s != fmi3OK) return s;
    if (pick(2)) buf[pick((unsigned)n)] ^= (unsigned char)(1u << pick(8));
    fmi3FMUState st2 = NULL;
    s = fmi3DeserializeFMUState(c, buf, pick(4) ? n : pick((unsigned)n), &st2);
    if (s == fmi3OK) {
        s = fmi3SetFMUState(c, st2);
        fmi3FreeFMUState(c, &st2);
    }
    return s;
}
static status change_mode(inst c, double *t) {
    switch (pick(3)) {
    case 0: *t = 0; return fmi3EnterInitializationMode(c, 0, 0, 0, 0, 0);
    case 1: return fmi3ExitInitializationMode(c);
    default: return fmi3Terminate(c);
    }
}
static status reset(inst c) { return fmi3Reset(c); }
static status derivative(inst c, const fmi3ValueReference u[], const fmi3ValueReference kn[],
                         size_t n, const double dk[], double du[]) {
    return pick(2) ? fmi3GetDirectionalDerivative(c, u, n, kn, n, dk, n, du, n)
                   : fmi3GetAdjointDerivative(c, u, n, kn, n, dk, n, du, n);
}
static status get_integer(inst c, fmi3ValueReference vr) {
    fmi3Int32 i32;
    fmi3Int64 i64;
    return pick(2) ? fmi3GetInt32(c, &vr, 1, &i32, 1) : fmi3GetInt64(c, &vr, 1, &i64, 1);
}
static status read_outputs(inst c, const fmi3ValueReference outs[5], double y[5]) {
    return fmi3GetFloat64(c, outs, 5, y, 5);
}
