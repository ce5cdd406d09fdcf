/* The FMI 3.0 null FMU for the benchmark's floor: see null_fmi2.c (why it
 * repeats that file's shape). */
#include <stdlib.h>

#include "fmi3Functions.h"

typedef struct {
    double v[32];
    int state;
} null_fmu;

fmi3Instance fmi3InstantiateCoSimulation(fmi3String a, fmi3String b, fmi3String c, fmi3Boolean d,
                                         fmi3Boolean e, fmi3Boolean f, fmi3Boolean g,
                                         const fmi3ValueReference h[], size_t i,
                                         fmi3InstanceEnvironment j, fmi3LogMessageCallback k,
                                         fmi3IntermediateUpdateCallback l) {
    (void)a; (void)b; (void)c; (void)d; (void)e; (void)f; (void)g; (void)h; (void)i; (void)j;
    (void)k; (void)l;
    null_fmu *n = calloc(1, sizeof *n);
    if (n) n->state = 1;
    return n;
}
void fmi3FreeInstance(fmi3Instance c) { free(c); }
fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean a, fmi3Float64 b, fmi3Float64 d,
                                       fmi3Boolean e, fmi3Float64 f) {
    (void)c; (void)a; (void)b; (void)d; (void)e; (void)f;
    return fmi3OK;
}
fmi3Status fmi3ExitInitializationMode(fmi3Instance c) { (void)c; return fmi3OK; }
fmi3Status fmi3SetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
                          const fmi3Float64 v[], size_t nv) {
    null_fmu *f = c;
    (void)nv;
    for (size_t i = 0; i < n; ++i) f->v[vr[i] & 31] = v[i];
    return fmi3OK;
}
fmi3Status fmi3GetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t n, fmi3Float64 v[],
                          size_t nv) {
    null_fmu *f = c;
    (void)nv;
    for (size_t i = 0; i < n; ++i) v[i] = f->v[vr[i] & 31];
    return fmi3OK;
}
fmi3Status fmi3SetInt64(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
                        const fmi3Int64 v[], size_t nv) {
    (void)c; (void)vr; (void)n; (void)v; (void)nv;
    return fmi3OK;
}
fmi3Status fmi3GetInt32(fmi3Instance c, const fmi3ValueReference vr[], size_t n, fmi3Int32 v[],
                        size_t nv) {
    null_fmu *f = c;
    (void)vr; (void)nv;
    for (size_t i = 0; i < n; ++i) v[i] = f->state;
    return fmi3OK;
}
fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 t, fmi3Float64 h, fmi3Boolean b, fmi3Boolean *ev,
                      fmi3Boolean *term, fmi3Boolean *early, fmi3Float64 *last) {
    (void)c; (void)b;
    if (ev) *ev = fmi3False;
    if (term) *term = fmi3False;
    if (early) *early = fmi3False;
    if (last) *last = t + h;
    return fmi3OK;
}
