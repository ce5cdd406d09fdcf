/* Unit tests of the FMI-free core against closed forms and balances. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "glue/fmu_bytes.h"
#include "glue/fmu_model.h"
#include "law/contact_law.h"
#include "models/OrthotropicContact/model.h"
#include "models/OrthotropicContact/table.h"
#include "random_values.h"

static const double PI = 3.14159265358979323846;

static oc_params params(int rule, double mu1, double mu2, double e1, double e2, double a,
                        double b) {
    oc_params p = {mu1, mu2, e1, e2, a, b, rule};
    return p;
}

static double yield(const oc_law *L, const double q[2]) {
    const double Fq0 = L->F[0][0] * q[0] + L->F[0][1] * q[1];
    const double Fq1 = L->F[1][0] * q[0] + L->F[1][1] * q[1];
    return sqrt(q[0] * Fq0 + q[1] * Fq1);
}

static void test_params_check(void) {
    oc_params good = params(2, 0.1, 0.5, 1e4, 1e3, 0.3, 0.4), p;
    CHECK(oc_params_check(&good) == NULL, "valid parameters rejected");
    p = good;
    p.mu1 = 0;
    CHECK(oc_params_check(&p) != NULL, "mu1 = 0 accepted");
    p = good;
    p.mu2 = -1;
    CHECK(oc_params_check(&p) != NULL, "mu2 < 0 accepted");
    p = good;
    p.eps1 = NAN;
    CHECK(oc_params_check(&p) != NULL, "eps1 NaN accepted");
    p = good;
    p.eps2 = INFINITY;
    CHECK(oc_params_check(&p) != NULL, "eps2 inf accepted");
    p = good;
    p.alpha = NAN;
    CHECK(oc_params_check(&p) != NULL, "alpha NaN accepted");
    p = good;
    p.rule = 4;
    CHECK(oc_params_check(&p) != NULL, "rule 4 accepted");
    oc_law L;
    memset(&L, 0x5a, sizeof L);
    p = good;
    p.rule = 0;
    CHECK(oc_law_init(&L, &p) == -1, "init with bad rule succeeded");
}

/* B and F as the paper builds them (eq. 6, 30), component by component. */
static void test_tensors(void) {
    const double a = 0.3, b = 1.1;
    oc_params p = params(2, 0.2, 0.7, 3e4, 2e3, a, b);
    oc_law L;
    CHECK(oc_law_init(&L, &p) == 0, "init failed");
    const double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b);
    CHECK_CLOSE(L.B[0][0], 3e4 * ca * ca + 2e3 * sa * sa, 1e-9, "B11");
    CHECK_CLOSE(L.B[0][1], (3e4 - 2e3) * sa * ca, 1e-9, "B12");
    CHECK_CLOSE(L.B[1][1], 3e4 * sa * sa + 2e3 * ca * ca, 1e-9, "B22");
    const double f1 = 1 / 0.04, f2 = 1 / 0.49;
    CHECK_CLOSE(L.F[0][0], f1 * cb * cb + f2 * sb * sb, 1e-12, "F11");
    CHECK_CLOSE(L.F[0][1], (f1 - f2) * sb * cb, 1e-12, "F12");
    CHECK_CLOSE(L.F[1][1], f1 * sb * sb + f2 * cb * cb, 1e-12, "F22");
}

static void test_stick_and_open(void) {
    oc_params p = params(2, 0.4, 0.6, 2e4, 5e3, 0.7, 0.2);
    oc_law L;
    oc_law_init(&L, &p);
    oc_state s0 = oc_state_unloaded(1e-4, -2e-4, 0.5);
    const double u[2] = {1.3e-4, -1.8e-4};
    oc_step st;
    oc_law_step(&L, &s0, u, 10.0, &st);
    CHECK(st.contact == OC_STICK, "small displacement did not stick (state %d)", st.contact);
    const double e0 = u[0] - s0.s[0], e1 = u[1] - s0.s[1];
    CHECK_CLOSE(st.q[0], L.B[0][0] * e0 + L.B[0][1] * e1, 1e-12, "stick q1 = B e");
    CHECK_CLOSE(st.q[1], L.B[1][0] * e0 + L.B[1][1] * e1, 1e-12, "stick q2 = B e");
    CHECK(st.next.s[0] == s0.s[0] && st.next.s[1] == s0.s[1], "stick changed the slip");
    CHECK(st.next.energy == s0.energy, "stick dissipated energy");

    oc_law_step(&L, &s0, u, 0.0, &st);
    CHECK(st.contact == OC_OPEN, "N = 0 is not open");
    CHECK(st.q[0] == 0 && st.q[1] == 0, "open contact carries force");
    CHECK(st.next.s[0] == u[0] && st.next.s[1] == u[1], "open: slip does not follow the body");
    CHECK(st.next.energy == s0.energy, "open contact counted released energy");
    /* Re-contact starts unloaded. */
    oc_step st2;
    oc_law_step(&L, &st.next, u, 5.0, &st2);
    CHECK(st2.contact == OC_STICK && st2.q[0] == 0 && st2.q[1] == 0, "re-contact is loaded");
    oc_law_step(&L, &s0, u, -3.0, &st);
    CHECK(st.contact == OC_OPEN, "N < 0 is not open");
}

/* A trial far outside the ellipse returns onto it, for every rule and many
 * directions, with positive dissipation. */
static void test_return_onto_yield_surface(void) {
    for (int rule = 1; rule <= 3; ++rule) {
        oc_params p = params(rule, 0.1, 0.5, 1e4, 1e3, 0.46, 0.46 + PI / 2);
        oc_law L;
        oc_law_init(&L, &p);
        for (int k = 0; k < 36; ++k) {
            const double th = 2 * PI * k / 36;
            const double mag = 1e-3 * (1 + k);
            const double u[2] = {mag * cos(th), mag * sin(th)};
            oc_state s0 = oc_state_unloaded(0, 0, 0);
            oc_step st;
            const double N = 7.5;
            oc_law_step(&L, &s0, u, N, &st);
            CHECK(st.contact == OC_SLIP, "rule %d dir %d did not slip", rule, k);
            CHECK_CLOSE(yield(&L, st.q), N, 1e-12 * N, "on the yield surface");
            CHECK(st.next.energy > 0, "rule %d dir %d: dissipation %g not positive", rule, k,
                  st.next.energy);
            /* The elastic relation holds after the step. */
            const double e0 = u[0] - st.next.s[0], e1 = u[1] - st.next.s[1];
            CHECK_CLOSE(L.B[0][0] * e0 + L.B[0][1] * e1, st.q[0], 1e-12 * N, "q = B(u - s)");
            if (rule != OC_RULE_EQ20) {
                /* Implicit rule: slip increment is dgamma G q with G = F or (BFB)^-1. */
                double G[2][2];
                if (rule == OC_RULE_ASSOCIATED)
                    memcpy(G, L.F, sizeof G);
                else {
                    double A[2][2];
                    for (int i = 0; i < 2; ++i)
                        for (int j = 0; j < 2; ++j) {
                            double acc = 0;
                            for (int k1 = 0; k1 < 2; ++k1)
                                for (int k2 = 0; k2 < 2; ++k2)
                                    acc += L.B[i][k1] * L.F[k1][k2] * L.B[k2][j];
                            A[i][j] = acc;
                        }
                    const double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
                    G[0][0] = A[1][1] / det;
                    G[1][1] = A[0][0] / det;
                    G[0][1] = -A[0][1] / det;
                    G[1][0] = -A[1][0] / det;
                }
                const double Gq0 = G[0][0] * st.q[0] + G[0][1] * st.q[1];
                const double Gq1 = G[1][0] * st.q[0] + G[1][1] * st.q[1];
                const double cross = st.next.s[0] * Gq1 - st.next.s[1] * Gq0;
                const double scale = hypot(st.next.s[0], st.next.s[1]) * hypot(Gq0, Gq1);
                CHECK(fabs(cross) <= 1e-10 * scale, "rule %d: slip not along G q (%g)", rule,
                      cross / scale);
            }
        }
    }
}

/* Isotropic B and F: the classic radial return, q = N q_tr / |q_tr| mu. */
static void test_isotropic_radial_return(void) {
    oc_params p = params(2, 0.3, 0.3, 5e3, 5e3, 0.2, 1.0);
    oc_law L;
    oc_law_init(&L, &p);
    oc_state s0 = oc_state_unloaded(0, 0, 0);
    const double u[2] = {0.01, -0.004};
    oc_step st;
    oc_law_step(&L, &s0, u, 20.0, &st);
    const double n = hypot(u[0], u[1]);
    CHECK_CLOSE(st.q[0], 0.3 * 20 * u[0] / n, 1e-12, "radial q1");
    CHECK_CLOSE(st.q[1], 0.3 * 20 * u[1] / n, 1e-12, "radial q2");
    /* dissipated = q . s = mu N (|u| - mu N / eps) */
    CHECK_CLOSE(st.next.energy, 6.0 * (n - 6.0 / 5e3), 1e-12, "radial dissipation");
}

/* Driving u along a straight line, the force settles where u - s is
 * constant: the slip moves along the drive direction d, i.e. G q || d, and
 * the steady force is independent of the step size (the steady state is a
 * fixed point of the implicit update for any increment). */
static void steady_force(int rule, double du, const double d[2], double q[2], int *state) {
    oc_params p = params(rule, 0.1, 0.5, 1e4, 1e3, 0.4, 0.4 + PI / 2);
    oc_law L;
    oc_law_init(&L, &p);
    oc_state s = oc_state_unloaded(0, 0, 0);
    oc_step st;
    const double travel = 0.05;
    const int n = (int)(travel / du + 0.5);
    for (int k = 1; k <= n; ++k) {
        const double u[2] = {k * du * d[0], k * du * d[1]};
        oc_law_step(&L, &s, u, 10.0, &st);
        s = st.next;
    }
    q[0] = st.q[0];
    q[1] = st.q[1];
    *state = st.contact;
}

static void test_step_size_independence(void) {
    const double d[2] = {cos(0.3), sin(0.3)};
    for (int rule = 1; rule <= 2; ++rule) {
        double qa[2], qb[2], qc[2];
        int sa, sb, sc;
        steady_force(rule, 1e-3, d, qa, &sa);
        steady_force(rule, 1e-4, d, qb, &sb);
        steady_force(rule, 1e-5, d, qc, &sc);
        CHECK(sa == OC_SLIP && sb == OC_SLIP && sc == OC_SLIP, "not sliding at the end");
        CHECK_CLOSE(qa[0], qc[0], 1e-9, "steady q1, du 1e-3 vs 1e-5");
        CHECK_CLOSE(qa[1], qc[1], 1e-9, "steady q2, du 1e-3 vs 1e-5");
        CHECK_CLOSE(qb[0], qc[0], 1e-9, "steady q1, du 1e-4 vs 1e-5");
        CHECK_CLOSE(qb[1], qc[1], 1e-9, "steady q2, du 1e-4 vs 1e-5");
    }
    /* The literal eq. (20) is not step-size independent: keep that visible. */
    double qa[2], qc[2];
    int sa, sc;
    steady_force(3, 1e-3, d, qa, &sa);
    steady_force(3, 1e-5, d, qc, &sc);
    CHECK(fabs(qa[0] - qc[0]) + fabs(qa[1] - qc[1]) > 1e-3,
          "eq. (20) unexpectedly step-size independent");
}

/* Discrete energy balance of backward Euler: the work of the force,
 * sum q_{n+1} . du, equals the change of stored energy, the dissipation and
 * the algorithmic term sum 1/2 de . B de, to rounding. */
static void test_energy_balance(void) {
    for (int rule = 1; rule <= 2; ++rule) {
        oc_params p = params(rule, 0.2, 0.6, 8e3, 2e3, 0.9, -0.3);
        oc_law L;
        oc_law_init(&L, &p);
        oc_state s = oc_state_unloaded(0, 0, 0);
        double u_prev[2] = {0, 0}, e_prev[2] = {0, 0};
        double work = 0, algo = 0;
        oc_step st;
        for (int k = 1; k <= 2000; ++k) {
            const double t = k * 1e-3;
            const double u[2] = {0.02 * sin(3 * t) + 0.01 * t, 0.015 * sin(5 * t + 1) * cos(t)};
            const double N = 8 + 3 * sin(7 * t);
            oc_law_step(&L, &s, u, N, &st);
            work += st.q[0] * (u[0] - u_prev[0]) + st.q[1] * (u[1] - u_prev[1]);
            const double e[2] = {u[0] - st.next.s[0], u[1] - st.next.s[1]};
            const double de[2] = {e[0] - e_prev[0], e[1] - e_prev[1]};
            algo += 0.5 * (de[0] * (L.B[0][0] * de[0] + L.B[0][1] * de[1]) +
                           de[1] * (L.B[1][0] * de[0] + L.B[1][1] * de[1]));
            s = st.next;
            memcpy(u_prev, u, sizeof u);
            memcpy(e_prev, e, sizeof e);
        }
        const double stored = 0.5 * (e_prev[0] * (L.B[0][0] * e_prev[0] + L.B[0][1] * e_prev[1]) +
                                     e_prev[1] * (L.B[1][0] * e_prev[0] + L.B[1][1] * e_prev[1]));
        CHECK(s.energy > 0, "no dissipation over a sliding history");
        CHECK_CLOSE(work, stored + s.energy + algo, 1e-10 * work, "discrete energy balance");
    }
}

/* Held inputs after a slip step stick with the same force. */
static void test_held_inputs_stick(void) {
    for (int rule = 1; rule <= 3; ++rule) {
        oc_params p = params(rule, 0.408, 0.625, 1.251e4, 1e4, 2.0, 0.43);
        oc_law L;
        oc_law_init(&L, &p);
        oc_state s = oc_state_unloaded(0.3, -0.2, 1.0);
        const double u[2] = {0.47, -0.13};
        oc_step a, b;
        oc_law_step(&L, &s, u, 18.4, &a);
        CHECK(a.contact == OC_SLIP, "did not slip");
        oc_law_step(&L, &a.next, u, 18.4, &b);
        CHECK(b.contact == OC_STICK, "rule %d: held inputs slipped again", rule);
        CHECK_CLOSE(b.q[0], a.q[0], 1e-10 * 18.4, "held q1");
        CHECK_CLOSE(b.q[1], a.q[1], 1e-10 * 18.4, "held q2");
        CHECK(b.next.energy == a.next.energy, "held inputs dissipated");
    }
}

/* The consistent tangent against central differences, in every branch. */
static void check_jacobian(int rule, const oc_state *s0, const double u[2], double N,
                           int expect_state) {
    oc_params p = params(rule, 0.15, 0.45, 1.2e4, 3e3, 0.5, 1.3);
    oc_law L;
    oc_law_init(&L, &p);
    oc_step st;
    oc_law_step(&L, s0, u, N, &st);
    CHECK(st.contact == expect_state, "rule %d: state %d, expected %d", rule, st.contact,
          expect_state);
    double J[OC_JAC_ROWS][OC_JAC_COLS];
    oc_law_jacobian(&L, s0, u, N, &st, J);
    const double hs[3] = {1e-8, 1e-8, 1e-6};
    for (int j = 0; j < 3; ++j) {
        double up[2] = {u[0], u[1]}, um[2] = {u[0], u[1]}, Np = N, Nm = N;
        if (j < 2) {
            up[j] += hs[j];
            um[j] -= hs[j];
        } else {
            Np += hs[j];
            Nm -= hs[j];
        }
        oc_step sp, sm;
        oc_law_step(&L, s0, up, Np, &sp);
        oc_law_step(&L, s0, um, Nm, &sm);
        const double yp[5] = {-sp.q[0], -sp.q[1], sp.next.s[0], sp.next.s[1], sp.next.energy};
        const double ym[5] = {-sm.q[0], -sm.q[1], sm.next.s[0], sm.next.s[1], sm.next.energy};
        for (int i = 0; i < 5; ++i) {
            const double fd = (yp[i] - ym[i]) / (2 * hs[j]);
            const double tol = 1e-5 * (fabs(J[i][j]) + fabs(fd)) + 1e-6;
            CHECK(fabs(fd - J[i][j]) <= tol, "rule %d state %d dY%d/dX%d: tangent %.10g fd %.10g",
                  rule, expect_state, i, j, J[i][j], fd);
        }
    }
}

static void test_jacobian(void) {
    oc_state s0 = oc_state_unloaded(1e-3, 2e-3, 0.25);
    const double u_stick[2] = {1.05e-3, 2.02e-3}, u_slip[2] = {4e-3, -2e-3};
    for (int rule = 1; rule <= 3; ++rule) {
        check_jacobian(rule, &s0, u_stick, 12.0, OC_STICK);
        check_jacobian(rule, &s0, u_slip, 12.0, OC_SLIP);
        check_jacobian(rule, &s0, u_slip, -1.0, OC_OPEN);
    }
}

/* Extreme but admissible inputs never give NaN. */
static void test_finite_everywhere(void) {
    const double Ns[] = {1e-9, 1e-3, 1.0, 1e3, 1e9};
    const double us[] = {0.0, 1e-300, 1e-12, 1e-6, 1.0, 1e3};
    for (int rule = 1; rule <= 3; ++rule) {
        oc_params p = params(rule, 1e-3, 10.0, 1e-2, 1e9, 0.1, 2.2);
        oc_law L;
        CHECK(oc_law_init(&L, &p) == 0, "extreme params rejected");
        for (size_t i = 0; i < sizeof Ns / sizeof Ns[0]; ++i)
            for (size_t j = 0; j < sizeof us / sizeof us[0]; ++j) {
                oc_state s0 = oc_state_unloaded(0, 0, 0);
                const double u[2] = {us[j], -0.5 * us[j]};
                oc_step st;
                oc_law_step(&L, &s0, u, Ns[i], &st);
                CHECK(oc_step_is_finite(&st), "rule %d N %g u %g: non-finite step", rule, Ns[i],
                      us[j]);
            }
    }
}

/* Strongly anisotropic stiffness and friction: after a slip step, held
 * inputs stick with exactly the committed force, and repeat forever. */
static void test_held_inputs_anisotropic(void) {
    const double ratios[] = {1e-10, 1e-8, 1e8, 1e10};
    for (int rule = 1; rule <= 3; ++rule)
        for (size_t r = 0; r < 4; ++r)
            for (int fr = 0; fr < 2; ++fr) {
                const double mu2 = fr ? 0.3 * 1e5 : 0.5, mu1 = fr ? 0.3 * 1e-5 : 0.3;
                oc_params p = params(rule, mu1, mu2, 1e4, 1e4 * ratios[r], 0.37, 1.21);
                oc_law L;
                CHECK(oc_law_init(&L, &p) == 0, "init ratio %g", ratios[r]);
                oc_state s = oc_state_unloaded(0.0, 0.0, 0.0);
                oc_step a, b;
                for (int k = 1; k <= 40; ++k) {
                    const double u[2] = {0.0123 * k, -0.0071 * k};
                    oc_law_step(&L, &s, u, 18.4, &a);
                    s = a.next;
                    for (int rep = 0; rep < 3; ++rep) {
                        oc_law_step(&L, &s, u, 18.4, &b);
                        CHECK(b.contact == OC_STICK,
                              "rule %d ratio %g fr %d k %d: held inputs "
                              "slipped again",
                              rule, ratios[r], fr, k);
                        CHECK(b.q[0] == a.q[0] && b.q[1] == a.q[1],
                              "rule %d ratio %g: held "
                              "force changed by %g",
                              rule, ratios[r], fabs(b.q[0] - a.q[0]));
                        CHECK(b.next.energy == a.next.energy, "held inputs dissipated");
                        s = b.next;
                    }
                }
            }
}

/* A trial force 1e200 times the yield force: finite, on the yield surface. */
static void test_far_trial(void) {
    for (int rule = 1; rule <= 2; ++rule) {
        oc_params p = params(rule, 0.1, 0.5, 1e4, 1e3, 0.46, 1.9);
        oc_law L;
        oc_law_init(&L, &p);
        oc_state s0 = oc_state_unloaded(0, 0, 0);
        const double rhos[] = {1e-50, 1e-155, 1e-200};
        for (int k = 0; k < 3; ++k) {
            const double N = 1.0 * rhos[k], u[2] = {1e-4, 3e-5};
            oc_step st;
            oc_law_step(&L, &s0, u, N, &st);
            CHECK(oc_step_is_finite(&st), "rule %d N %g: not finite", rule, N);
            CHECK(st.contact == OC_SLIP, "rule %d N %g: did not slip", rule, N);
            CHECK_CLOSE(oc_norm2(st.next.a[0], st.next.a[1]), N, 1e-14 * N, "|a| = N");
            CHECK(oc_state_check(&L, &st.next) == NULL, "committed state refused");
        }
    }
}

/* oc_norm2 is hypot without the libm symbol: exact at the extremes. */
static void test_norm2(void) {
    CHECK_CLOSE(oc_norm2(3e300, 4e300), 5e300, 4e284, "norm2 overflow");
    CHECK_CLOSE(oc_norm2(3e-300, 4e-300), 5e-300, 2e-315, "norm2 underflow");
    CHECK(oc_norm2(3 * 0x1p1000, 4 * 0x1p1000) == 5 * 0x1p1000, "norm2 exact");
    /* Equivariant under power-of-two scaling, bit for bit, over the range. */
    for (int e = -1000; e <= 1000; e += 37) {
        const double x = 0.3141592653589793, y = -2.718281828459045, k = ldexp(1.0, e);
        CHECK(oc_norm2(x * k, y * k) == oc_norm2(x, y) * k, "norm2 not equivariant at 2^%d", e);
    }
    CHECK(oc_norm2(0, 0) == 0, "norm2 zero");
    CHECK(oc_norm2(-3, 4) == 5, "norm2 plain");
    CHECK(isinf(oc_norm2(INFINITY, 1)), "norm2 inf");
}

/* ---- oc_model: the contact as a model of the shared FMI glue -------------- */

static void test_model_table_and_errors(void) {
    oc_model m;
    fmu_model_init(&m);
    fmu_msg msg;
    /* Every table entry is readable through its own type, nothing else is. */
    int n_real = 0, n_int = 0;
    for (unsigned vr = 0; vr < 40; ++vr) {
        double d;
        int32_t i;
        const int ok_r = fmu_model_get_float64(&m, &vr, 1, &d, &msg) == FMU_OK;
        const int ok_i = fmu_model_get_int(&m, &vr, 1, &i, 4, FMU_INT32 | FMU_ENUM, &msg) == FMU_OK;
        CHECK(!(ok_r && ok_i), "vr %u readable as both types", vr);
        CHECK((ok_r || ok_i) == (fmu_model_variable_name(vr) != NULL),
              "vr %u table/accessor mismatch", vr);
        n_real += ok_r;
        n_int += ok_i;
    }
    CHECK(n_real == 17 && n_int == 3, "found %d Float64 and %d integer variables", n_real, n_int);
    /* Enumeration and Int32 are told apart (FMI 3.0 reads them differently). */
    const unsigned vr_rule = OC_VR_slidingRule, vr_state = OC_VR_contactState;
    int64_t i64;
    CHECK(fmu_model_get_int(&m, &vr_rule, 1, &i64, 8, FMU_ENUM, &msg) == FMU_OK && i64 == 2,
          "rule");
    CHECK(fmu_model_get_int(&m, &vr_rule, 1, &i64, 8, FMU_INT32, &msg) == FMU_ERR, "rule as Int32");
    CHECK(fmu_model_get_int(&m, &vr_state, 1, &i64, 8, FMU_ENUM, &msg) == FMU_ERR, "state as enum");

    const unsigned vr_mu1 = OC_VR_mu1, vr_T1 = OC_VR_T1, vr_u1 = OC_VR_u1, vr_alpha = OC_VR_alpha,
                   vr_time = OC_VR_time, bad = 99;
    double v = -1;
    CHECK(fmu_model_set_float64(&m, &vr_mu1, 1, &v, FMU_ALLOW_PARAMETERS, &msg) == FMU_ERR,
          "mu1<0");
    CHECK(strstr(msg.text, "mu1") != NULL, "message does not name mu1: %s", msg.text);
    CHECK(m.params.mu1 == 0.408, "rejected call changed mu1");
    v = 1e-151;
    CHECK(fmu_model_set_float64(&m, &vr_mu1, 1, &v, 3, &msg) == FMU_ERR, "mu1 below its min");
    v = 13.0;
    CHECK(fmu_model_set_float64(&m, &vr_alpha, 1, &v, 3, &msg) == FMU_ERR, "alpha above its max");
    v = 1;
    CHECK(fmu_model_set_float64(&m, &vr_time, 1, &v, 3, &msg) == FMU_ERR, "time set");
    CHECK(fmu_model_set_float64(&m, &vr_T1, 1, &v, 3, &msg) == FMU_ERR, "output set");
    CHECK(fmu_model_set_float64(&m, &bad, 1, &v, 3, &msg) == FMU_ERR, "unknown vr set");
    CHECK(fmu_model_set_float64(&m, &vr_mu1, 1, &v, FMU_ALLOW_INPUTS, &msg) == FMU_ERR,
          "fixed parameter set after initialization");
    v = NAN;
    CHECK(fmu_model_set_float64(&m, &vr_u1, 1, &v, 3, &msg) == FMU_ERR, "NaN input accepted");
    const unsigned vrs[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
    const double big[3] = {1e308, -1e308, 1e308};
    /* In step mode: before it ends, the initial slip follows the inputs (no force). */
    CHECK(fmu_model_set_float64(&m, vrs, 3, big, FMU_ALLOW_INPUTS, &msg) == FMU_ERR,
          "overflowing inputs accepted");
    CHECK(m.u[0] == 0 && m.N == 0, "rejected inputs were kept");
    /* Absurd but finite inputs: rejected or finite, never NaN. */
    const double absurd[][3] = {{1e3, -1e3, 1e-300}, {1e-300, 1e-300, 1e-300}, {1e200, 0, 1e200}};
    for (int k = 0; k < 3; ++k) {
        const fmu_status st = fmu_model_set_float64(&m, vrs, 3, absurd[k], 3, &msg);
        const unsigned outs[5] = {OC_VR_T1, OC_VR_T2, OC_VR_s1, OC_VR_s2, OC_VR_dissipatedEnergy};
        double y[5];
        fmu_model_get_float64(&m, outs, 5, y, &msg);
        for (int i = 0; i < 5; ++i)
            CHECK(isfinite(y[i]), "absurd inputs %d (status %d): output %d = %g", k, st, i, y[i]);
    }
    fmu_model_init(&m);
    /* Atomic: one bad value in a batch sets none of it. */
    const unsigned mixed[2] = {OC_VR_mu2, OC_VR_eps1};
    const double mv[2] = {0.9, -5};
    CHECK(fmu_model_set_float64(&m, mixed, 2, mv, 3, &msg) == FMU_ERR, "eps1 < 0 accepted");
    CHECK(m.params.mu2 == 0.625, "partial batch applied");
    int32_t r = 7;
    CHECK(fmu_model_set_int(&m, &vr_rule, 1, &r, 4, FMU_ENUM, 3, &msg) == FMU_ERR,
          "rule 7 accepted");
    r = 1;
    CHECK(fmu_model_set_int(&m, &vr_state, 1, &r, 4, FMU_INT32, 3, &msg) == FMU_ERR, "output set");
}

/* Drives a model over a path with sliding, opening and re-contact. */
static void drive(oc_model *m, int steps) {
    fmu_msg msg;
    const unsigned vrs[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
    for (int k = 1; k <= steps; ++k) {
        const double v[3] = {1e-4 * k, 3e-5 * k * sin(0.1 * k), k % 17 == 0 ? 0.0 : 18.0};
        fmu_model_set_float64(m, vrs, 3, v, FMU_ALLOW_INPUTS, &msg);
        fmu_model_do_step(m, 1e-3, &msg);
    }
}

static void test_model_state(void) {
    oc_model a, b;
    fmu_model_init(&a);
    fmu_model_init(&b);
    fmu_msg msg;
    drive(&a, 50);
    unsigned char buf[512], again[512];
    const size_t n = fmu_model_state_size();
    CHECK(n <= sizeof buf, "state larger than expected");
    memset(buf, 0xAA, sizeof buf);
    memset(again, 0x55, sizeof again);
    fmu_model_state_write(&a, buf);
    CHECK(fmu_model_state_read(&b, buf, &msg) == FMU_OK, "%s", msg.text);
    fmu_model_state_write(&b, again);
    CHECK(memcmp(buf, again, n) == 0, "equal states serialize to different bytes");
    /* The restored model continues exactly as the original. */
    drive(&a, 20);
    drive(&b, 20);
    double ya[5], yb[5];
    const unsigned outs[5] = {OC_VR_T1, OC_VR_T2, OC_VR_s1, OC_VR_s2, OC_VR_dissipatedEnergy};
    fmu_model_get_float64(&a, outs, 5, ya, &msg);
    fmu_model_get_float64(&b, outs, 5, yb, &msg);
    CHECK(memcmp(ya, yb, sizeof ya) == 0, "restored model diverged");

    /* Forged fields are refused and change nothing. */
    struct {
        size_t at;
        double value;
        const char *what;
    } forged[] = {{0, -1.0, "mu1 < 0"},
                  {32, 100.0, "alpha out of range"},
                  {6 * 8 + 4 + 3 * 8 + 7 * 8, -1e37, "negative energy"},
                  {6 * 8 + 4 + 3 * 8 + 2 * 8, 0.0, "open contact with a force"},
                  {6 * 8 + 4 + 3 * 8 + 3 * 8, 1e6, "force outside the yield surface"},
                  {6 * 8 + 4, NAN, "NaN input"}};
    for (size_t k = 0; k < sizeof forged / sizeof forged[0]; ++k) {
        memcpy(again, buf, n);
        fmu_put_f64(again + forged[k].at, forged[k].value);
        oc_model c = b;
        CHECK(fmu_model_state_read(&b, again, &msg) == FMU_ERR, "forged state accepted: %s",
              forged[k].what);
        CHECK(memcmp(&c, &b, sizeof b) == 0, "refused state changed the model: %s", forged[k].what);
    }
    memcpy(again, buf, n);
    fmu_put_u32(again + 6 * 8, 7);
    CHECK(fmu_model_state_read(&b, again, &msg) == FMU_ERR, "rule 7 accepted");
    memcpy(again, buf, n);
    fmu_put_u32(again + n - 4, 2);
    CHECK(fmu_model_state_read(&b, again, &msg) == FMU_ERR, "commit flag 2 accepted");
}

/* ---- the law's promises at the edges ------------------------------------ */

/* An independent reference, for tests only: the return map for alpha = beta,
 * where B, F and G are diagonal in the shared axes and each component
 * returns as q_i = qtr_i / (1 + l k_i) (k_i = eps_i / mu_i^2 associated,
 * mu_i^2 / eps_i coupled); l solves sum (q_i / mu_i)^2 = N^2, by bisection
 * in long double.  From an unloaded start at s = 0, displacement d in the
 * axes; returns the force T = -q in X1, X2 and the dissipation l q.G q. */
static void aligned_reference(int rule, const double mu[2], const double eps[2], double th,
                              const long double d[2], double N, long double T[2], long double *E) {
    long double qt[2], k[2], q[2], l = 0;
    for (int i = 0; i < 2; ++i) {
        qt[i] = (long double)eps[i] * d[i];
        k[i] = rule == OC_RULE_ASSOCIATED ? (long double)eps[i] / ((long double)mu[i] * mu[i])
                                          : (long double)mu[i] * mu[i] / eps[i];
        q[i] = qt[i];
    }
#define OC_REF_PHI(x)                                                                              \
    sqrtl(powl(qt[0] / (mu[0] * (1 + (x)*k[0])), 2) + powl(qt[1] / (mu[1] * (1 + (x)*k[1])), 2))
    if (OC_REF_PHI(0.0L) > N) {
        long double lo = 0, hi = 1e-400L;
        while (OC_REF_PHI(hi) > N) {
            lo = hi;
            hi *= 2;
        }
        for (int it = 0; it < 400 && hi - lo > hi * 1e-21L; ++it) {
            const long double m = 0.5L * (lo + hi);
            if (OC_REF_PHI(m) > N)
                lo = m;
            else
                hi = m;
        }
        l = 0.5L * (lo + hi);
        for (int i = 0; i < 2; ++i) q[i] = qt[i] / (1 + l * k[i]);
    }
#undef OC_REF_PHI
    const long double c = cosl(th), s = sinl(th);
    T[0] = -(c * q[0] - s * q[1]);
    T[1] = -(s * q[0] + c * q[1]);
    *E = l * (q[0] * q[0] * k[0] / eps[0] + q[1] * q[1] * k[1] / eps[1]);
}

/* |T - T_ref| / (eps |T_ref| + the largest change of T_ref when the
 * displacement moves along an axis by up to 4 eps |d|, on a grid of steps
 * eps |d|, or a component that small becomes 0): how far the law is from
 * exact, in units of what the rounding of its inputs alone can cause (at a
 * contrast of 1e20 an ulp of the rotation is a different force; near the
 * point where the weak axis alone reaches the yield surface the exact map is
 * that steep). */
static double aligned_error(int rule, double mu1, double mu2, double e1, double e2, double th,
                            const double du[2], double N, double *energy_error) {
    const double mu[2] = {mu1, mu2}, eps[2] = {e1, e2};
    oc_params p = params(rule, mu1, mu2, e1, e2, th, th);
    oc_law L;
    if (oc_law_init(&L, &p) != 0) return INFINITY;
    oc_state s0 = oc_state_unloaded(0, 0, 0);
    oc_step st;
    oc_law_step(&L, &s0, du, N, &st);
    const long double c = cosl(th), s = sinl(th);
    const long double d[2] = {c * du[0] + s * du[1], -s * du[0] + c * du[1]};
    long double T[2], E;
    aligned_reference(rule, mu, eps, th, d, N, T, &E);
    const long double dl = 4 * DBL_EPSILON * sqrtl(d[0] * d[0] + d[1] * d[1]);
    long double near[18][2];
    int nn = 0;
    for (int j = -4; j <= 4; ++j) {
        if (j == 0) continue;
        near[nn][0] = d[0] + j * dl / 4;
        near[nn++][1] = d[1];
        near[nn][0] = d[0];
        near[nn++][1] = d[1] + j * dl / 4;
    }
    near[nn][0] = fabsl(d[0]) <= dl ? 0 : d[0];
    near[nn++][1] = d[1];
    near[nn][0] = d[0];
    near[nn++][1] = fabsl(d[1]) <= dl ? 0 : d[1];
    long double sT = 0, sE = 0;
    for (int k = 0; k < nn; ++k) {
        long double T2[2], E2;
        aligned_reference(rule, mu, eps, th, near[k], N, T2, &E2);
        sT = fmaxl(sT, hypotl(T2[0] - T[0], T2[1] - T[1]));
        sE = fmaxl(sE, fabsl(E2 - E));
    }
    const long double dT = hypotl(-st.q[0] - T[0], -st.q[1] - T[1]);
    *energy_error = (double)(fabsl(st.next.energy - E) / (DBL_EPSILON * E + sE + LDBL_MIN));
    return (double)(dT / (DBL_EPSILON * hypotl(T[0], T[1]) + sT));
}

/* Both implicit rules as accurate as their inputs allow at every
 * contrast, with the friction and stiffness axes shared (alpha = beta). */
static void test_accuracy_aligned_axes(void) {
    /* The reported case: mu1/mu2 = eps1/eps2 = r, slides in all directions.
     * The error was 7e-13 at r = 1e2 .. 6 % at 1e8 and |T| 1000x off at 1e10. */
    double worst = 0, worstE = 0;
    for (int rule = 1; rule <= 2; ++rule)
        for (double r = 1e2; r <= 1.1e10; r *= 100)
            for (int a = 0; a < 4; ++a)
                for (int k = 0; k < 72; ++k) {
                    const double th = (double[]){0.0, 0.3, -2.2, PI / 2}[a], phi = k * PI / 36;
                    const double len = 1e3 * 0.5 * 10 / (1e5 / r);
                    const double du[2] = {len * cos(phi), len * sin(phi)};
                    double eE = 0;
                    worst = fmax(
                        worst, aligned_error(rule, 0.9, 0.9 / r, 1e5, 1e5 / r, th, du, 10.0, &eE));
                    worstE = fmax(worstE, eE);
                }
    CHECK(worst <= 4, "aligned axes, mu1/mu2 = eps1/eps2 <= 1e10: force error %.3g x bound", worst);
    CHECK(worstE <= 4, "aligned axes, mu1/mu2 = eps1/eps2 <= 1e10: energy error %.3g x bound",
          worstE);
    /* A slide along the shared strong axis: |T| = mu1 N (was 8.3e-6 N for 7.2 N). */
    for (int rule = 1; rule <= 2; ++rule) {
        oc_params p = params(rule, 0.72, 0.72e-10, 1e6, 1e-4, 0.7, 0.7);
        oc_law L;
        oc_law_init(&L, &p);
        oc_state s0 = oc_state_unloaded(0, 0, 0);
        oc_step st;
        const double du[2] = {cos(0.7), sin(0.7)};
        oc_law_step(&L, &s0, du, 10.0, &st);
        CHECK_CLOSE(oc_norm2(st.q[0], st.q[1]), 7.2, 8 * DBL_EPSILON * 7.2,
                    "|T| along the strong axis");
        CHECK(fabs(st.q[0] * sin(0.7) - st.q[1] * cos(0.7)) <= 8 * DBL_EPSILON * 7.2,
              "rule %d: the force leaves the strong axis: q = (%g, %g)", rule, st.q[0], st.q[1]);
    }
    /* Random parameters over the documented range: mu and eps ratios up to 1e10
     * each, any shared axes, trials from inside to 1e4 times outside. */
    rng_state = 0x19u;
    worst = worstE = 0;
    for (int n = 0; n < 3000; ++n) {
        const int rule = 1 + (int)pick(2);
        const double mu1 = pow(10, -1.3 + 1.3 * uniform()),
                     mu2 = mu1 * pow(10, 20 * uniform() - 10);
        const double e1 = pow(10, 2 + 4 * uniform()), e2 = e1 * pow(10, 20 * uniform() - 10);
        const double th = pick(4) == 0 ? 0.0 : PI * (2 * uniform() - 1);
        const double phi = pick(4) == 0 ? th + pick(4) * PI / 2 : PI * (2 * uniform() - 1);
        const double N = 1 + 19 * uniform();
        const double len = fmax(mu1, mu2) * N / fmin(e1, e2) * pow(10, 4 * uniform() - 3);
        const double du[2] = {len * cos(phi), len * sin(phi)};
        double eE = 0;
        worst = fmax(worst, aligned_error(rule, mu1, mu2, e1, e2, th, du, N, &eE));
        worstE = fmax(worstE, eE);
    }
    CHECK(worst <= 4, "aligned axes, random: force error %.3g x bound", worst);
    CHECK(worstE <= 4, "aligned axes, random: energy error %.3g x bound", worstE);
}

/* A trial at the top of the exponent range is seen as what it is. */
static void test_huge_trial(void) {
    CHECK(oc_norm2(1.2e308, 0) == 1.2e308, "norm2(1.2e308, 0) = %g", oc_norm2(1.2e308, 0));
    CHECK(oc_norm2(-1e308, 1e308) == 1e308 * sqrt(2.0), "norm2(-1e308, 1e308) = %g",
          oc_norm2(-1e308, 1e308));
    CHECK(oc_norm2(DBL_MAX, DBL_MAX) == INFINITY, "norm2(max, max) is not inf");
    for (int rule = 1; rule <= 3; ++rule) {
        oc_params p = params(rule, 0.5, 0.5, 1e300, 1e300, 0, 0);
        oc_law L;
        oc_law_init(&L, &p);
        oc_state s0 = oc_state_unloaded(0, 0, 0);
        oc_step st;
        const double u[2] = {5e7, 0};
        oc_law_step(&L, &s0, u, 1.0, &st);
        CHECK(st.contact == OC_SLIP && oc_step_is_finite(&st),
              "rule %d: q_tr = 5e307 N, N = 1: state %d", rule, st.contact);
        CHECK_CLOSE(st.q[0], 0.5, 4 * DBL_EPSILON, "huge trial: q1 = mu N");
        oc_state forged = oc_state_unloaded(0, 0, 0);
        forged.N = 1.0;
        forged.a[0] = 1.2e308;
        CHECK(oc_state_check(&L, &forged) != NULL,
              "a committed force of 1.2e308 with N = 1 accepted");
    }
}

/* Whatever the law commits, it accepts back, and it sticks with held
 * inputs, also for subnormal N (through the FMU's state, into itself). */
static void test_subnormal_normal_force(void) {
    int refused = 0, moved = 0, restored = 0;
    fmu_msg msg;
    const unsigned vrs[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N}, vr_rule = OC_VR_slidingRule;
    for (int rule = 1; rule <= 3; ++rule) {
        oc_model m;
        fmu_model_init(&m);
        int32_t r = rule;
        fmu_model_set_int(&m, &vr_rule, 1, &r, 4, FMU_ENUM, 3, &msg);
        for (int k = 1; k < 400; ++k) {
            const double v[3] = {1e-300 * cos(k), 1e-300 * sin(k),
                                 k * 7.3 * 4.9406564584124654e-324};
            oc_step st;
            const oc_state s0 = oc_state_unloaded(0, 0, 0);
            oc_law_step(&m.law, &s0, v, v[2], &st);
            refused += oc_state_check(&m.law, &st.next) != NULL;
            oc_step held;
            oc_law_step(&m.law, &st.next, v, v[2], &held);
            moved += held.contact != OC_STICK || held.q[0] != st.q[0] || held.q[1] != st.q[1];
            fmu_model_set_float64(&m, vrs, 3, v, FMU_ALLOW_INPUTS, &msg);
            fmu_model_do_step(&m, 1e-3, &msg);
            unsigned char buf[512];
            fmu_model_state_write(&m, buf);
            restored += fmu_model_state_read(&m, buf, &msg) == FMU_OK;
        }
    }
    CHECK(refused == 0, "%d of 1197 committed states with subnormal N refused by the law", refused);
    CHECK(moved == 0, "%d of 1197 held steps with subnormal N changed the force", moved);
    CHECK(restored == 1197, "the FMU refused %d of 1197 of its own states", 1197 - restored);
}

/* A tiny N with an ordinary displacement is an ordinary slip. */
static void test_tiny_normal_force(void) {
    oc_model m;
    fmu_model_init(&m); /* the default parameters */
    for (int k = 0; k < 5; ++k) {
        const double N = (double[]){1e-300, 1e-305, 1e-307, 1e-310, 1e-320}[k];
        oc_state s0 = oc_state_unloaded(0, 0, 0);
        oc_step st;
        const double u[2] = {1, 0};
        oc_law_step(&m.law, &s0, u, N, &st);
        CHECK(st.contact == OC_SLIP && oc_step_is_finite(&st), "N = %g: state %d, finite %d", N,
              st.contact, oc_step_is_finite(&st));
        /* Slid the whole way (the elastic part is ~N / eps): the dissipation
         * is q . s, with q on the yield surface. */
        const double qs = st.q[0] * st.next.s[0] + st.q[1] * st.next.s[1];
        CHECK(st.next.energy > 0 && fabs(st.next.energy - qs) <= 1e-12 * qs + 0x1p-1070,
              "N = %g: energy %.17g, q.s %.17g", N, st.next.energy, qs);
        fmu_msg msg;
        const unsigned vrs[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
        const double v[3] = {1, 0, N};
        CHECK(fmu_model_set_float64(&m, vrs, 3, v, FMU_ALLOW_INPUTS, &msg) == FMU_OK,
              "N = %g refused: %s", N, msg.text);
        fmu_model_init(&m);
    }
}

/* Eq. (20) at a friction ratio of 1e10 along friction axis 1. */
static void test_eq20_strong_friction_contrast(void) {
    for (int rule = 1; rule <= 3; ++rule)
        for (int a = 0; a < 3; ++a) {
            const double b = (double[]){0.0, 0.3, -2.0}[a];
            oc_params p = params(rule, 0.5, 0.5e-10, 1e4, 1e4, b, b);
            oc_law L;
            oc_law_init(&L, &p);
            oc_state s0 = oc_state_unloaded(0, 0, 0);
            oc_step st;
            const double u[2] = {cos(b), sin(b)};
            oc_law_step(&L, &s0, u, 1.0, &st);
            CHECK(oc_step_is_finite(&st) && st.contact == OC_SLIP, "rule %d beta %g: no slip", rule,
                  b);
            CHECK_CLOSE(oc_norm2(st.q[0], st.q[1]), 0.5, 4 * DBL_EPSILON, "|q| = mu1 N");
            CHECK(fabs(st.q[0] * sin(b) - st.q[1] * cos(b)) <= 4 * DBL_EPSILON,
                  "rule %d beta %g: the force leaves friction axis 1: (%g, %g)", rule, b, st.q[0],
                  st.q[1]);
            CHECK_CLOSE(st.next.energy, 0.5 * (1 - 0.5 / 1e4), 1e-14,
                        "energy mu1 N (|u| - mu1 N / eps)");
        }
}

/* Power-of-two units give the same bits, wherever the outputs are
 * normal numbers (the distribution of tests/fmus/test_scale_properties.py, and
 * the corner the fuzzer found: mu2 ~ 1e-10, k = 2^-455). */
static int subnormal(double x) { return x != 0 && fabs(x) < DBL_MIN; }
static void test_power_of_two_units(void) {
    (void)hostile; /* random_values.h's, for the glue tests */
    rng_state = 0x7007u;
    int compared = 0, differ = 0;
    for (int n = 0; n < 12000; ++n) {
        const int corner = n % 2;
        const double mu1 = corner ? 0.625 : pow(10, -1.3 + 1.3 * uniform());
        const double mu2 =
            corner ? mu1 * pow(10, -10 + uniform()) : mu1 * pow(10, 20 * uniform() - 10);
        const double e1 = corner ? 1000 : pow(10, 2 + 4 * uniform());
        const double e2 = corner ? 1000 : e1 * pow(10, 20 * uniform() - 10);
        const double al = pick(2) ? 0 : PI * (2 * uniform() - 1),
                     be = pick(3) == 0 ? al
                          : pick(2)    ? 0
                                       : PI * (2 * uniform() - 1);
        const int a = corner && pick(2) ? -455 : (int)pick(997) - 498, b = (int)pick(997) - 498;
        const double lm = fmax(fabs(log10(mu1)), fabs(log10(mu2)));
        if (abs(a + b) > 400 || fabs(log10(e1) + (a - b) * log10(2.0)) + 2 * lm >= 290 ||
            fabs(log10(e2) + (a - b) * log10(2.0)) + 2 * lm >= 290)
            continue;
        const double k = ldexp(1, a), m = ldexp(1, b);
        const int rule = 1 + (int)pick(3);
        oc_params p = params(rule, mu1, mu2, e1, e2, al, be), ps = p;
        ps.eps1 = e1 * k / m;
        ps.eps2 = e2 * k / m;
        oc_law L, Ls;
        if (oc_law_init(&L, &p) || oc_law_init(&Ls, &ps)) continue;
        const double N0 = 10, len = fmax(mu1, mu2) * N0 / fmin(e1, e2);
        oc_state s = oc_state_unloaded(0, 0, 0), ss = s;
        double u[2] = {0, 0}, N = N0;
        for (int j = 0; j < 12; ++j) {
            const unsigned kind = pick(5);
            const double d1 = pick(3) ? 2 * uniform() - 1 : 0, d2 = pick(3) ? 2 * uniform() - 1 : 0;
            const double size = len * pow(10, 4 * uniform() - 3);
            if (kind < 3) {
                u[0] += size * d1;
                u[1] += size * d2;
                N = N0 * (0.5 + uniform());
            } else if (kind == 4)
                N = 0;
            const double us[2] = {u[0] * m, u[1] * m};
            oc_step st, sts;
            oc_law_step(&L, &s, u, N, &st);
            oc_law_step(&Ls, &ss, us, N * k, &sts);
            const double o[5] = {st.q[0] * k, st.q[1] * k, st.next.s[0] * m, st.next.s[1] * m,
                                 st.next.energy * (k * m)};
            const double os[5] = {sts.q[0], sts.q[1], sts.next.s[0], sts.next.s[1],
                                  sts.next.energy};
            int sub = 0;
            for (int i = 0; i < 5; ++i) sub |= subnormal(o[i]) || subnormal(os[i]);
            if (sub) break; /* subnormal numbers lose bits: outside the promise */
            ++compared;
            if (memcmp(o, os, sizeof o) != 0) {
                if (++differ <= 3)
                    printf("  units: rule %d mu (%.17g, %.17g) eps (%.17g, %.17g) alpha %.17g beta "
                           "%.17g "
                           "k 2^%d m 2^%d step %d\n",
                           rule, mu1, mu2, e1, e2, al, be, a, b, j);
                break;
            }
            s = st.next;
            ss = sts.next;
        }
    }
    CHECK(differ == 0, "%d of %d paths differ under power-of-two units", differ, compared);
    CHECK(compared > 20000, "only %d steps compared", compared);
}

/* 1 if two steps are the same, bit for bit, in every field a step writes. */
static int same_step(const oc_step *x, const oc_step *y) {
    const double a[] = {x->q[0],      x->q[1],      x->next.u[0], x->next.u[1], x->next.N,
                        x->next.a[0], x->next.a[1], x->next.s[0], x->next.s[1], x->next.energy,
                        x->dgamma,    x->w[0],      x->w[1],      x->inv_wmax};
    const double b[] = {y->q[0],      y->q[1],      y->next.u[0], y->next.u[1], y->next.N,
                        y->next.a[0], y->next.a[1], y->next.s[0], y->next.s[1], y->next.energy,
                        y->dgamma,    y->w[0],      y->w[1],      y->inv_wmax};
    return x->contact == y->contact && memcmp(a, b, sizeof a) == 0;
}

/* oc_law_step_batch is oc_law_step, cell by cell, bit for bit: batches of
 * every size up to 3 OC_BATCH_MAX (whole groups of OC_LANES lanes and not,
 * whole chunks of OC_BATCH_MAX and not),
 * open, sticking and slipping cells mixed in one batch, all three rules,
 * contrasts up to 1e10 (the far solve), tiny and subnormal normal forces,
 * trials whose square leaves the normal range, each cell from the state its
 * previous step committed. */
static void test_batch_is_the_cell_by_cell_step(void) {
    rng_state = 0x5eedu;
    enum { MOST = 3 * OC_BATCH_MAX };
    static oc_state from[MOST];
    static oc_step want[MOST], got[MOST];
    const oc_state *start[MOST];
    static double u[MOST][2], N[MOST];
    long compared = 0, kinds[3] = {0, 0, 0}, laned = 0;
    for (int episode = 0; episode < 400; ++episode) {
        /* drawn one by one: the order of a call's arguments is the compiler's */
        const int rule = 1 + (int)pick(3);
        const double contrast = pick(4) == 0 ? pow(10, 20 * uniform() - 10) : 0.5 + uniform();
        const double mu1 = 0.2 + uniform(), e1 = pow(10, 2 + 4 * uniform());
        const double mu2 = mu1 * (pick(2) ? contrast : 1.0);
        const double e2 = e1 * (pick(2) ? contrast : 1.0);
        const double alpha = PI * (2 * uniform() - 1);
        const double beta = PI * (2 * uniform() - 1);
        const oc_params p = params(rule, mu1, mu2, e1, e2, alpha, beta);
        oc_law L;
        if (oc_law_init(&L, &p) != 0) continue;
        const int n = 1 + (int)pick(pick(4) ? OC_BATCH_MAX : MOST);
        const double scale = pick(6) == 0 ? pow(2, (double)pick(2000) - 1000) : 1.0;
        const double reach = (pick(2) ? 3.0 : 0.3) * fmax(p.mu1, p.mu2) / fmin(p.eps1, p.eps2);
        for (int k = 0; k < n; ++k) {
            from[k] = oc_state_unloaded(0.0, 0.0, 0.0);
            start[k] = &from[k];
        }
        for (int step = 0; step < 6; ++step) {
            for (int k = 0; k < n; ++k) {
                switch (pick(12)) {
                case 0: N[k] = pick(2) ? 0.0 : -1.0; break;        /* open */
                case 1: N[k] = 0x1p-1040 * (1 + uniform()); break; /* subnormal */
                case 2: N[k] = 0x1p-1010 * (1 + uniform()); break; /* tiny */
                default: N[k] = scale * (1 + 19 * uniform());
                }
                const double nk = N[k] > 0 ? N[k] : 1.0;
                const double len = pick(10) == 0 ? 1e6 : reach * (pick(3) ? 1.0 : 0.05);
                u[k][0] = from[k].u[0] + nk * len * (2 * uniform() - 1);
                u[k][1] = from[k].u[1] + nk * len * (2 * uniform() - 1);
            }
            memset(want, 0, sizeof want);
            memset(got, 0, sizeof got);
            for (int k = 0; k < n; ++k) oc_law_step(&L, start[k], u[k], N[k], &want[k]);
            oc_law_step_batch(&L, start, (const double(*)[2])u, N, got, n);
            int slipping = 0;
            for (int k = 0; k < n; ++k) {
                CHECK(same_step(&got[k], &want[k]),
                      "episode %d step %d cell %d of %d (rule %d): q (%.17g, %.17g) vs "
                      "(%.17g, %.17g), contact %d vs %d",
                      episode, step, k, n, rule, got[k].q[0], got[k].q[1], want[k].q[0],
                      want[k].q[1], got[k].contact, want[k].contact);
                ++kinds[want[k].contact];
                slipping += want[k].contact == OC_SLIP;
                ++compared;
            }
            laned += slipping >= 2 && rule != OC_RULE_EQ20;
            for (int k = 0; k < n; ++k)
                if (oc_step_is_finite(&want[k])) from[k] = want[k].next;
        }
    }
    CHECK(kinds[OC_OPEN] > 1000 && kinds[OC_STICK] > 1000 && kinds[OC_SLIP] > 1000 && laned > 500,
          "open %ld, stick %ld, slip %ld cells; %ld batches with slipping lanes", kinds[OC_OPEN],
          kinds[OC_STICK], kinds[OC_SLIP], laned);
    printf("batch: %ld cells bit for bit (open %ld, stick %ld, slip %ld), %ld batches in lanes\n",
           compared, kinds[OC_OPEN], kinds[OC_STICK], kinds[OC_SLIP], laned);
}

int main(void) {
    test_params_check();
    test_tensors();
    test_stick_and_open();
    test_return_onto_yield_surface();
    test_isotropic_radial_return();
    test_step_size_independence();
    test_energy_balance();
    test_held_inputs_stick();
    test_jacobian();
    test_finite_everywhere();
    test_held_inputs_anisotropic();
    test_far_trial();
    test_norm2();
    test_model_table_and_errors();
    test_model_state();
    test_accuracy_aligned_axes();
    test_huge_trial();
    test_subnormal_normal_force();
    test_tiny_normal_force();
    test_eq20_strong_friction_contrast();
    test_power_of_two_units();
    test_batch_is_the_cell_by_cell_step();
    return oc_report();
}
