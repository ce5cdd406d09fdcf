/* Random FMI 2.0 call sequences with random and hostile values (NaN, inf,
 * huge, unknown references, wrong states).  Whatever happens, a call returns
 * a defined status, a successful read never yields a non-finite number, and
 * under the sanitizers nothing reads or writes out of bounds. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fmi2Functions.h"
#include "host_support.h"
#include "models/OrthotropicContact/table.h"
#include "random_values.h"

int main(void) {
    rng_state = 0x9e3779b97f4a7c15ull;
    const fmi2ValueReference outs[5] = {OC_VR_T1, OC_VR_T2, OC_VR_s1, OC_VR_s2,
                                        OC_VR_dissipatedEnergy};
    long ok_reads = 0, calls = 0, bad_status = 0, non_finite = 0;
    for (int episode = 0; episode < 200; ++episode) {
        fmi2Component c =
            fmi2Instantiate("fuzz", fmi2CoSimulation, FMU_GUID, "", &host_quiet2_cb, 0, 0);
        fmi2FMUstate st = NULL;
        double t = 0.0;
        for (int k = 0; k < 300; ++k, ++calls) {
            fmi2Status s = fmi2OK;
            switch (pick(14)) {
            case 0:
            case 1:
            case 2:
            case 3: { /* inputs, sometimes hostile */
                const fmi2ValueReference vr[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
                double v[3];
                for (int i = 0; i < 3; ++i) v[i] = pick(8) ? (uniform() - 0.5) * 0.02 : hostile();
                if (pick(2)) v[2] = 5 + 20 * uniform();
                s = fmi2SetReal(c, vr, 3, v);
                break;
            }
            case 4: { /* any variable, any value */
                const fmi2ValueReference vr = pick(20);
                const double v = hostile();
                s = fmi2SetReal(c, &vr, 1, &v);
                break;
            }
            case 5: {
                const fmi2ValueReference vr = pick(20);
                const fmi2Integer v = (fmi2Integer)pick(5) - 1;
                s = fmi2SetInteger(c, &vr, 1, &v);
                break;
            }
            case 6:
            case 7: {
                const double h = pick(6) ? 1e-3 : hostile();
                s = fmi2DoStep(c, pick(10) ? t : hostile(), h, fmi2True);
                if (s == fmi2OK) t += h;
                break;
            }
            case 8: s = fmi2GetFMUstate(c, &st); break;
            case 9:
                if (st) s = fmi2SetFMUstate(c, st);
                break;
            case 10: {
                switch (pick(4)) {
                case 0:
                    s = fmi2SetupExperiment(c, 0, 0, 0, 0, 0);
                    t = 0;
                    break;
                case 1: s = fmi2EnterInitializationMode(c); break;
                case 2: s = fmi2ExitInitializationMode(c); break;
                default: s = fmi2Terminate(c); break;
                }
                break;
            }
            case 11:
                if (!pick(10)) {
                    s = fmi2Reset(c);
                    t = 0;
                }
                break;
            case 12: {
                const fmi2ValueReference u[2] = {outs[pick(5)], pick(20)};
                const fmi2ValueReference kn[2] = {OC_VR_u1 + pick(3), pick(20)};
                const double dk[2] = {1.0, hostile()};
                double du[2] = {0, 0};
                const size_t n = 1 + pick(2);
                s = fmi2GetDirectionalDerivative(c, u, n, kn, n, dk, du);
                if (s == fmi2OK)
                    for (size_t i = 0; i < n; ++i) non_finite += !isfinite(du[i]);
                break;
            }
            default: {
                double y[5];
                s = fmi2GetReal(c, outs, 5, y);
                if (s == fmi2OK) {
                    ++ok_reads;
                    for (int i = 0; i < 5; ++i) non_finite += !isfinite(y[i]);
                }
            }
            }
            bad_status += !(s == fmi2OK || s == fmi2Error || s == fmi2Discard);
        }
        if (st) fmi2FreeFMUstate(c, &st);
        fmi2FreeInstance(c);
    }
    CHECK(bad_status == 0, "%ld calls returned an undefined status", bad_status);
    CHECK(non_finite == 0, "%ld non-finite values read after successful calls", non_finite);
    CHECK(ok_reads > 1000, "only %ld successful reads: the sequences did not reach step mode",
          ok_reads);
    printf("%ld random calls, %ld successful reads\n", calls, ok_reads);
    return oc_report();
}
