/* The random call sequences of test_fmi2_random.c and test_fmi3_random.c,
 * written once: a template (no include guard) each includes after defining
 *   RANDOM_FMI    its FMI version, 2 or 3;
 *   RANDOM_SEED   the generator's seed;
 *   RANDOM_OPS    the operations (OP_*), one drawn at a time (one listed k
 *                 times is drawn k times as often);
 * and then defines the version's calls on the point contact declared below.
 * Whatever happens, a call returns a defined status, a successful read never
 * yields a non-finite number, and under the sanitizers nothing reads or
 * writes out of bounds. */

#if RANDOM_FMI == 2
typedef fmi2Component inst;
typedef fmi2Status status;
typedef fmi2FMUstate fmu_state;
#define R_OK fmi2OK
#define R_ERROR fmi2Error
#define R_DISCARD fmi2Discard
#else
typedef fmi3Instance inst;
typedef fmi3Status status;
typedef fmi3FMUState fmu_state;
#define R_OK fmi3OK
#define R_ERROR fmi3Error
#define R_DISCARD fmi3Discard
#endif

static inst instantiate(void);
static void free_instance(inst c);
static status set_inputs(inst c, const double v[3]); /* u1, u2, N */
static status set_real(inst c, unsigned int vr, double v);
static status set_integer(inst c, unsigned int vr); /* a random value */
static status do_step(inst c, double t, double h);
static status get_state(inst c, fmu_state *st);
static status set_state(inst c, fmu_state st);
static void free_state(inst c, fmu_state *st);
/* One at random of: setup (FMI 2.0), enter or exit initialization,
 * terminate; the time back to 0 where the experiment starts again. */
static status change_mode(inst c, double *t);
static status reset(inst c);
/* n unknowns by n knowns, of the version's kinds at random */
static status derivative(inst c, const unsigned int u[], const unsigned int kn[], size_t n,
                         const double dk[], double du[]);
static status read_outputs(inst c, const unsigned int outs[5], double y[5]);
#if RANDOM_FMI == 3
/* serialize, maybe corrupt, deserialize (maybe short), restore */
static status serialized_round_trip(inst c, fmu_state st);
static status get_integer(inst c, unsigned int vr);
#endif

enum {
    OP_INPUTS,
    OP_REAL,
    OP_INTEGER,
    OP_STEP,
    OP_GET_STATE,
    OP_SET_STATE,
    OP_SERIALIZED,
    OP_MODE,
    OP_RESET,
    OP_DERIVATIVE,
    OP_GET_INTEGER,
    OP_READ
};
static const unsigned char OPS[] = {RANDOM_OPS};

int main(void) {
    rng_state = RANDOM_SEED;
    const unsigned int outs[5] = {OC_VR_T1, OC_VR_T2, OC_VR_s1, OC_VR_s2, OC_VR_dissipatedEnergy};
    long ok_reads = 0, calls = 0, bad_status = 0, non_finite = 0;
    for (int episode = 0; episode < 200; ++episode) {
        inst c = instantiate();
        fmu_state st = NULL;
        double t = 0.0;
        for (int k = 0; k < 300; ++k, ++calls) {
            status s = R_OK;
            switch (OPS[pick((unsigned)sizeof OPS)]) {
            case OP_INPUTS: { /* inputs, sometimes hostile */
                double v[3];
                for (int i = 0; i < 3; ++i) v[i] = pick(8) ? (uniform() - 0.5) * 0.02 : hostile();
                if (pick(2)) v[2] = 5 + 20 * uniform();
                s = set_inputs(c, v);
                break;
            }
            case OP_REAL: { /* any variable, any value */
                const unsigned int vr = pick(20);
                s = set_real(c, vr, hostile());
                break;
            }
            case OP_INTEGER: s = set_integer(c, pick(20)); break;
            case OP_STEP: {
                const double h = pick(6) ? 1e-3 : hostile();
                s = do_step(c, pick(10) ? t : hostile(), h);
                if (s == R_OK) t += h;
                break;
            }
            case OP_GET_STATE: s = get_state(c, &st); break;
            case OP_SET_STATE:
                if (st) s = set_state(c, st);
                break;
#if RANDOM_FMI == 3
            case OP_SERIALIZED:
                if (st) s = serialized_round_trip(c, st);
                break;
            case OP_GET_INTEGER: s = get_integer(c, pick(20)); break;
#endif
            case OP_MODE: s = change_mode(c, &t); break;
            case OP_RESET:
                if (!pick(10)) {
                    s = reset(c);
                    t = 0;
                }
                break;
            case OP_DERIVATIVE: {
                const unsigned int u[2] = {outs[pick(5)], pick(20)};
                const unsigned int kn[2] = {OC_VR_u1 + pick(3), pick(20)};
                const double dk[2] = {1.0, hostile()};
                double du[2] = {0, 0};
                const size_t n = 1 + pick(2);
                s = derivative(c, u, kn, n, dk, du);
                if (s == R_OK)
                    for (size_t i = 0; i < n; ++i) non_finite += !isfinite(du[i]);
                break;
            }
            default: {
                double y[5];
                s = read_outputs(c, outs, y);
                if (s == R_OK) {
                    ++ok_reads;
                    for (int i = 0; i < 5; ++i) non_finite += !isfinite(y[i]);
                }
            }
            }
            bad_status += !(s == R_OK || s == R_ERROR || s == R_DISCARD);
        }
        if (st) free_state(c, &st);
        free_instance(c);
    }
    CHECK(bad_status == 0, "%ld calls returned an undefined status", bad_status);
    CHECK(non_finite == 0, "%ld non-finite values read after successful calls", non_finite);
    CHECK(ok_reads > 1000, "only %ld successful reads: the sequences did not reach step mode",
          ok_reads);
    printf("%ld random calls, %ld successful reads\n", calls, ok_reads);
    return oc_report();
}
