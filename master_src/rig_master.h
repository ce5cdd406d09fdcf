/*
 * The compiled master's interface: runs the rig (fmu_src/rig/rig_core.h) over a
 * contact FMU's FMI 2.0 functions for batches of parameter sets, called from
 * Python (python/orthocontact/rig/compiled.py, through ctypes).
 *
 * The structs' layouts reach Python from here only: rm_layout describes
 * them (from the same field lists that declare them), and compiled.py builds
 * its ctypes structures from that description and checks every offset and
 * size before its first call.
 */
#ifndef RIG_MASTER_H
#define RIG_MASTER_H

#include <stddef.h>

#include "models/OrthotropicContact/table.h"
#include "rig/rig_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A contact parameter set: the law's parameters as the contact's table
 * names them (its L rows, models/OrthotropicContact/table.h; mu [-], eps [N/m], angles
 * [rad]) and the rule, the value of its slidingRule. */
#define RM_LAW_FIELD(name, ...) double name;
typedef struct {
    OC_LAW_PARAMETERS(RM_LAW_FIELD)
    int rule;
} rm_contact;

/* The structs a caller passes, one per line: "struct <name> <size>", then
 * "<field> <offset> <type>" per field in declaration order, type one of
 * double, int, long.  Returns the length written (as snprintf), or more than
 * n - 1 if buf was too small. */
int rm_layout(char *buf, size_t n);

/* Loads the contact FMU's binary (an extracted FMI 2.0 co-simulation FMU);
 * NULL with err on failure.  rm_close releases it. */
void *rm_open(const char *binary, const char *guid, const char *resources, char *err, size_t n);
void rm_close(void *h);

/* Runs count (contact, rig) sets on one instance, reset between sets; the
 * figures of set i into out[i].  0, or -1 with err. */
int rm_run(void *h, int count, const rm_contact *p, const rig_setup *r, rig_figures *out, char *err,
           size_t n);

/* One run, recorded every `every` steps (and at the last) into rows
 * (capacity x RM_RECORD_COLUMNS, row-major: t, x1, x2, T1, T2, s1, s2,
 * state, energy, drive as rig.RigResult's columns); *n_rows rows written.
 * 0, or -1 with err. */
enum { RM_RECORD_COLUMNS = 10 };
int rm_record(void *h, const rm_contact *p, const rig_setup *r, long every, double *rows,
              long capacity, long *n_rows, rig_figures *out, char *err, size_t n);

#ifdef __cplusplus
}
#endif
#endif
