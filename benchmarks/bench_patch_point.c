/* The point FMU's token and value references for bench_patch.c, in a unit of
 * its own: the two models' tables (models/OrthotropicContact/table.h, models/ContactPatch/table.h)
 * and their generated token headers share names, so one unit cannot hold both. */
#include "models/OrthotropicContact/table.h"

const char *const BENCH_POINT_TOKEN = FMU_TOKEN;

#define POINT_LAW_NAME(name, ...) #name,
#define POINT_LAW_VR(name, vr, ...) vr,
const char *const BENCH_POINT_LAW_NAMES[] = {OC_LAW_PARAMETERS(POINT_LAW_NAME) 0};
const unsigned int BENCH_POINT_LAW_VRS[] = {OC_LAW_PARAMETERS(POINT_LAW_VR) 0};

/* in this order: slidingRule, initialSlip, u1, u2, N, T1, T2, contactState */
const unsigned int BENCH_POINT_VRS[8] = {OC_VR_slidingRule, OC_VR_initialSlip, OC_VR_u1,
                                         OC_VR_u2,          OC_VR_N,           OC_VR_T1,
                                         OC_VR_T2,          OC_VR_contactState};
