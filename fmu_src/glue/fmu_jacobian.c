/*
 * Directional derivatives, once for every model: the model's hook, or its
 * Jacobian's through fmu_jacobian_derivative (fmu_instance.h), which checks
 * every value reference and seed and forms J seed or J^T seed.
 */
#include <math.h>
#include <stdio.h>

#include "glue/fmu_access.h"

fmu_status fmu_model_derivative(const fmu_model *m, const unsigned int unknown[], size_t n_unknown,
                                const unsigned int known[], size_t n_known, const double seed[],
                                double out[], int adjoint, fmu_msg *msg) {
    if (!INFO.derivative)
        return fmu_fail(msg, "this FMU provides no derivatives (providesDirectionalDerivative = "
                             "false)");
    return INFO.derivative(m, unknown, n_unknown, known, n_known, seed, out, adjoint, msg);
}

static const char *name_or_unknown(unsigned int vr) {
    const fmu_var *x = var_of(vr);
    return x ? x->name : "unknown";
}

/* vr's position in list[0..n), -1 if it is not there */
static int index_of(const unsigned int *list, int n, unsigned int vr) {
    for (int i = 0; i < n; ++i)
        if (list[i] == vr) return i;
    return -1;
}

/* "T1, T2, ...": the names of list[0..n), for a message */
static const char *names_of(const unsigned int *list, int n, char *buf, size_t size) {
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < n && used < size; ++i) {
        const int w =
            snprintf(buf + used, size - used, "%s%s", i ? ", " : "", name_or_unknown(list[i]));
        if (w < 0) break;
        used += (size_t)w;
    }
    return buf;
}

fmu_status fmu_jacobian_derivative(const fmu_jacobian *jac, const fmu_model *m,
                                   const unsigned int unknown[], size_t n_unknown,
                                   const unsigned int known[], size_t n_known, const double seed[],
                                   double out[], int adjoint, fmu_msg *msg) {
    char names[256];
    for (size_t j = 0; j < n_known; ++j)
        if (index_of(jac->inputs, jac->cols, known[j]) < 0)
            return fmu_fail(msg, "known vr %u (%s) is not an input %s", known[j],
                            name_or_unknown(known[j]),
                            names_of(jac->inputs, jac->cols, names, sizeof names));
    for (size_t i = 0; i < n_unknown; ++i)
        if (index_of(jac->outputs, jac->rows, unknown[i]) < 0)
            return fmu_fail(msg, "unknown vr %u (%s) is not an output %s", unknown[i],
                            name_or_unknown(unknown[i]),
                            names_of(jac->outputs, jac->rows, names, sizeof names));
    const size_t n_seed = adjoint ? n_unknown : n_known;
    for (size_t k = 0; k < n_seed; ++k)
        if (!isfinite(seed[k])) return fmu_fail(msg, "seed %zu is not finite", k);
    double J[FMU_JACOBIAN_MAX];
    jac->partials(m, J);
    const size_t n_out = adjoint ? n_known : n_unknown, cols = (size_t)jac->cols;
    /* every index was checked above */
#define JAC(row_vr, col_vr)                                                                        \
    J[(size_t)index_of(jac->outputs, jac->rows, row_vr) * cols +                                   \
      (size_t)index_of(jac->inputs, jac->cols, col_vr)]
    for (size_t k = 0; k < n_out; ++k) {
        double acc = 0.0;
        if (adjoint)
            for (size_t i = 0; i < n_unknown; ++i) acc += JAC(unknown[i], known[k]) * seed[i];
        else
            for (size_t j = 0; j < n_known; ++j) acc += JAC(unknown[k], known[j]) * seed[j];
        if (!isfinite(acc)) return fmu_fail(msg, "the derivative overflows");
        out[k] = acc;
    }
#undef JAC
    return FMU_OK;
}
