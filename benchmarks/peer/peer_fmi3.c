/* The peer's minimal FMI 3.0 Co-Simulation layer (see peer.h): the calls a
 * master makes to run it, each checking its instance and phase.  Written
 * apart from the FMU's glue and from peer_fmi2.c, on purpose (an independent
 * reference: see peer_fmi2.c). */
#include <stdlib.h>

#include "fmi3Functions.h"
#include "peer.h"

#define P(c) ((peer *)(c))

const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Instance fmi3InstantiateCoSimulation(fmi3String name, fmi3String token, fmi3String resources,
                                         fmi3Boolean visible, fmi3Boolean logging,
                                         fmi3Boolean eventMode, fmi3Boolean earlyReturn,
                                         const fmi3ValueReference req[], size_t nreq,
                                         fmi3InstanceEnvironment env, fmi3LogMessageCallback log,
                                         fmi3IntermediateUpdateCallback upd) {
    (void)name; (void)token; (void)resources; (void)visible; (void)logging; (void)earlyReturn;
    (void)req; (void)nreq; (void)env; (void)log; (void)upd;
    if (eventMode) return NULL;
    peer *p = calloc(1, sizeof *p);
    if (p) peer_init(p);
    return p;
}

void fmi3FreeInstance(fmi3Instance c) { free(c); }

fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean tolDef, fmi3Float64 tol,
                                       fmi3Float64 t0, fmi3Boolean stopDef, fmi3Float64 t1) {
    (void)tolDef; (void)tol; (void)stopDef; (void)t1;
    if (!c || P(c)->phase != PEER_INSTANTIATED) return fmi3Error;
    P(c)->time = t0;
    P(c)->phase = PEER_INIT;
    return fmi3OK;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance c) {
    if (!c || P(c)->phase != PEER_INIT) return fmi3Error;
    return peer_exit_init(P(c)) == 0 ? fmi3OK : fmi3Error;
}

fmi3Status fmi3Terminate(fmi3Instance c) {
    if (!c) return fmi3Error;
    P(c)->phase = PEER_TERMINATED;
    return fmi3OK;
}

fmi3Status fmi3Reset(fmi3Instance c) {
    if (!c) return fmi3Error;
    peer_init(P(c));
    return fmi3OK;
}

fmi3Status fmi3SetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
                          const fmi3Float64 v[], size_t nv) {
    if (!c || nv != n || P(c)->phase == PEER_TERMINATED) return fmi3Error;
    for (size_t i = 0; i < n; ++i)
        if (peer_set_real(P(c), vr[i], v[i]) != 0) return fmi3Error;
    return fmi3OK;
}

fmi3Status fmi3GetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
                          fmi3Float64 v[], size_t nv) {
    if (!c || nv != n) return fmi3Error;
    for (size_t i = 0; i < n; ++i)
        if (peer_get_real(P(c), vr[i], &v[i]) != 0) return fmi3Error;
    return fmi3OK;
}

fmi3Status fmi3SetInt64(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
                        const fmi3Int64 v[], size_t nv) {
    if (!c || nv != n) return fmi3Error;
    for (size_t i = 0; i < n; ++i)
        if (peer_set_int(P(c), vr[i], (int)v[i]) != 0) return fmi3Error;
    return fmi3OK;
}

fmi3Status fmi3GetInt32(fmi3Instance c, const fmi3ValueReference vr[], size_t n, fmi3Int32 v[],
                        size_t nv) {
    if (!c || nv != n) return fmi3Error;
    for (size_t i = 0; i < n; ++i)
        if (peer_get_int(P(c), vr[i], &v[i]) != 0) return fmi3Error;
    return fmi3OK;
}

fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 t, fmi3Float64 h, fmi3Boolean noSetPrior,
                      fmi3Boolean *event, fmi3Boolean *terminate, fmi3Boolean *early,
                      fmi3Float64 *last) {
    (void)noSetPrior;
    if (!c || P(c)->phase != PEER_STEP || !(h > 0)) return fmi3Error;
    peer_step(P(c));
    P(c)->time = t + h;
    if (event) *event = fmi3False;
    if (terminate) *terminate = fmi3False;
    if (early) *early = fmi3False;
    if (last) *last = P(c)->time;
    return fmi3OK;
}
