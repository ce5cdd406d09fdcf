/*
 * The benchmark's peer: an independent, straightforward implementation of
 * the same contact law (Konyukhov & Schweizerhof, the three sliding rules of
 * fmu_src/law/contact_law.h) with a minimal FMI 2.0 and 3.0 layer.  It exists
 * only as a yardstick for benchmarks/bench_peer*.c (what the plainest
 * implementation pays for a step) and as a second opinion the benchmark's
 * check compares the shipped FMU with (CTest `peer_agrees`).  It is written
 * the way the law reads on paper, sharing no code with fmu_src/:
 *   B = Q(alpha) diag(eps) Q(alpha)^T, F = Q(beta) diag(1/mu^2) Q(beta)^T,
 *   q_tr = B (u - s_n), stick if sqrt(q_tr . F q_tr) <= N, else
 *   q = (I + dgamma B G)^-1 q_tr with sqrt(q . F q) = N solved for dgamma
 *   by Newton with a bisection fallback, G = F or (B F B)^-1;
 *   eq. (20): q = N z / sqrt(z . F z), z = B F q_tr;
 *   s = u - B^-1 q; dissipated energy += dgamma q . G q (eq. 20: q . ds, >= 0).
 * No care for extreme scales: it is not shipped.
 *
 * Value references are those of the shipped FMU's table (OC_VR_*).
 */
#ifndef PEER_H
#define PEER_H

/* The value references, and nothing else, from the shipped FMU's table. */
#include "models/OrthotropicContact/table.h"

enum { PEER_INSTANTIATED, PEER_INIT, PEER_STEP, PEER_TERMINATED };

typedef struct {
    /* parameters and the tensors made of them at the end of initialization */
    double mu1, mu2, eps1, eps2, alpha, beta;
    int rule;
    double B[2][2], Binv[2][2], F[2][2], BG[2][2], G[2][2];
    /* inputs, the committed state and the outputs of the last step */
    double u[2], N;
    double s[2], energy;
    double T[2];
    int contact;
    int phase;
    double time;
} peer;

void peer_init(peer *P);
/* 0, or -1 if the parameters are not admissible. */
int peer_exit_init(peer *P);
/* 0, or -1 for an unknown or unsettable vr or a non-finite value. */
int peer_set_real(peer *P, unsigned vr, double v);
int peer_set_int(peer *P, unsigned vr, int v);
/* 0, or -1 for an unknown vr. */
int peer_get_real(const peer *P, unsigned vr, double *v);
int peer_get_int(const peer *P, unsigned vr, int *v);
/* The step from the committed state to the current inputs, committed. */
void peer_step(peer *P);

#endif
