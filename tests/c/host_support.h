/* The importer's side of an FMU's logging and memory, for both FMI versions,
 * written once for every C host of the repository: the C tests
 * (tests/c/<model>/), the fuzz target (tests/fuzz/) and the benchmarks
 * (benchmarks/).  It lives with the C tests, the hosts that check what a
 * message says; the fuzz target and the benchmarks are hosts of the same
 * kind and take it from here (CMake adds tests/c to their include folders),
 * as the tests take the benchmarks' peer for the law's independent copy.
 * (tests/c/fmu_run.c and fmi_script_host.c are built on their own by the
 * platform tests, with their own loggers: they print every message.)
 *
 * Three loggers a version (FMI 2.0's also in callbacks with the C library's
 * allocator):
 *   keep:  counts the messages and keeps the last one (formatted), its
 *          status and category (host_log), to check what a refusal says;
 *   quiet: drops every message (random call sequences log thousands);
 *   print: prints "FMU: <message>" on stderr (a benchmark's failure). */
#ifndef OC_HOST_SUPPORT_H
#define OC_HOST_SUPPORT_H
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "fmi2FunctionTypes.h"
#include "fmi3FunctionTypes.h"

/* What the keep loggers saw: the number of messages since the host last
 * zeroed it, and the last message with its status and category. */
static struct {
    int count;
    int status;
    char category[64];
    char message[1024];
} host_log;

/* The status and category of a message the keep loggers see. */
static inline void host_keep(int status, const char *category) {
    ++host_log.count;
    host_log.status = status;
    snprintf(host_log.category, sizeof host_log.category, "%s", category ? category : "");
}

/* ---- FMI 2.0: the message is a printf format, its values follow --------- */

static inline void host_keep2(fmi2ComponentEnvironment e, fmi2String n, fmi2Status s, fmi2String c,
                              fmi2String m, ...) {
    host_keep((int)s, c);
    va_list ap;
    va_start(ap, m);
    vsnprintf(host_log.message, sizeof host_log.message, m, ap);
    va_end(ap);
}
static inline void host_quiet2(fmi2ComponentEnvironment e, fmi2String n, fmi2Status s, fmi2String c,
                               fmi2String m, ...) {}
static inline void host_print2(fmi2ComponentEnvironment e, fmi2String n, fmi2Status s, fmi2String c,
                               fmi2String m, ...) {
    va_list ap;
    va_start(ap, m);
    fputs("FMU: ", stderr);
    vfprintf(stderr, m, ap);
    fputc('\n', stderr);
    va_end(ap);
}
/* Each with the C library's allocator (static: an FMU may keep the pointer). */
static const fmi2CallbackFunctions host_keep2_cb = {host_keep2, calloc, free, NULL, NULL};
static const fmi2CallbackFunctions host_quiet2_cb = {host_quiet2, calloc, free, NULL, NULL};
static const fmi2CallbackFunctions host_print2_cb = {host_print2, calloc, free, NULL, NULL};

/* ---- FMI 3.0: the message is text -------------------------------------- */

static inline void host_keep3(fmi3InstanceEnvironment e, fmi3Status s, fmi3String c, fmi3String m) {
    host_keep((int)s, c);
    snprintf(host_log.message, sizeof host_log.message, "%s", m);
}
static inline void host_quiet3(fmi3InstanceEnvironment e, fmi3Status s, fmi3String c,
                               fmi3String m) {}
static inline void host_print3(fmi3InstanceEnvironment e, fmi3Status s, fmi3String c,
                               fmi3String m) {
    fprintf(stderr, "FMU: %s\n", m);
}
#endif
