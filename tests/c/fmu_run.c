/* A minimal FMI 3.0 importer for the platform tests: loads an FMU binary with
 * dlopen, as any importer does, runs it over an input table and prints the
 * outputs.  Cross-compiled for aarch64 and run under qemu-user, it runs the
 * aarch64-linux binary of the FMU on this x86_64 machine.
 *
 * Usage: fmu_run BINARY TOKEN INPUT.csv   (rows: t,u1,u2,N; step = row spacing)
 * Prints: t,T1,T2,s1,s2,dissipatedEnergy,contactState per step, %.17g. */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

#include "fmi3FunctionTypes.h"

#define LOAD(name)                                                                                 \
    name##TYPE *name = (name##TYPE *)dlsym(lib, #name);                                            \
    if (!name) {                                                                                   \
        fprintf(stderr, "missing %s\n", #name);                                                    \
        return 2;                                                                                  \
    }

static void logger(fmi3InstanceEnvironment e, fmi3Status s, fmi3String c, fmi3String m) {
    (void)e;
    (void)c;
    fprintf(stderr, "[status %d] %s\n", (int)s, m);
}

int main(int argc, char **argv) {
    if (argc != 4) {
        fprintf(stderr, "usage: %s BINARY TOKEN INPUT.csv\n", argv[0]);
        return 2;
    }
    void *lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        fprintf(stderr, "dlopen: %s\n", dlerror());
        return 2;
    }
    LOAD(fmi3InstantiateCoSimulation)
    LOAD(fmi3EnterInitializationMode)
    LOAD(fmi3ExitInitializationMode)
    LOAD(fmi3SetFloat64)
    LOAD(fmi3GetFloat64)
    LOAD(fmi3GetInt32)
    LOAD(fmi3DoStep)
    LOAD(fmi3FreeInstance)
    FILE *in = fopen(argv[3], "r");
    if (!in) {
        perror(argv[3]);
        return 2;
    }
    static double rows[100000][4];
    int n = 0;
    while (n < 100000 &&
           fscanf(in, "%lf,%lf,%lf,%lf", &rows[n][0], &rows[n][1], &rows[n][2], &rows[n][3]) == 4)
        ++n;
    fclose(in);
    fmi3Instance c =
        fmi3InstantiateCoSimulation("run", argv[2], "", 0, 0, 0, 0, NULL, 0, NULL, logger, NULL);
    if (!c || fmi3EnterInitializationMode(c, 0, 0, rows[0][0], 0, 0) != fmi3OK ||
        fmi3ExitInitializationMode(c) != fmi3OK)
        return 3;
    /* value references of the table (OC_VR_*, models/OrthotropicContact/table.h): u1 u2 N,
     * then T1 T2 s1 s2 energy, contactState */
    const fmi3ValueReference in_vr[3] = {16, 17, 18}, out_vr[5] = {19, 20, 21, 22, 24}, st_vr = 23;
    for (int k = 0; k + 1 < n; ++k) {
        fmi3Boolean ev, term, early;
        fmi3Float64 last, y[5];
        fmi3Int32 state;
        if (fmi3SetFloat64(c, in_vr, 3, &rows[k][1], 3) != fmi3OK ||
            fmi3DoStep(c, rows[k][0], rows[k + 1][0] - rows[k][0], fmi3True, &ev, &term, &early,
                       &last) != fmi3OK ||
            fmi3GetFloat64(c, out_vr, 5, y, 5) != fmi3OK ||
            fmi3GetInt32(c, &st_vr, 1, &state, 1) != fmi3OK)
            return 4;
        printf("%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d\n", rows[k + 1][0], y[0], y[1], y[2], y[3],
               y[4], (int)state);
    }
    fmi3FreeInstance(c);
    dlclose(lib);
    return 0;
}
