/* A null FMU for the benchmark's floor (bench_peer): the FMI 2.0 calls a
 * step makes, doing nothing but keep the inputs and hand back two numbers.
 * What a step through dlopen'ed FMI calls costs before any physics or check.
 * Not an FMU anyone should use.  Each version's null FMU is written out on
 * its own (null_fmi3.c repeats it on purpose): nothing shared between them
 * or with the FMU's glue, so that the floor is the calls' and nothing else's. */
#include <stdlib.h>

#include "fmi2Functions.h"

typedef struct {
    double v[32];
    int state;
} null_fmu;

fmi2Component fmi2Instantiate(fmi2String n, fmi2Type t, fmi2String g, fmi2String r,
                              const fmi2CallbackFunctions *cb, fmi2Boolean vis, fmi2Boolean log) {
    (void)n; (void)t; (void)g; (void)r; (void)cb; (void)vis; (void)log;
    null_fmu *f = calloc(1, sizeof *f);
    if (f) f->state = 1;
    return f;
}
void fmi2FreeInstance(fmi2Component c) { free(c); }
fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean a, fmi2Real b, fmi2Real d,
                               fmi2Boolean e, fmi2Real f) {
    (void)c; (void)a; (void)b; (void)d; (void)e; (void)f;
    return fmi2OK;
}
fmi2Status fmi2EnterInitializationMode(fmi2Component c) { (void)c; return fmi2OK; }
fmi2Status fmi2ExitInitializationMode(fmi2Component c) { (void)c; return fmi2OK; }
fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real v[]) {
    null_fmu *f = c;
    for (size_t i = 0; i < n; ++i) f->v[vr[i] & 31] = v[i];
    return fmi2OK;
}
fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real v[]) {
    null_fmu *f = c;
    for (size_t i = 0; i < n; ++i) v[i] = f->v[vr[i] & 31];
    return fmi2OK;
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          const fmi2Integer v[]) {
    (void)c; (void)vr; (void)n; (void)v;
    return fmi2OK;
}
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Integer v[]) {
    null_fmu *f = c;
    (void)vr;
    for (size_t i = 0; i < n; ++i) v[i] = f->state;
    return fmi2OK;
}
fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean b) {
    (void)c; (void)t; (void)h; (void)b;
    return fmi2OK;
}
