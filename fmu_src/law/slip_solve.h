/*
 * The implicit rules' slip solve (contact_law.c, section 3), written once
 * over a lane type (law/lanes.h) and included twice by contact_law.c: with
 * OC_SLIP_LANES 1 for one cell (double: the functions dgamma1_*, the solve
 * of oc_law_step) and with OC_SLIP_LANES 2 for two cells in a vector's
 * lanes (v2d: dgamma2_*), so that a batch of cells (oc_law_step_batch)
 * steps two cells by one vector instruction, each lane its cell's own
 * arithmetic bit for bit.  Where the iteration branches, both sides are
 * formed and each lane takes its own (sel).  No include guard: a template.
 *
 * It solves sum_i a_i^2 / (1 + y s_i)^2 = rho^2 for y > 0, given |a| = 1 >
 * rho and s_i = sigma_i / sigma_ref in (0, 1] (so y = dgamma sigma_ref is
 * dimensionless).  k(y) = rho / |p(y)| - 1 is a power mean of exponent -2
 * of the affine 1 + y s_i, hence concave and increasing: Newton from the
 * left of the root climbs monotonically to it, and from the right it lands
 * on the left in one step.  The iteration works on g_i = W p_i with W =
 * w_0 w_1, w_i = 1 + y s_i, so that an evaluation costs one square root
 * and one division; its products (up to W^7) stay finite while W < 1e40,
 * which the caller guarantees (W <= kappa / rho^2 at the root: the fast
 * solve's gate).
 *
 * dgammaN_start (no square root, so that it runs beside the caller's):
 * from the trial a_raw = (ar0, ar1), |a_raw|^2 = sq, |a_raw| = n_tr, and N
 * (N_), the direction a = a_raw / n_tr, rho = N / n_tr and the start x.
 * Its divisions depend only on the trial, not on its square root: they run
 * beside it.  Moments are taken over a_i^2 / |a|^2.  The start is the
 * root's series in the Newton step h from y = 0, to third order (error
 * O(h^4), exact when s_1 = s_2), from the moments M_j = sum_i a_i^2 s_i^j:
 * k(0) = rho - 1, k' = rho M1, k''/(2 k') = A2 = 3 (M1^2 - M2) / (2 M1),
 * k'''/(6 k') = A3 = (15 M1^3 - 27 M1 M2 + 12 M3) / (6 M1).  Far from the
 * root the series need not converge: Newton's step then (x > 0 && x < 4 h
 * ? x : h).
 *
 * dgammaN_step: one evaluation at the iterate x, into *E; moves the iterate
 * and returns the mask of the lanes where it was the last (a lane whose
 * evaluation ends it unmoved has dx = 0).  In u_i = W s_i / w_i, k' = rho
 * C / m^3 with C = sum g_i^2 u_i and k'' / k' = -3 (m^2 D2 - C^2) / (W m^2
 * C), D2 = sum g_i^2 u_i^2.  Left of the root (res > 0): Halley in one
 * division, dx = -(k / k') / (1 - k k'' / (2 k'^2)): k < 0 and k'' <= 0
 * make the bracket < 1, a step longer than Newton's; its error is the cube
 * of the step, so that a step below 5e-6 y is the last (remainder below
 * (dy/y)^3 ~ 1e-16), typically one evaluation after the start.  Where the
 * bracket falls below 1/2 (far from the root) the step is held at twice
 * Newton's: overshooting the root is harmless (Newton from the right lands
 * left of it).  Right of it: Newton.
 *
 * dgammaN_root: the root y = x + dx of the evaluation *E, and p there, to
 * second order: p_i(x + dx) = p_i / (1 + t_i) with t_i = s_i dx / w_i =
 * u_i dx / W.  |p| = rho to rounding then, so 1 / |p| is one Newton step of
 * the inverse square root from 1 / rho: no square root, no division.
 *
 * dgammaN_weights: what the tangent needs of the root y (oc_step.w,
 * inv_wmax): w_i = 1 + y s_i as w_i / max w, and 1 / max w.
 *
 * slip_lanes (the inclusion whose lanes are the batch's, OC_LANE_WIDTH):
 * solves and finishes n <= OC_LANES slipping cells of a batch, a lane
 * each, the groups' evaluations in turn (independent chains of square
 * roots and divisions, which the processor overlaps).  An odd cell out
 * fills every lane of its group.  A lane done goes on being evaluated
 * (harmlessly: nothing traps) until its group is; its results are those of
 * the evaluation that ended it.  Needs slip_cell and slip_cell_finish.
 */
#if OC_SLIP_LANES == 1
#define LANE_T double
#define LANE_M int
#define LANE(op) lane1_##op
#define DG(name) dgamma1_##name
#elif OC_SLIP_LANES == 2
#define LANE_T v2d
#define LANE_M v2m
#define LANE(op) lane2_##op
#define DG(name) dgamma2_##name
#else
#error "define OC_SLIP_LANES as 1 or 2 before including law/slip_solve.h"
#endif

typedef struct {
    LANE_T a0, a1;       /* the trial's direction a_raw / n_tr */
    LANE_T rho, inv_rho; /* N / n_tr and its inverse */
    LANE_T x;            /* the iterate y */
    LANE_T it;           /* evaluations made */
} DG(solve);

typedef struct {
    LANE_T x, dx, W, g0, g1, u0, u1;
} DG(eval);

static OC_ALWAYS_INLINE void DG(start)(LANE_T ar0, LANE_T ar1, LANE_T sq, LANE_T n_tr, LANE_T N_,
                                       const double sh[2], DG(solve) * S) {
    const LANE_T A0 = ar0 * ar0, A1 = ar1 * ar1;
    const double s0 = sh[0], s1 = sh[1];
    const LANE_T R1 = A0 * s0 + A1 * s1;
    const LANE_T inv_sq = 1.0 / sq, inv_R1 = 1.0 / R1, inv_N = 1.0 / N_;
    const LANE_T inv_ntr = n_tr * inv_sq, rho = N_ * inv_ntr, inv_rho = n_tr * inv_N;
    S->a0 = ar0 * inv_ntr;
    S->a1 = ar1 * inv_ntr;
    S->rho = rho;
    S->inv_rho = inv_rho;
    const LANE_T M1 = R1 * inv_sq, M2 = (A0 * s0 * s0 + A1 * s1 * s1) * inv_sq;
    const LANE_T M3 = (A0 * s0 * s0 * s0 + A1 * s1 * s1 * s1) * inv_sq;
    const LANE_T inv_M1 = sq * inv_R1;
    const LANE_T h = (1.0 - rho) * inv_rho * inv_M1;
    const LANE_T A2 = 1.5 * (M1 * M1 - M2) * inv_M1;
    const LANE_T A3 = (15.0 * M1 * M1 * M1 - 27.0 * M1 * M2 + 12.0 * M3) * inv_M1 * (1.0 / 6.0);
    const LANE_T x = h * (1.0 - A2 * h + (2.0 * A2 * A2 - A3) * h * h);
    S->x = LANE(sel_usual)((LANE_M)(x < 4.0 * h), LANE(sel_usual)((LANE_M)(x > 0.0), x, h), h);
    S->it = LANE(splat)(0.0);
}

static OC_ALWAYS_INLINE LANE_M DG(step)(DG(solve) * S, const double sh[2], DG(eval) * E) {
    const LANE_T x = S->x, rho = S->rho, inv_rho = S->inv_rho;
    const LANE_T w0x = 1.0 + x * sh[0], w1x = 1.0 + x * sh[1], W = w0x * w1x;
    const LANE_T g0 = S->a0 * w1x, g1 = S->a1 * w0x;
    const LANE_T G0 = g0 * g0, G1 = g1 * g1, m2 = G0 + G1, m = LANE(sqrt)(m2);
    const LANE_T res = m - rho * W;
    const LANE_T u0 = sh[0] * w1x, u1 = sh[1] * w0x;
    const LANE_M far = (LANE_M)(LANE(abs)(res) > 2 * DBL_EPSILON * rho * W);
    const LANE_M more = (LANE_M)(S->it < 100.0);
    const LANE_M left = (LANE_M)(res > 0.0);
    const LANE_T C = G0 * u0 + G1 * u1;
    const LANE_T D2 = G0 * u0 * u0 + G1 * u1 * u1, nC2 = rho * W * C * C;
    const LANE_T num = LANE(sel)(left, res * m2 * W * C, res * m2 * inv_rho);
    const LANE_T den =
        LANE(sel)(left, LANE(max)(nC2 - 1.5 * res * (m2 * D2 - C * C), 0.5 * nC2), C);
    const LANE_T zero = LANE(splat)(0.0);
    const LANE_T dx = LANE(sel)(more, LANE(sel)(far, num / den, zero), zero);
    const LANE_M small = (LANE_M)(LANE(abs)(dx) <= LANE(sel)(left, 5e-6 * x, 1e-8 * x));
    E->x = x;
    E->dx = dx;
    E->W = W;
    E->g0 = g0;
    E->g1 = g1;
    E->u0 = u0;
    E->u1 = u1;
    S->x = LANE(max)(x + dx, zero);
    S->it = S->it + 1.0;
    return LANE(not )(far & more) | small;
}

static OC_ALWAYS_INLINE void DG(root)(const DG(solve) * S, const DG(eval) * E, LANE_T *p0,
                                      LANE_T *p1, LANE_T *inv_norm, LANE_T *root) {
    const LANE_T invW = 1.0 / E->W, inv_rho = S->inv_rho;
    const LANE_T t0 = E->u0 * E->dx * invW, t1 = E->u1 * E->dx * invW;
    *p0 = E->g0 * invW * (1.0 - t0 + t0 * t0);
    *p1 = E->g1 * invW * (1.0 - t1 + t1 * t1);
    const LANE_T pp = *p0 * *p0 + *p1 * *p1;
    *inv_norm = inv_rho * (1.5 - 0.5 * pp * inv_rho * inv_rho);
    *root = E->x + E->dx;
}

static OC_ALWAYS_INLINE void DG(weights)(LANE_T y, const double sh[2], LANE_T *w0, LANE_T *w1,
                                         LANE_T *inv_wmax) {
    const LANE_T v0 = 1.0 + y * sh[0], v1 = 1.0 + y * sh[1], wmax = LANE(max)(v0, v1);
    *w0 = v0 / wmax;
    *w1 = v1 / wmax;
    *inv_wmax = 1.0 / wmax;
}

#if OC_SLIP_LANES == OC_LANE_WIDTH
/* A group of OC_SLIP_LANES slipping cells of a batch, solved together. */
typedef struct {
    DG(solve) s;
    int done[OC_SLIP_LANES];
    double p0[OC_SLIP_LANES], p1[OC_SLIP_LANES], inv_norm[OC_SLIP_LANES], root[OC_SLIP_LANES];
} DG(group);

/* One evaluation of a group's lanes: 1 when every lane is done. */
static OC_ALWAYS_INLINE int DG(group_step)(DG(group) * S, const double sh[2]) {
    DG(eval) E;
    const LANE_M end = DG(step)(&S->s, sh, &E);
    LANE_T p0, p1, inv_norm, root;
    DG(root)(&S->s, &E, &p0, &p1, &inv_norm, &root);
    for (int l = 0; l < OC_SLIP_LANES; ++l)
        if (!S->done[l] && LANE(mask_get)(end, l)) {
            S->done[l] = 1;
            S->p0[l] = LANE(get)(p0, l);
            S->p1[l] = LANE(get)(p1, l);
            S->inv_norm[l] = LANE(get)(inv_norm, l);
            S->root[l] = LANE(get)(root, l);
        }
    return S->done[0] && S->done[OC_SLIP_LANES - 1];
}

static void slip_lanes(const oc_law *L, const slip_cell c[], int n) {
    enum { W = OC_SLIP_LANES, GROUPS = (OC_LANES + W - 1) / W };
    const int groups = (n + W - 1) / W;
    DG(group) S[GROUPS];
    for (int v = 0; v < groups; ++v) {
        const slip_cell *c0 = &c[W * v], *c1 = W * v + 1 < n ? &c[W * v + 1] : c0;
        const LANE_T sc = LANE(make)(c0->sc, c1->sc);
        const LANE_T ar0 = LANE(make)(c0->r->a[0], c1->r->a[0]) * sc;
        const LANE_T ar1 = LANE(make)(c0->r->a[1], c1->r->a[1]) * sc;
        const LANE_T n_tr = LANE(make)(c0->n_tr, c1->n_tr) * sc;
        const LANE_T N = LANE(make)(c0->r->out->next.N, c1->r->out->next.N) * sc;
        DG(start)(ar0, ar1, ar0 * ar0 + ar1 * ar1, n_tr, N, L->sig_hat, &S[v].s);
        for (int l = 0; l < W; ++l) S[v].done[l] = 0;
    }
    for (int left = groups; left > 0;)
        for (int v = 0; v < groups; ++v)
            if (!(S[v].done[0] && S[v].done[W - 1]) && DG(group_step)(&S[v], L->sig_hat)) --left;
    for (int v = 0; v < groups; ++v) {
        const LANE_T y = LANE(make)(S[v].root[0], S[v].root[W - 1]);
        LANE_T w0, w1, inv_wmax;
        DG(weights)(y, L->sig_hat, &w0, &w1, &inv_wmax);
        for (int l = 0; l < W && W * v + l < n; ++l) {
            const double p[2] = {S[v].p0[l], S[v].p1[l]};
            slip_cell_finish(L, &c[W * v + l], LANE(get)(y, l), p, S[v].inv_norm[l],
                             LANE(get)(w0, l), LANE(get)(w1, l), LANE(get)(inv_wmax, l));
        }
    }
}
#endif

#undef LANE_T
#undef LANE_M
#undef LANE
#undef DG
#undef OC_SLIP_LANES
