/*
 * One FMU instance, independent of the FMI version: the life-cycle phase,
 * logging categories, the time, the serialized state (phase and time
 * included, so that a state restores into a freshly instantiated instance)
 * and the checks every entry point makes.  fmi2_glue.c and fmi3_glue.c are
 * thin translations of their standard's signatures onto this.  Written in
 * fmu_instance.c (the instance, its log, its phases and a step),
 * fmu_start_values.c, fmu_state.c and fmu_jacobian.c (fmu_jacobian).
 */
#ifndef FMU_INSTANCE_H
#define FMU_INSTANCE_H

#include <stddef.h>

#include "glue/fmu_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Life-cycle phases, as bits so that a call names the phases it allows. */
enum { FMU_INSTANTIATED = 1, FMU_INIT = 2, FMU_STEP = 4, FMU_TERMINATED = 8 };
/* FMI 3.0's configuration mode, entered from and left to the instantiated
 * phase: only structural parameters may be set (not in FMU_ALIVE: no state is
 * taken or restored there). */
enum { FMU_CONFIG = 16 };
#define FMU_ALIVE (FMU_INSTANTIATED | FMU_INIT | FMU_STEP | FMU_TERMINATED)
#define FMU_READABLE (FMU_INIT | FMU_STEP | FMU_TERMINATED)

enum { FMU_LOG_ERROR = 0, FMU_LOG_WARNING = 1, FMU_LOG_CALLS = 2, FMU_LOG_N = 3 };
extern const char *const FMU_LOG_NAMES[FMU_LOG_N];

/* Status levels; both standards number OK..Error the same way. */
enum { FMU_S_OK = 0, FMU_S_WARNING = 1, FMU_S_DISCARD = 2, FMU_S_ERROR = 3 };

typedef struct fmu_instance fmu_instance;
/* The version's way to hand a finished message to the importer. */
typedef void (*fmu_log_fn)(fmu_instance *I, int status, const char *category, const char *text);

struct fmu_instance {
    fmu_model *model;
    int phase;
    int log_on[FMU_LOG_N];
    char *name;
    double *start; /* start values by value reference: the table's, or the resources' */
    fmu_log_fn log;
    void *(*alloc)(size_t n, size_t size);
    void (*release)(void *p);
    void *glue;                    /* the version's own data (callbacks, environment) */
    struct fmu_held_state *states; /* the FMU states it gave out and has not freed (fmu_state.c) */
};

/* NULL if out of memory.  Errors and warnings are logged unless switched
 * off with SetDebugLogging; logging_on adds the call trace. */
fmu_instance *fmu_instance_new(const char *name, void *(*alloc)(size_t, size_t),
                               void (*release)(void *), fmu_log_fn log, void *glue, int logging_on);
void fmu_instance_free(fmu_instance *I);

void fmu_log(fmu_instance *I, int status, int category, const char *fmt, ...);
#define FMU_ERROR(I, ...) fmu_log((I), FMU_S_ERROR, FMU_LOG_ERROR, __VA_ARGS__)

/* The entry points' checks are inline: a step's three calls make them nine
 * times, and as calls into this unit they cost more than the law's stick
 * step.  Only what is rare (a refusal, the call trace) leaves the line. */
int fmu_allowed_slow(fmu_instance *I, const char *fn, int phases);
int fmu_result_error(fmu_instance *I, const fmu_msg *msg, const char *fn);

/* 1 if `fn` may be called in the current phase (logs the call), else logs
 * why not and returns 0. */
static inline int fmu_allowed(fmu_instance *I, const char *fn, int phases) {
    if (I && (I->phase & phases) && !I->log_on[FMU_LOG_CALLS]) return 1;
    return fmu_allowed_slow(I, fn, phases);
}
/* FMU_ALLOW_* for the current phase. */
static inline int fmu_settable(const fmu_instance *I) {
    int allow = 0;
    if (I->phase & (FMU_INSTANTIATED | FMU_INIT | FMU_CONFIG)) allow |= FMU_ALLOW_PARAMETERS;
    if (I->phase & (FMU_INSTANTIATED | FMU_INIT | FMU_STEP)) allow |= FMU_ALLOW_INPUTS;
    return allow;
}
/* Logs msg under `fn` and returns FMU_S_ERROR, or FMU_S_OK. */
static inline int fmu_result(fmu_instance *I, fmu_status st, const fmu_msg *msg, const char *fn) {
    return st == FMU_OK ? FMU_S_OK : fmu_result_error(I, msg, fn);
}

/* 0, or -1 (logged) for an unknown category. */
int fmu_set_debug_logging(fmu_instance *I, const char *fn, int on, size_t n,
                          const char *const categories[]);

/*
 * Start values from the FMU's resources: <resources>/start_values.txt.
 *
 * A writer that changes parameters' start values in modelDescription.xml
 * writes the same values into this file, so that the binary's defaults equal
 * the description's start values even when the importer sets nothing.
 * Format (UTF-8/ASCII text, one assignment a line):
 *   - blank lines and lines whose first non-blank character is '#' are ignored;
 *   - otherwise `name = value`, blanks (space, tab) allowed around both; `name`
 *     is the name of a *parameter* of the model's table, each at most once;
 *   - a Float64 value is a C99 hexadecimal floating constant as printf's %a
 *     and Python's float.hex() write it, [+-]0x<hex digits>[.<hex digits>]p[+-]<decimal
 *     exponent> (e.g. 0x1.a1cac083126e9p-2 for 0.408), read exactly and
 *     independently of the locale; or a decimal integer of at most 15 digits;
 *   - an Int32 or Enumeration value is a decimal integer;
 *   - every value must lie in the variable's [min, max] and be finite, and
 *     the parameters together must be admissible for the model;
 *   - lines end with LF or CRLF and are at most 1000 characters long.
 * Any other line makes instantiation fail with a logged message naming the
 * file, the line and what was expected.  No file: the compiled start values,
 * silently.  fmi2Reset / fmi3Reset return to the file's values.
 */
#define FMU_START_VALUES_FILE "start_values.txt"

/* Reads the file under `resources` (an FMI 2.0 file URI when is_uri, else an
 * FMI 3.0 native path; NULL or empty: no file) into the instance's start
 * values and re-initializes the model with them.  0, or -1 (logged under fn). */
int fmu_load_start_values(fmu_instance *I, const char *fn, const char *resources, int is_uri);
/* The native path of a file URI (file:///, file:/, file://localhost/,
 * percent-escapes, Windows drive letters), allocated with malloc; NULL if
 * `uri` is not a file URI or out of memory. */
char *fmu_path_from_uri(const char *uri);

/* Refused, unchanged, if the model's outputs at time t are not finite
 * (its refresh hook). */
fmu_status fmu_set_start_time(fmu_instance *I, double t, fmu_msg *msg);
/* Back to the instantiated state at the instance's start values. */
void fmu_reset(fmu_instance *I);
/* Ends initialization: the model's exit hook, then step mode. */
fmu_status fmu_exit_init(fmu_instance *I, fmu_msg *msg);
/* Checks and commits a communication step [t, t + h]. */
fmu_status fmu_do_step(fmu_instance *I, double t, double h, fmu_msg *msg);

/* Serialized state: tag, format version, length, phase, time, the model's
 * fields (its field list, fmu_fields.h).  Reading validates everything and
 * changes I only on success.  Format 3 (0.4.0) added the contact's initial
 * slip; a state of another format is refused with a message that says so
 * (its meaning differs: no conversion guesses it). */
enum { FMU_STATE_FORMAT = 3, FMU_STATE_HEADER_BYTES = 4 + 4 + 4 + 4 + 8 };
#define FMU_STATE_HEADER_LAYOUT                                                                    \
    "the model's tag (4 bytes), the format (u32), the length in bytes (u32), the FMI phase "       \
    "(u32: 1 instantiated, 2 initialization, 4 step, 8 terminated), the time (f64)"
size_t fmu_state_size(void);
void fmu_state_write(const fmu_instance *I, unsigned char *buf);
fmu_status fmu_state_read(fmu_instance *I, const unsigned char *buf, size_t size, fmu_msg *msg);

/* The FMU-state entry points of both standards.  A state object is a buffer
 * holding the serialized state itself, from the instance's allocator and
 * listed by it: getting serializes (into *state, allocated if NULL, else one
 * of the instance's states), setting validates and restores,
 * deserializing validates on a scratch model before any buffer is touched.
 * `fn` names the calling FMI function in messages.  Return FMU_S_*. */
int fmu_state_get(fmu_instance *I, const char *fn, void **state);
int fmu_state_set(fmu_instance *I, const char *fn, const void *state);
/* Frees a state this instance gave; refuses (logged) any other pointer. */
int fmu_state_free(fmu_instance *I, const char *fn, void **state);
int fmu_state_size_of(fmu_instance *I, const char *fn, size_t *size);
int fmu_state_serialize(fmu_instance *I, const char *fn, const void *state, unsigned char *bytes,
                        size_t size);
int fmu_state_deserialize(fmu_instance *I, const char *fn, const unsigned char *bytes, size_t size,
                          void **state);

/* A model's derivative hook (fmu_model_info.derivative) over a dense matrix
 * of partial derivatives J (`rows` x `cols`, row-major): `outputs` lists the
 * value references of its rows in order, `inputs` those of its columns
 * (the messages name them from the table).  Checks every value reference
 * and seed, then has partials(m, J) fill J and forms out = J seed
 * (adjoint: J^T seed) over the rows of `unknown` and the columns of
 * `known`, refusing a result that overflows. */
typedef struct {
    int rows, cols;
    const unsigned int *outputs, *inputs;
    void (*partials)(const fmu_model *m, double *J);
} fmu_jacobian;
enum { FMU_JACOBIAN_MAX = 64 }; /* rows x cols at most */
fmu_status fmu_jacobian_derivative(const fmu_jacobian *jac, const fmu_model *m,
                                   const unsigned int unknown[], size_t n_unknown,
                                   const unsigned int known[], size_t n_known, const double seed[],
                                   double out[], int adjoint, fmu_msg *msg);

#ifdef __cplusplus
}
#endif
#endif
