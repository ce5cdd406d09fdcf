/* What the random call-sequence tests share: a seeded generator and hostile
 * values (NaN, inf, huge, zero, negative, ordinary). */
#ifndef OC_RANDOM_VALUES_H
#define OC_RANDOM_VALUES_H
#include <math.h>
#include <stdint.h>

static uint64_t rng_state;
static uint64_t next(void) { /* xorshift64* */
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return rng_state * 0x2545f4914f6cdd1dull;
}
static double uniform(void) { return (next() >> 11) * (1.0 / 9007199254740992.0); }
static unsigned pick(unsigned n) { return (unsigned)(next() % n); }

static double hostile(void) {
    switch (pick(10)) {
    case 0: return NAN;
    case 1: return INFINITY * (pick(2) ? 1 : -1);
    case 2: return 1e300 * (pick(2) ? 1 : -1);
    case 3: return 0.0;
    case 4: return -1.0;
    default: return (uniform() - 0.3) * pow(10.0, (double)pick(8) - 5.0);
    }
}
#endif
