/*
 * Field-by-field little-endian encoding of serialized FMU states, so that
 * equal states give equal bytes on every platform (no struct images, no
 * padding).  Doubles travel as their IEEE 754 bit patterns.
 */
#ifndef FMU_BYTES_H
#define FMU_BYTES_H

#include <stdint.h>
#include <string.h>

static inline unsigned char *fmu_put_u32(unsigned char *p, uint32_t x) {
    for (int i = 0; i < 4; ++i) p[i] = (unsigned char)(x >> (8 * i));
    return p + 4;
}

static inline unsigned char *fmu_put_f64(unsigned char *p, double d) {
    uint64_t x;
    memcpy(&x, &d, 8);
    for (int i = 0; i < 8; ++i) p[i] = (unsigned char)(x >> (8 * i));
    return p + 8;
}

static inline const unsigned char *fmu_get_u32(const unsigned char *p, uint32_t *x) {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= (uint32_t)p[i] << (8 * i);
    *x = v;
    return p + 4;
}

static inline const unsigned char *fmu_get_f64(const unsigned char *p, double *d) {
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= (uint64_t)p[i] << (8 * i);
    memcpy(d, &v, 8);
    return p + 8;
}

#endif
