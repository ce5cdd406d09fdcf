/* Random FMI 3.0 call sequences with random and hostile values (NaN, inf,
 * huge, unknown references, wrong states, mismatched array sizes, corrupted
 * serialized states).  Whatever happens, a call returns a defined status, a
 * successful read never yields a non-finite number, and under the
 * sanitizers nothing reads or writes out of bounds. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fmi3Functions.h"
#include "host_support.h"
#include "models/OrthotropicContact/table.h"
#include "random_values.h"

int main(void) {
    rng_state = 0x2545f4914f6cdd1dull;
    const fmi3ValueReference outs[5] = {OC_VR_T1, OC_VR_T2, OC_VR_s1, OC_VR_s2,
                                        OC_VR_dissipatedEnergy};
    long ok_reads = 0, calls = 0, bad_status = 0, non_finite = 0;
    for (int episode = 0; episode < 200; ++episode) {
        fmi3Instance c = fmi3InstantiateCoSimulation("fuzz", FMU_GUID, "", 0, 0, 0, 0, NULL, 0,
                                                     NULL, host_quiet3, NULL);
        fmi3FMUState st = NULL;
        double t = 0.0;
        for (int k = 0; k < 300; ++k, ++calls) {
            fmi3Status s = fmi3OK;
            switch (pick(16)) {
            case 0:
            case 1:
            case 2:
            case 3: { /* inputs, sometimes hostile */
                const fmi3ValueReference vr[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
                double v[3];
                for (int i = 0; i < 3; ++i) v[i] = pick(8) ? (uniform() - 0.5) * 0.02 : hostile();
                if (pick(2)) v[2] = 5 + 20 * uniform();
                s = fmi3SetFloat64(c, vr, 3, v, pick(10) ? 3 : pick(5));
                break;
            }
            case 4: { /* any variable, any value */
                const fmi3ValueReference vr = pick(20);
                const double v = hostile();
                s = fmi3SetFloat64(c, &vr, 1, &v, 1);
                break;
            }
            case 5: {
                const fmi3ValueReference vr = pick(20);
                const fmi3Int64 v = (fmi3Int64)pick(5) - 1;
                const fmi3Int32 w = (fmi3Int32)pick(5) - 1;
                s = pick(2) ? fmi3SetInt64(c, &vr, 1, &v, 1) : fmi3SetInt32(c, &vr, 1, &w, 1);
                break;
            }
            case 6:
            case 7: {
                const double h = pick(6) ? 1e-3 : hostile();
                fmi3Boolean ev, term, early;
                double last;
                s = fmi3DoStep(c, pick(10) ? t : hostile(), h, fmi3True, &ev, &term, &early, &last);
                if (s == fmi3OK) t += h;
                break;
            }
            case 8: s = fmi3GetFMUState(c, &st); break;
            case 9:
                if (st) s = fmi3SetFMUState(c, st);
                break;
            case 10: { /* serialize, maybe corrupt, deserialize, restore */
                if (!st) break;
                size_t n = 0;
                s = fmi3SerializedFMUStateSize(c, st, &n);
                if (s != fmi3OK || n == 0 || n > 4096) break;
                unsigned char buf[4096];
                s = fmi3SerializeFMUState(c, st, buf, n);
                if (s != fmi3OK) break;
                if (pick(2)) buf[pick((unsigned)n)] ^= (unsigned char)(1u << pick(8));
                fmi3FMUState st2 = NULL;
                s = fmi3DeserializeFMUState(c, buf, pick(4) ? n : pick((unsigned)n), &st2);
                if (s == fmi3OK) {
                    s = fmi3SetFMUState(c, st2);
                    fmi3FreeFMUState(c, &st2);
                }
                break;
            }
            case 11: {
                switch (pick(3)) {
                case 0:
                    s = fmi3EnterInitializationMode(c, 0, 0, 0, 0, 0);
                    t = 0;
                    break;
                case 1: s = fmi3ExitInitializationMode(c); break;
                default: s = fmi3Terminate(c); break;
                }
                break;
            }
            case 12:
                if (!pick(10)) {
                    s = fmi3Reset(c);
                    t = 0;
                }
                break;
            case 13: {
                const fmi3ValueReference u[2] = {outs[pick(5)], pick(20)};
                const fmi3ValueReference kn[2] = {OC_VR_u1 + pick(3), pick(20)};
                const double dk[2] = {1.0, hostile()};
                double du[2] = {0, 0};
                const size_t n = 1 + pick(2);
                s = pick(2) ? fmi3GetDirectionalDerivative(c, u, n, kn, n, dk, n, du, n)
                            : fmi3GetAdjointDerivative(c, u, n, kn, n, dk, n, du, n);
                if (s == fmi3OK)
                    for (size_t i = 0; i < n; ++i) non_finite += !isfinite(du[i]);
                break;
            }
            case 14: {
                const fmi3ValueReference vr = pick(20);
                fmi3Int32 i32;
                fmi3Int64 i64;
                s = pick(2) ? fmi3GetInt32(c, &vr, 1, &i32, 1) : fmi3GetInt64(c, &vr, 1, &i64, 1);
                break;
            }
            default: {
                double y[5];
                s = fmi3GetFloat64(c, outs, 5, y, 5);
                if (s == fmi3OK) {
                    ++ok_reads;
                    for (int i = 0; i < 5; ++i) non_finite += !isfinite(y[i]);
                }
            }
            }
            bad_status += !(s == fmi3OK || s == fmi3Error || s == fmi3Discard);
        }
        if (st) fmi3FreeFMUState(c, &st);
        fmi3FreeInstance(c);
    }
    CHECK(bad_status == 0, "%ld calls returned an undefined status", bad_status);
    CHECK(non_finite == 0, "%ld non-finite values read after successful calls", non_finite);
    CHECK(ok_reads > 1000, "only %ld successful reads: the sequences did not reach step mode",
          ok_reads);
    printf("%ld random calls, %ld successful reads\n", calls, ok_reads);
    return oc_report();
}
