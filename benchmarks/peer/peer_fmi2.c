/* The peer's minimal FMI 2.0 Co-Simulation layer (see peer.h): the calls a
 * master makes to run it, each checking its instance and phase.  Written
 * apart from the FMU's glue and from peer_fmi3.c, each call spelled out: the
 * peer is an independent reference (bench_peer --check, the CTest
 * peer_agrees), so its twin layers repeat each other on purpose. */
#include <stdlib.h>

#include "fmi2Functions.h"
#include "peer.h"

typedef struct {
    peer p;
    fmi2CallbackFunctions cb;
} inst2;

#define P(c) (&((inst2 *)(c))->p)

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid,
                              fmi2String resources, const fmi2CallbackFunctions *cb,
                              fmi2Boolean visible, fmi2Boolean logging) {
    (void)name; (void)guid; (void)resources; (void)visible; (void)logging;
    if (type != fmi2CoSimulation || !cb) return NULL;
    inst2 *I = calloc(1, sizeof *I);
    if (!I) return NULL;
    I->cb = *cb;
    peer_init(&I->p);
    return I;
}

void fmi2FreeInstance(fmi2Component c) { free(c); }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n, const fmi2String cat[]) {
    (void)on; (void)n; (void)cat;
    return c ? fmi2OK : fmi2Error;
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean tolDef, fmi2Real tol, fmi2Real t0,
                               fmi2Boolean stopDef, fmi2Real t1) {
    (void)tolDef; (void)tol; (void)stopDef; (void)t1;
    if (!c || P(c)->phase != PEER_INSTANTIATED) return fmi2Error;
    P(c)->time = t0;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    if (!c || P(c)->phase != PEER_INSTANTIATED) return fmi2Error;
    P(c)->phase = PEER_INIT;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    if (!c || P(c)->phase != PEER_INIT) return fmi2Error;
    return peer_exit_init(P(c)) == 0 ? fmi2OK : fmi2Error;
}

fmi2Status fmi2Terminate(fmi2Component c) {
    if (!c) return fmi2Error;
    P(c)->phase = PEER_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c) {
    if (!c) return fmi2Error;
    peer_init(P(c));
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                       const fmi2Real v[]) {
    if (!c || P(c)->phase == PEER_TERMINATED) return fmi2Error;
    for (size_t i = 0; i < n; ++i)
        if (peer_set_real(P(c), vr[i], v[i]) != 0) return fmi2Error;
    return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real v[]) {
    if (!c) return fmi2Error;
    for (size_t i = 0; i < n; ++i)
        if (peer_get_real(P(c), vr[i], &v[i]) != 0) return fmi2Error;
    return fmi2OK;
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          const fmi2Integer v[]) {
    if (!c) return fmi2Error;
    for (size_t i = 0; i < n; ++i)
        if (peer_set_int(P(c), vr[i], v[i]) != 0) return fmi2Error;
    return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          fmi2Integer v[]) {
    if (!c) return fmi2Error;
    for (size_t i = 0; i < n; ++i)
        if (peer_get_int(P(c), vr[i], &v[i]) != 0) return fmi2Error;
    return fmi2OK;
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean noSetPrior) {
    (void)noSetPrior;
    if (!c || P(c)->phase != PEER_STEP || !(h > 0)) return fmi2Error;
    peer_step(P(c));
    P(c)->time = t + h;
    return fmi2OK;
}
