/* The pad FMU's token and value references for bench_patch.c, in a unit of
 * its own (as bench_patch_point.c the point's): the models' tables and their
 * generated token headers share names, so one unit cannot hold two. */
#include "models/ContactPad/table.h"

const char *const BENCH_PAD_TOKEN = FMU_TOKEN;

/* in this order: the inputs u1, u2, theta, d, phi1, phi2; the outputs T1,
 * T2, Mz, Fn, M1, M2; n1, n2, kn, slipFraction, contactFraction; the input vr */
const unsigned int BENCH_PAD_VRS[18] = {PAD_VR_u1,
                                        PAD_VR_u2,
                                        PAD_VR_theta,
                                        PAD_VR_d,
                                        PAD_VR_phi1,
                                        PAD_VR_phi2,
                                        PAD_VR_T1,
                                        PAD_VR_T2,
                                        PAD_VR_Mz,
                                        PAD_VR_Fn,
                                        PAD_VR_M1,
                                        PAD_VR_M2,
                                        PAD_VR_n1,
                                        PAD_VR_n2,
                                        PAD_VR_kn,
                                        PAD_VR_slipFraction,
                                        PAD_VR_contactFraction,
                                        PAD_VR_vr};
