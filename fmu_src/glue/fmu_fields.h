/*
 * A model's part of the serialized state as a field list, declared once
 * (in its model.h, beside its struct): the writer (fmu_fields_write), the
 * reader with its checks (fmu_fields_read), the size (fmu_fields_size) and
 * the layout paragraph of the reference (gen_model_description's manifest,
 * docs/reference/variables.md) all come from it.  Field by field,
 * little-endian (fmu_bytes.h), no padding: equal states give equal bytes
 * on every platform.
 *
 * A list describes a struct S: each field is a double (FMU_F64) or an int
 * slot travelling as a u32 (FMU_U32) at its offset in S, or a record of
 * another list at an offset (FMU_RECORD: the law's parameters, a committed
 * state), or `count` such records one after the other (FMU_RECORDS: the
 * patch's cells, which its model writes and reads itself, their states
 * lying where its steps left them).  `group` names a field and those after
 * it that have the same group in the layout ("the inputs").
 */
#ifndef FMU_FIELDS_H
#define FMU_FIELDS_H

#include <stddef.h>

#include "glue/fmu_model.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { FMU_FIELD_F64 = 1, FMU_FIELD_U32 = 2, FMU_FIELD_RECORD = 3 };

/* What reading a field checks before its model sees it. */
enum {
    FMU_CHECK_NONE,   /* nothing: its model checks it with what it derives */
    FMU_CHECK_FINITE, /* a finite number */
    FMU_CHECK_RANGE,  /* in its table's [min, max] (value reference vr), finite; a u32 an int32 */
    FMU_CHECK_FLAG    /* 0 or 1 */
};

typedef struct fmu_fields fmu_fields;
typedef struct {
    const char *name;          /* in the layout: the variable's name where it holds one */
    const char *group;         /* the layout's words for it and its group */
    unsigned char type, check; /* FMU_FIELD_*, FMU_CHECK_* */
    unsigned int vr;           /* FMU_CHECK_RANGE's variable */
    size_t offset;             /* in S */
    const fmu_fields *record;  /* FMU_FIELD_RECORD: its records' list, */
    unsigned int count;        /*   how many there are */
} fmu_field;

struct fmu_fields {
    const fmu_field *field;
    unsigned int n;
    size_t stride; /* sizeof S, the distance of two records */
};

#define FMU_F64(S, member, name, group, check, vr)                                                 \
    { name, group, FMU_FIELD_F64, FMU_CHECK_##check, vr, offsetof(S, member), NULL, 0 }
#define FMU_U32(S, member, name, group, check, vr)                                                 \
    { name, group, FMU_FIELD_U32, FMU_CHECK_##check, vr, offsetof(S, member), NULL, 0 }
#define FMU_RECORD(S, member, list, group)                                                         \
    { "", group, FMU_FIELD_RECORD, FMU_CHECK_NONE, 0, offsetof(S, member), list, 1 }
#define FMU_RECORDS(S, member, list, count, group)                                                 \
    { "", group, FMU_FIELD_RECORD, FMU_CHECK_NONE, 0, offsetof(S, member), list, count }
/* The list of an array of fmu_field describing S. */
#define FMU_FIELDS(array, S)                                                                       \
    { array, sizeof array / sizeof array[0], sizeof(S) }

/* Bytes the list takes (inline: the model-description generator, which
 * links no glue, states the size too). */
static inline size_t fmu_fields_size(const fmu_fields *list) {
    size_t n = 0;
    for (unsigned int i = 0; i < list->n; ++i) {
        const fmu_field *f = &list->field[i];
        n += f->type == FMU_FIELD_F64   ? 8
             : f->type == FMU_FIELD_U32 ? 4
                                        : f->count * fmu_fields_size(f->record);
    }
    return n;
}
/* Writes s's fields at p; returns the end. */
unsigned char *fmu_fields_write(const fmu_fields *list, const void *s, unsigned char *p);
/* Reads the fields at *p into s, checking each as its list says, and
 * advances *p; on the first that fails FMU_ERR with the reason ("serialized
 * state: ..."), s then partly written: read into a scratch copy, or put
 * back what was there. */
fmu_status fmu_fields_read(const fmu_fields *list, void *s, const unsigned char **p, fmu_msg *msg);
/* 1 if every field of a and b has the same bits (not ==: -0.0 and +0.0
 * differ, as the tensors they give do). */
int fmu_fields_same(const fmu_fields *list, const void *a, const void *b);
/* 1 if every number of s is 0 (of either sign). */
int fmu_fields_zero(const fmu_fields *list, const void *s);

#ifdef __cplusplus
}
#endif
#endif
