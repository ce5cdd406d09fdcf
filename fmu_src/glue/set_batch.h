/*
 * The body of fmu_model_set_float64 and fmu_model_set_int (fmu_instance.c),
 * written once and included in each (a template: no include guard).  One
 * pass: each value is checked, its old value saved and the new one written;
 * then refresh (before update, which may derive from its outputs) and
 * update.  A refused value or a refusing model puts the old ones back (last
 * first, so that a value reference named twice ends as it was) and, if
 * refresh had already rewritten its outputs, has it derive them again from
 * the old values (which it accepted before).  Only the refusal formats a
 * message.
 *
 * The includer declares SET_CTYPE stack[SAVED_ON_STACK] and defines
 * SET_CTYPE (the slots' type), SET_SLOT(m, x) (the slot of x), SET_VALUE
 * (value i, as a double), SET_TYPE_OK (whether this function may set x)
 * and SET_KIND (x's kind, for a message).  A function written instead, one
 * body for both types, made the FMI 3.0 stick step of the host build 4-5 %
 * slower (its registers and layout differ).
 */
const fmu_var *const vars = INFO.vars;
const unsigned int nv = INFO.n_vars;
SET_CTYPE *saved = stack;
if (n > SAVED_ON_STACK && !(saved = malloc(n * sizeof *saved)))
    return fmu_fail(msg, "out of memory");
int changed = 0;
fmu_status st = FMU_OK;
size_t i = 0;
for (; i < n; ++i) {
    /* a row without a variable has settable 0: no name test on the way */
    const fmu_var *x = vr[i] < nv ? &vars[vr[i]] : NULL;
    const double d = (double)(SET_VALUE);
    if (!x || !(x->settable & allow) || !(SET_TYPE_OK) || !in_range(x, d)) {
        if (x && !x->name) x = NULL;
        st = why_not_settable(x, vr[i], x ? (SET_KIND) : 0, x && (SET_TYPE_OK), d, allow, msg);
        break;
    }
    SET_CTYPE *slot = SET_SLOT(m, x);
    saved[i] = *slot;
    *slot = (SET_CTYPE)d; /* in [min, max]: exact for both slot types */
    changed |= x->settable;
}
int refreshed = 0;
if (st == FMU_OK && n > 0 && (st = model_refresh(m, msg)) == FMU_OK) {
    refreshed = 1;
    st = fmu_model_update(m, changed, allow, msg);
}
if (st != FMU_OK) {
    while (i-- > 0) *SET_SLOT(m, &vars[vr[i]]) = saved[i];
    if (refreshed) (void)model_refresh(m, NULL);
}
if (saved != stack) free(saved);
return st;

#undef SET_CTYPE
#undef SET_SLOT
#undef SET_VALUE
#undef SET_TYPE_OK
#undef SET_KIND
