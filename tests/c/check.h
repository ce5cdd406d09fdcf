/* Minimal test harness: CHECK records failures and the program ends with
 * "N passed, N failed" and a non-zero exit status on any failure. */
#ifndef OC_CHECK_H
#define OC_CHECK_H
#include <math.h>
#include <stdio.h>

static int oc_passed = 0, oc_failed = 0;

#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (cond) {                                                                                \
            ++oc_passed;                                                                           \
        } else {                                                                                   \
            ++oc_failed;                                                                           \
            printf("FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                                 \
            printf(__VA_ARGS__);                                                                   \
            printf("\n");                                                                          \
        }                                                                                          \
    } while (0)

#define CHECK_CLOSE(a, b, tol, what)                                                               \
    CHECK(fabs((a) - (b)) <= (tol), "%s: %.17g vs %.17g (|diff| %.3g > %.3g)", what, (double)(a),  \
          (double)(b), fabs((double)(a) - (double)(b)), (double)(tol))

static int oc_report(void) {
    printf("%d passed, %d failed\n", oc_passed, oc_failed);
    return oc_failed ? 1 : 0;
}
#endif
