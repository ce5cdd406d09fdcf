/*
 * A model's part of the serialized state as a field list (fmu_fields.h):
 * its writer, its reader with the checks, and the comparisons of two
 * records.
 */
#include "glue/fmu_fields.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "glue/fmu_bytes.h"

unsigned char *fmu_fields_write(const fmu_fields *list, const void *s, unsigned char *p) {
    for (unsigned int i = 0; i < list->n; ++i) {
        const fmu_field *f = &list->field[i];
        const char *at = (const char *)s + f->offset;
        if (f->type == FMU_FIELD_F64) {
            p = fmu_put_f64(p, *(const double *)(const void *)at);
        } else if (f->type == FMU_FIELD_U32) {
            p = fmu_put_u32(p, (uint32_t) * (const int *)(const void *)at);
        } else {
            for (unsigned int k = 0; k < f->count; ++k)
                p = fmu_fields_write(f->record, at + k * f->record->stride, p);
        }
    }
    return p;
}

/* The checks of a number read (a u32's as a double, exactly). */
static fmu_status check_read(const fmu_field *f, double v, fmu_msg *msg) {
    switch (f->check) {
    case FMU_CHECK_FINITE:
        if (isfinite(v)) return FMU_OK;
        return fmu_fail(msg, "serialized state: %s = %g is not finite", f->name, v);
    case FMU_CHECK_RANGE:
        if (f->type == FMU_FIELD_U32 && v > INT32_MAX)
            return fmu_fail(msg, "serialized state: %s = %.0f is not an int32", f->name, v);
        return fmu_model_check_range(f->vr, v, "serialized state", msg);
    case FMU_CHECK_FLAG:
        if (v == 0 || v == 1) return FMU_OK;
        return fmu_fail(msg, "serialized state: %s = %.0f is not 0 or 1", f->name, v);
    default: return FMU_OK;
    }
}

fmu_status fmu_fields_read(const fmu_fields *list, void *s, const unsigned char **p, fmu_msg *msg) {
    for (unsigned int i = 0; i < list->n; ++i) {
        const fmu_field *f = &list->field[i];
        char *at = (char *)s + f->offset;
        if (f->type == FMU_FIELD_RECORD) {
            for (unsigned int k = 0; k < f->count; ++k)
                if (fmu_fields_read(f->record, at + k * f->record->stride, p, msg) != FMU_OK)
                    return FMU_ERR;
            continue;
        }
        double v;
        if (f->type == FMU_FIELD_F64) {
            *p = fmu_get_f64(*p, &v);
            *(double *)(void *)at = v;
        } else {
            uint32_t u;
            *p = fmu_get_u32(*p, &u);
            v = (double)u;
            *(int *)(void *)at = (int)(u > INT32_MAX ? INT32_MAX : u); /* refused below */
        }
        if (check_read(f, v, msg) != FMU_OK) return FMU_ERR;
    }
    return FMU_OK;
}

int fmu_fields_same(const fmu_fields *list, const void *a, const void *b) {
    for (unsigned int i = 0; i < list->n; ++i) {
        const fmu_field *f = &list->field[i];
        const char *x = (const char *)a + f->offset, *y = (const char *)b + f->offset;
        if (f->type == FMU_FIELD_RECORD) {
            for (unsigned int k = 0; k < f->count; ++k)
                if (!fmu_fields_same(f->record, x + k * f->record->stride,
                                     y + k * f->record->stride))
                    return 0;
        } else if (memcmp(x, y, f->type == FMU_FIELD_F64 ? sizeof(double) : sizeof(int)) != 0) {
            return 0;
        }
    }
    return 1;
}

int fmu_fields_zero(const fmu_fields *list, const void *s) {
    for (unsigned int i = 0; i < list->n; ++i) {
        const fmu_field *f = &list->field[i];
        const char *at = (const char *)s + f->offset;
        if (f->type == FMU_FIELD_RECORD) {
            for (unsigned int k = 0; k < f->count; ++k)
                if (!fmu_fields_zero(f->record, at + k * f->record->stride)) return 0;
        } else if (f->type == FMU_FIELD_F64 ? *(const double *)(const void *)at != 0.0
                                            : *(const int *)(const void *)at != 0) {
            return 0;
        }
    }
    return 1;
}
