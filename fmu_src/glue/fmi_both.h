/*
 * The entry points FMI 2.0 and 3.0 define alike, written once: a template
 * included by fmi2_glue.c and fmi3_glue.c (no include guard), each after
 * defining
 *   FMI_PREFIX       its functions' and types' prefix, fmi2 or fmi3;
 *   FMI_INSTANCE     its instance type;
 *   FMI_STATE, FMI_DESERIALIZE  how its FMU-state functions spell "state"
 *                    and "deserialize" (fmi2DeSerializeFMUstate,
 *                    fmi3DeserializeFMUState);
 *   FMI_CONFIG       the phase of its configuration mode (FMI 3.0's
 *                    FMU_CONFIG; 0 in FMI 2.0, which has none).
 * FMI_(name) is the version's name: FMI_(Terminate) is fmi2Terminate in
 * fmi2_glue.c, fmi3Terminate in fmi3_glue.c.  Defined here, for both:
 * FreeInstance, SetDebugLogging, ExitInitializationMode, Terminate, Reset;
 * the six FMU-state functions; the Model Exchange functions both versions
 * name alike, each refused; and for the includer status_of (an FMU_S_*
 * status as the version's), with_start_values (the end of instantiation),
 * start_at (the start time of an experiment), refuse_unless_empty,
 * no_such_variables, unsupported and FMI_NO_ME_ARRAY.
 * None of them is on a step's path (the setters, getters and doStep are
 * each glue's own).
 */

#define FMI_CAT_(a, b) a##b
#define FMI_CAT(a, b) FMI_CAT_(a, b)
#define FMI_(name) FMI_CAT(FMI_PREFIX, name)
#define FMI_STATUS FMI_(Status)
/* fmi<v><pre>FMU<state><post>, and the state's type fmi<v>FMU<state> */
#define FMI_STATE_FN(pre, post) FMI_CAT(FMI_CAT(FMI_(pre), FMU), FMI_CAT(FMI_STATE, post))
#define FMI_STATE_T FMI_CAT(FMI_(FMU), FMI_STATE)

#define NO_ME "this is a Co-Simulation FMU only"

static FMI_STATUS status_of(int s) { return (FMI_STATUS)s; }

/* A call this FMU does not provide: refused, with why, if c is an instance. */
static FMI_STATUS unsupported(FMI_INSTANCE c, const char *fn, const char *why) {
    fmu_instance *I = INST(c);
    if (I) FMU_ERROR(I, "%s: %s", fn, why);
    return FMI_(Error);
}

/* A call allowed in `phases` that has nothing to do for n = 0 and cannot do
 * anything else: OK for none, refused with why for any. */
static FMI_STATUS refuse_unless_empty(FMI_INSTANCE c, const char *fn, int phases, size_t n,
                                      const char *why) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, fn, phases)) return FMI_(Error);
    if (n == 0) return FMI_(OK);
    FMU_ERROR(I, "%s: %s", fn, why);
    return FMI_(Error);
}

/* Types of which this FMU has no variables: any value reference is unknown. */
static FMI_STATUS no_such_variables(fmu_instance *I, const char *fn, int phases, size_t nvr,
                                    const FMI_(ValueReference) vr[]) {
    if (!fmu_allowed(I, fn, phases)) return FMI_(Error);
    if (nvr == 0) return FMI_(OK);
    FMU_ERROR(I, "%s: unknown value reference %u (this FMU has no variables of that type)", fn,
              vr ? vr[0] : 0u);
    return FMI_(Error);
}

/* fmi2SetupExperiment's and fmi3EnterInitializationMode's start time, once
 * the phase is checked: FMU_S_OK, or FMU_S_ERROR (logged). */
static int start_at(fmu_instance *I, const char *fn, double startTime, int stopTimeDefined,
                    double stopTime) {
    if (!isfinite(startTime) || (stopTimeDefined && !(stopTime >= startTime))) {
        FMU_ERROR(I, "%s: startTime = %g, stopTime = %g are not a valid interval", fn, startTime,
                  stopTime);
        return FMU_S_ERROR;
    }
    fmu_msg msg;
    return fmu_result(I, fmu_set_start_time(I, startTime, &msg), &msg, fn);
}

/* ---- Instance, logging, initialization, termination, reset --------------- */

/* An instance freed with its glue's data (which came from its allocator). */
static void free_instance(fmu_instance *I) {
    void (*release)(void *) = I->release;
    void *glue = I->glue;
    fmu_instance_free(I);
    release(glue);
}

/* A new instance, the call logged, with the start values of its resources
 * (fmu_instance.h: a URI when is_uri): I, or NULL (freed) if they are
 * refused. */
static FMI_INSTANCE with_start_values(fmu_instance *I, const char *fn, const char *resources,
                                      int is_uri) {
    fmu_log(I, FMU_S_OK, FMU_LOG_CALLS, fn);
    if (fmu_load_start_values(I, fn, resources, is_uri) == 0) return I;
    free_instance(I);
    return NULL;
}

void FMI_(FreeInstance)(FMI_INSTANCE c) {
    fmu_instance *I = INST(c);
    if (!I) return;
    fmu_log(I, FMU_S_OK, FMU_LOG_CALLS, __func__);
    free_instance(I);
}

FMI_STATUS FMI_(SetDebugLogging)(FMI_INSTANCE c, FMI_(Boolean) loggingOn, size_t nCategories,
                                 const FMI_(String) categories[]) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE | FMI_CONFIG)) return FMI_(Error);
    return fmu_set_debug_logging(I, __func__, loggingOn, nCategories, categories) ? FMI_(Error)
                                                                                  : FMI_(OK);
}

FMI_STATUS FMI_(ExitInitializationMode)(FMI_INSTANCE c) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_INIT)) return FMI_(Error);
    fmu_msg msg;
    return status_of(fmu_result(I, fmu_exit_init(I, &msg), &msg, __func__));
}

FMI_STATUS FMI_(Terminate)(FMI_INSTANCE c) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_INIT | FMU_STEP)) return FMI_(Error);
    I->phase = FMU_TERMINATED;
    return FMI_(OK);
}

FMI_STATUS FMI_(Reset)(FMI_INSTANCE c) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE | FMI_CONFIG)) return FMI_(Error);
    fmu_reset(I);
    return FMI_(OK);
}

/* ---- FMU state: the objects and their checks are the instance layer's ---- */

FMI_STATUS FMI_STATE_FN(Get, )(FMI_INSTANCE c, FMI_STATE_T *state) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return FMI_(Error);
    return status_of(fmu_state_get(I, __func__, state));
}

FMI_STATUS FMI_STATE_FN(Set, )(FMI_INSTANCE c, FMI_STATE_T state) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return FMI_(Error);
    return status_of(fmu_state_set(I, __func__, state));
}

FMI_STATUS FMI_STATE_FN(Free, )(FMI_INSTANCE c, FMI_STATE_T *state) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return FMI_(Error);
    return status_of(fmu_state_free(I, __func__, state));
}

FMI_STATUS FMI_STATE_FN(Serialized, Size)(FMI_INSTANCE c, FMI_STATE_T state, size_t *size) {
    fmu_instance *I = INST(c);
    (void)state;
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return FMI_(Error);
    return status_of(fmu_state_size_of(I, __func__, size));
}

FMI_STATUS FMI_STATE_FN(Serialize, )(FMI_INSTANCE c, FMI_STATE_T state, FMI_(Byte) bytes[],
                                     size_t size) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return FMI_(Error);
    return status_of(fmu_state_serialize(I, __func__, state, (unsigned char *)bytes, size));
}

FMI_STATUS FMI_STATE_FN(FMI_DESERIALIZE, )(FMI_INSTANCE c, const FMI_(Byte) bytes[], size_t size,
                                           FMI_STATE_T *state) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return FMI_(Error);
    return status_of(fmu_state_deserialize(I, __func__, (const unsigned char *)bytes, size, state));
}

/* ---- Model Exchange: not this FMU's; exported so that every symbol resolves */

FMI_STATUS FMI_(EnterContinuousTimeMode)(FMI_INSTANCE c) { return unsupported(c, __func__, NO_ME); }
FMI_STATUS FMI_(CompletedIntegratorStep)(FMI_INSTANCE c, FMI_(Boolean) noSet, FMI_(Boolean) * enter,
                                         FMI_(Boolean) * term) {
    (void)noSet;
    (void)enter;
    (void)term;
    return unsupported(c, __func__, NO_ME);
}
/* (fmi2Real and fmi3Float64 are double) */
FMI_STATUS FMI_(SetTime)(FMI_INSTANCE c, double time) {
    (void)time;
    return unsupported(c, __func__, NO_ME);
}
/* The functions on an array of n values, one a row. */
#define FMI_NO_ME_ARRAY(name, type)                                                                \
    FMI_STATUS FMI_(name)(FMI_INSTANCE c, type values[], size_t n) {                               \
        (void)values;                                                                              \
        (void)n;                                                                                   \
        return unsupported(c, __func__, NO_ME);                                                    \
    }
FMI_NO_ME_ARRAY(SetContinuousStates, const double)
FMI_NO_ME_ARRAY(GetEventIndicators, double)
FMI_NO_ME_ARRAY(GetContinuousStates, double)
FMI_NO_ME_ARRAY(GetNominalsOfContinuousStates, double)
