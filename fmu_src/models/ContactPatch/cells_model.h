/*
 * What every model on the cells (cells.h) defines alike, written once: a
 * template included (no include guard) by models/ContactPatch/model.c and
 * models/ContactPad/model.c, each after its model.h (its struct fmu_model
 * with the members params, g, out, time and cells; its FMU_STATE_FIELDS
 * and CELLS_HEAD_FIELDS: cells_fields.h) and after defining
 *   FMU_SLOT_<name>  the slots of its table's own rows (those of the law's,
 *                    the cells' and the outputs in cells_sums are here);
 *   MODEL_JAC_ROWS, MODEL_JAC_COLS, MODEL_JAC_OUTPUTS, MODEL_JAC_INPUTS
 *                    its Jacobian's size and its rows' and columns' value
 *                    references, in order.
 * It defines in turn (static, in this order) overflow (why a step was
 * refused: cells_step's index `bad`), exit_init (glue/fmu_model.h's hook),
 * and partials (glue/fmu_instance.h's fmu_jacobian).
 *
 * Defined here: VARS, the FMI 3.0 arrays of its table's FMU_ARRAYS (each
 * row's name the array cells_array gives: cellT1, cellT2, cellFn,
 * cellState), FMU_MODEL_INFO, the derivative hook, the serialized state's
 * size and writer, and for the model law_for, refused_state and
 * restored_cells.
 */

#include <stddef.h>

#include "glue/fmu_instance.h"

/* Where each variable of the table lives.  The law's parameters (the
 * table's L rows) live in params under their own names. */
#define LAW_ROW(name, vr, type, caus, var, init, start, lo, hi, unit, ...)                         \
    [vr] = {#name, FMU_T_##type, FMU_C_##caus, FMU_SET_##caus,                                     \
            start, lo,           hi,           offsetof(struct fmu_model, params.name),            \
            unit},
#define FMU_SLOT_time offsetof(struct fmu_model, time)
#define FMU_SLOT_slidingRule offsetof(struct fmu_model, params.rule)
#define FMU_SLOT_initialSlip offsetof(struct fmu_model, g.initial_slip)
#define FMU_SLOT_s1Start offsetof(struct fmu_model, g.s_start[0])
#define FMU_SLOT_s2Start offsetof(struct fmu_model, g.s_start[1])
#define FMU_SLOT_length offsetof(struct fmu_model, g.length)
#define FMU_SLOT_width offsetof(struct fmu_model, g.width)
#define FMU_SLOT_n1 offsetof(struct fmu_model, g.n[0])
#define FMU_SLOT_n2 offsetof(struct fmu_model, g.n[1])
#define FMU_SLOT_u1 offsetof(struct fmu_model, g.u[0])
#define FMU_SLOT_u2 offsetof(struct fmu_model, g.u[1])
#define FMU_SLOT_theta offsetof(struct fmu_model, g.theta)
#define FMU_SLOT_T1 offsetof(struct fmu_model, out.T[0])
#define FMU_SLOT_T2 offsetof(struct fmu_model, out.T[1])
#define FMU_SLOT_Mz offsetof(struct fmu_model, out.Mz)
#define FMU_SLOT_dissipatedEnergy offsetof(struct fmu_model, out.energy)
#define FMU_SLOT_slipFraction offsetof(struct fmu_model, out.slip_fraction)
#define FMU_SLOT_contactState offsetof(struct fmu_model, out.contact)

enum { FMU_ENUM_TYPES(FMU_ENUM_KIND) CELLS_ENUM_KINDS_END };

static const fmu_var VARS[] = {FMU_GROUPED_VARIABLES(FMU_VAR_ROW, LAW_ROW)};

static fmu_status overflow(const struct fmu_model *m, int bad, fmu_msg *msg);
static fmu_status exit_init(struct fmu_model *m, fmu_msg *msg);
static void partials(const struct fmu_model *m, double *J);

/* ---- FMI 3.0: the cells as arrays (the table's FMU_ARRAYS) ------------------ */

/* The array of each row's name, cells_array's `what`. */
enum {
    CELLS_ARRAY_cellT1 = CELLS_ARRAY_T1,
    CELLS_ARRAY_cellT2 = CELLS_ARRAY_T2,
    CELLS_ARRAY_cellFn = CELLS_ARRAY_N,
    CELLS_ARRAY_cellState = CELLS_ARRAY_STATE
};
#define CELLS_ARRAY_CASE(name, vr, type, ...)                                                      \
    case vr: *kind = FMU_T_##type; return CELLS_ARRAY_##name;

/* The array of value reference vr and its type (*kind), or -1: none. */
static int array_of(unsigned int vr, int *kind) {
    switch (vr) {
        FMU_ARRAYS(CELLS_ARRAY_CASE)
    default: return -1;
    }
}

static size_t array_size(const struct fmu_model *m, unsigned int vr, int *type) {
    if (array_of(vr, type) < 0) return 0;
    return (size_t)m->g.n[0] * (size_t)m->g.n[1];
}

/* Element [i][j] (row-major, shape (n1, n2)) is cell c = i + n1 j of the
 * shown step (cells_array). */
static void array_get(const struct fmu_model *m, unsigned int vr, void *out) {
    int type;
    const int what = array_of(vr, &type);
    if (what >= 0) cells_array(&m->cells, &m->g, what, out);
}

static const unsigned int STRUCTURAL[] = {CELLS_VR_n1, CELLS_VR_n2};
static const fmu_arrays ARRAYS = {array_size, array_get, STRUCTURAL, 2};

/* ---- the Jacobian of the shown step (the model's partials) ------------------ */

/* J fits the glue's buffer (a negative size fails to compile) */
typedef char jacobian_fits[MODEL_JAC_ROWS * MODEL_JAC_COLS <= FMU_JACOBIAN_MAX ? 1 : -1];
static const unsigned int JAC_OUTPUTS[] = {MODEL_JAC_OUTPUTS}, JAC_INPUTS[] = {MODEL_JAC_INPUTS};
typedef char jacobian_listed[sizeof JAC_OUTPUTS / sizeof *JAC_OUTPUTS == MODEL_JAC_ROWS &&
                                     sizeof JAC_INPUTS / sizeof *JAC_INPUTS == MODEL_JAC_COLS
                                 ? 1
                                 : -1];
static const fmu_jacobian JACOBIAN = {MODEL_JAC_ROWS, MODEL_JAC_COLS, JAC_OUTPUTS, JAC_INPUTS,
                                      partials};

static fmu_status derivative(const struct fmu_model *m, const unsigned int unknown[],
                             size_t n_unknown, const unsigned int known[], size_t n_known,
                             const double seed[], double out[], int adjoint, fmu_msg *msg) {
    return fmu_jacobian_derivative(&JACOBIAN, m, unknown, n_unknown, known, n_known, seed, out,
                                   adjoint, msg);
}

const fmu_model_info FMU_MODEL_INFO = {FMU_MODEL_IDENTIFIER,
                                       FMU_TOKEN,
                                       FMU_STATE_TAG,
                                       VARS,
                                       sizeof VARS / sizeof VARS[0],
                                       sizeof(struct fmu_model),
                                       NULL /* the outputs live in their slots */,
                                       exit_init,
                                       derivative,
                                       &ARRAYS};

/* ---- the step's law --------------------------------------------------------- */

/* The law fmu_model_update steps with: the cells' own, or (a parameter
 * `changed`) computed into *scratch; NULL, and msg says why, if refused. */
static const oc_law *law_for(const struct fmu_model *m, int changed, oc_law *scratch,
                             fmu_msg *msg) {
    if (!(changed & FMU_CHANGED_PARAMETERS)) return &m->cells.law;
    return cells_law(&m->params, &m->g, scratch, msg) == FMU_OK ? scratch : NULL;
}

/* ---- serialized state: the field list of model.h ---------------------------- */

size_t fmu_model_state_size(void) { return fmu_fields_size(&FMU_STATE_FIELDS); }

void fmu_model_state_write(const struct fmu_model *m, unsigned char *p) {
    p = fmu_fields_write(&CELLS_HEAD_FIELDS, m, p);
    cells_state_write(&m->cells, &m->g, p);
}

/* A serialized state refused as a step would be: overflow's why. */
static fmu_status refused_state(const struct fmu_model *m, int bad, fmu_msg *msg) {
    fmu_msg why;
    overflow(m, bad, &why);
    return fmu_fail(msg, "serialized state: %s", why.text);
}

/* The last of reading a state: the shown result recomputed (into the free
 * buffer, which nothing reads) from the checked cells at `cells` with `law`
 * and the normal forces Nc, into m->out; or refused, nothing changed. */
static fmu_status restored_cells(struct fmu_model *m, const oc_law *law, const double Nc[],
                                 const unsigned char *cells, fmu_msg *msg) {
    cells_sums S;
    const int bad = cells_state_read(&m->cells, law, &m->g, Nc, cells, &S);
    if (bad >= 0) return refused_state(m, bad, msg);
    m->out = S;
    return FMU_OK;
}
