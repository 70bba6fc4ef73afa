/*
 * offset_lanes.h: root_dd's common path on VN requests at once, one a lane
 * (offset.c, above roots4_avx2, says what it computes and why), written
 * once for both widths: offset.c includes it for AVX2's four lanes
 * (roots4_avx2) and for AVX-512F's eight (roots8_512), each time with
 * these defined:
 *  - VN, the lanes; VD, a vector of VN doubles (GCC's vector extension:
 *    its + - * / are the lanes' own operations); VM, a mask of VN lanes;
 *  - VF(name): the name of that width's helper (v4_name, v8_name), of
 *    which ld, st, set1, sqrt, abs, min, max, sel (m ? b : a), the
 *    comparisons lt, le, gt, eq, ne, the masks' and, or, xor, andnot (~a
 *    & b), bits (lane k in bit k), coord (the lanes whose request's
 *    coordinate is y), rows and pairs (the transposes) are offset.c's;
 *  - V_ALL(E): E(0), E(1), ..., E(VN - 1), a helper's VN arguments;
 *  - VATTR, the helpers' attributes, VTARGET the target, VROOTS the
 *    function's name.
 * Each lane's operations are the scalar forms' in their order, so each
 * root and point is the scalar one bit for bit (tests/test_area_offset.c,
 * test_roots_batch, both widths).
 */

VATTR VD VF(two_sum)(VD a, VD b, VD *e)
{
    VD s = a + b, bb = s - a;
    *e = (a - (s - bb)) + (b - bb);
    return s;
}

/* dd_two_prod's fma form: a b - p by one rounding */
VATTR VD VF(two_prod)(VD a, VD b, VD *e)
{
    VD p = a * b;
    *e = VF(fmsub)(a, b, p);
    return p;
}

/* A batch's curves, each lane one request's, loaded and transposed once:
 * the base cubic's coefficients (b[k]: x's t^k; b[4 + k]: y's), the map
 * (m[k]), its row for the request's coordinate (r0, r1, r2 = m[c],
 * m[2 + c], m[4 + c]), d, and fx's double-double form (the pairs of
 * dc[k][h], du[k][0], du[2][1] as x's and y's) */
typedef struct VF(curves) {
    VD b[8], m[4], r0, r1, r2, d;
    VD dch[4][2], dcl[4][2], duh[3][2], du2l[2];
    int axes; /* 1: r0 is 0 in every lane, 2: r1 is (and r0 in none), else 0 */
} VF(curves);

/* eval_dd in each lane: f, df and dn at t (its blends: the sums of the
 * row's products that eval_dd takes where r0 or r1 is 0, and the two).
 * Where the map keeps the axes in every lane (C->axes, as a scene's
 * placement does: r0 0 on y's rows, r1 on x's), the one product eval_dd
 * takes there alone, without the other coordinate's base and the blends:
 * the same value in each lane. */
VATTR void VF(eval_dd)(const VF(curves) *C, VD t, VD tgt, VD *f, VD *df, VD *dn)
{
    const VD *b = C->b, zero = VF(set1)(0.0);
    VD s;
    if (C->axes == 1) {
        s = C->r1 * (b[4] + t * (b[5] + t * (b[6] + t * b[7])));
    } else if (C->axes == 2) {
        s = C->r0 * (b[0] + t * (b[1] + t * (b[2] + t * b[3])));
    } else {
        VD bx = b[0] + t * (b[1] + t * (b[2] + t * b[3]));
        VD by = b[4] + t * (b[5] + t * (b[6] + t * b[7]));
        VD s0 = C->r0 * bx, s1 = C->r1 * by;
        s = VF(sel)(VF(eq)(C->r0, zero), VF(sel)(VF(eq)(C->r1, zero), s0 + s1, s0), s1);
    }
    VD base0 = s + C->r2;
    VD ux = b[1] + t * (2 * b[2] + 3 * t * b[3]), uy = b[5] + t * (2 * b[6] + 3 * t * b[7]);
    VD vx = 2 * b[2] + 6 * t * b[3], vy = 2 * b[6] + 6 * t * b[7];
    VD c = ux * vy - uy * vx, L2 = ux * ux + uy * uy, w = C->r1 * ux - C->r0 * uy;
    VD il = 1 / VF(sqrt)(L2), nrm = C->d * w * il;
    *df = (C->r0 * ux + C->r1 * uy) * (1 - C->d * c * (il * il * il));
    *dn = VF(abs)(nrm);
    *f = (base0 - tgt) + nrm;
}

/* dd_point_parts in each lane: p[k][0] x's, p[k][1] y's (dd_v2 p[k]'s
 * lanes), dp likewise */
VATTR void VF(point_parts)(const VF(curves) *C, VD t, VD p[4][2], VD dp[2][2])
{
    /* dd_normal_pt: B' as hi (uh) + lo (ul) */
    VD uh[2], ul[2], e, e2;
    for (int c = 0; c < 2; c++) {
        VD q = VF(two_prod)(C->duh[2][c], t, &e);
        VD sh = VF(two_sum)(q, C->duh[1][c], &e2), sl = e2 + (e + C->du2l[c] * t);
        q = VF(two_prod)(sh, t, &e);
        VD s2 = VF(two_sum)(q, C->duh[0][c], &e2);
        uh[c] = VF(two_sum)(s2, e2 + (e + sl * t), &ul[c]);
    }
    VD e1, e3, e4, p1 = VF(two_prod)(uh[0], uh[0], &e1);
    VD p2 = VF(two_prod)(uh[1], uh[1], &e4), s = VF(two_sum)(p1, p2, &e3);
    VD ql = e3 + e1 + e4 + 2 * (uh[0] * ul[0] + uh[1] * ul[1]);
    VD qh = VF(two_sum)(s, ql, &ql);
    VD lh = VF(sqrt)(qh), il = 1 / lh, el, pl = VF(two_prod)(lh, lh, &el);
    VD ll = (((qh - pl) - el) + ql) * (0.5 * il);
    VD fh[2], fl[2];
    for (int c = 0; c < 2; c++) { /* w for row c: r0 = m[c], r1 = m[2 + c] */
        VD r0 = C->m[c], r1 = C->m[2 + c], ea, eb, es, wl2;
        VD a = VF(two_prod)(r1, uh[0], &ea), b = VF(two_prod)(-r0, uh[1], &eb);
        VD ws = VF(two_sum)(a, b, &es), wl = es + ea + eb + (r1 * ul[0] - r0 * ul[1]);
        VD wh = VF(two_sum)(ws, wl, &wl2), ef;
        fh[c] = wh * il;
        VD pf = VF(two_prod)(fh[c], lh, &ef);
        fl[c] = (((wh - pf) - ef) + (wl2 - fh[c] * ll)) * il;
    }
    for (int c = 0; c < 2; c++) {
        VD eh;
        p[1][c] = VF(two_prod)(C->d, fh[c], &eh);
        p[3][c] = eh + C->d * fl[c];
    }
    /* the derivatives (dd_normal_pt's dp) */
    VD v[2] = {C->duh[1][0] + (6 * t) * C->b[3], C->duh[1][1] + (6 * t) * C->b[7]};
    VD cc = uh[0] * v[1] - uh[1] * v[0], cp = 6 * (uh[0] * C->b[7] - uh[1] * C->b[3]);
    VD dot = uh[0] * v[0] + uh[1] * v[1];
    VD il3 = il * il * il, g = 1 - C->d * cc * il3;
    VD q[2] = {uh[0] * g, uh[1] * g};
    VD gp = -C->d * il3 * (cp - 3 * cc * dot * (il * il));
    VD rv[2] = {v[0] * g + uh[0] * gp, v[1] * g + uh[1] * gp};
    for (int c = 0; c < 2; c++) {
        dp[0][c] = C->m[c] * q[0] + C->m[2 + c] * q[1];
        dp[1][c] = C->m[c] * rv[0] + C->m[2 + c] * rv[1];
    }
    /* dd_base */
    for (int c = 0; c < 2; c++) {
        VD sh = C->dch[3][c], sl = C->dcl[3][c];
        for (int k = 2; k >= 0; k--) {
            VD q2 = VF(two_prod)(sh, t, &e);
            sh = VF(two_sum)(q2, C->dch[k][c], &e2);
            sl = e2 + (e + (sl * t + C->dcl[k][c]));
        }
        p[0][c] = sh, p[2][c] = sl;
    }
}

/* lane k of the parts as dd_point_parts gives them (for a scalar
 * continuation) */
static inline void VF(lane_parts)(const double pv[4][2][VN], const double dpv[2][2][VN], int k,
                                  dd_v2 p[4], dd_v2 dp[2])
{
    for (int i = 0; i < 4; i++)
        p[i] = (dd_v2){pv[i][0][k], pv[i][1][k]};
    for (int i = 0; i < 2; i++)
        dp[i] = (dd_v2){dpv[i][0][k], dpv[i][1][k]};
}

/* The requests r[0..n) (n 2 to VN, each root_dd's common start; lanes n
 * and on repeat r[0], their results dropped) */
static __attribute__((noinline, target(VTARGET))) void VROOTS(aa__offset_rootq *const *r, int n)
{
#define V_R(k) (k) < n ? r[k] : r[0]
#define V_O(k) R[k]->oc
#define V_X(k) R[k]->fx
    const aa__offset_rootq *R[VN] = {V_ALL(V_R)};
    const aa_offset_curve *o[VN] = {V_ALL(V_O)};
    const aa__offset_fix *x[VN] = {V_ALL(V_X)};
    VF(curves) C;
#define V_B0(k) o[k]->b
#define V_B4(k) o[k]->b + 4
#define V_M(k) o[k]->m
    VF(rows)(V_ALL(V_B0), C.b);
    VF(rows)(V_ALL(V_B4), C.b + 4);
    VF(rows)(V_ALL(V_M), C.m);
    VM cm = VF(coord)(R);
    C.r0 = VF(sel)(cm, C.m[0], C.m[1]), C.r1 = VF(sel)(cm, C.m[2], C.m[3]);
    {
        const int full = (1 << VN) - 1; /* lanes n and on repeat r[0] */
        VD z = VF(set1)(0.0);
        int z0 = VF(bits)(VF(eq)(C.r0, z)), z1 = VF(bits)(VF(eq)(C.r1, z));
        C.axes = z0 == full ? 1 : z1 == full && !z0 ? 2 : 0;
    }
#define V_R2(k) o[k]->m[4 + R[k]->coord]
#define V_D(k) o[k]->d
    C.r2 = VF(set)(V_ALL(V_R2));
    C.d = VF(set)(V_ALL(V_D));
    for (int k = 0; k < 4; k++)
        for (int h = 0; h < 2; h++) {
            VD *dst = h ? C.dcl[k] : C.dch[k];
#define V_DC(i) x[i]->dc[k][h]
            VF(pairs)(V_ALL(V_DC), &dst[0], &dst[1]);
        }
    for (int k = 0; k < 3; k++) {
#define V_DU(i) x[i]->du[k][0]
        VF(pairs)(V_ALL(V_DU), &C.duh[k][0], &C.duh[k][1]);
    }
#define V_DU2(i) x[i]->du[2][1]
    VF(pairs)(V_ALL(V_DU2), &C.du2l[0], &C.du2l[1]);
#define V_TGT(k) R[k]->target
#define V_TA(k) R[k]->ta
#define V_TB(k) R[k]->tb
#define V_GUESS(k) R[k]->guess
#define V_FA(k) R[k]->fa
#define V_SIZE(k) x[k]->dsize[R[k]->coord]
    VD tgt = VF(set)(V_ALL(V_TGT)), ta = VF(set)(V_ALL(V_TA)), tb = VF(set)(V_ALL(V_TB));
    VD t = VF(set)(V_ALL(V_GUESS));
    VD zero = VF(set1)(0.0), one = VF(set1)(1.0), half = VF(set1)(0.5);
    VM neg = VF(lt)(VF(set)(V_ALL(V_FA)), zero);
    VD size = VF(set)(V_ALL(V_SIZE)) + VF(abs)(tgt);
#undef V_R
#undef V_O
#undef V_X
#undef V_B0
#undef V_B4
#undef V_M
#undef V_R2
#undef V_D
#undef V_DC
#undef V_DU
#undef V_DU2
#undef V_TGT
#undef V_TA
#undef V_TB
#undef V_GUESS
#undef V_FA
#undef V_SIZE
    /* solve_step at the guess: its stops (the value within rounding of
     * the target, the bracket two adjacent doubles, a step within
     * DD_D_STEP, clamped to the bracket) */
    VD f, df, dn;
    VF(eval_dd)(&C, t, tgt, &f, &df, &dn);
    VM sa = VF(le)(VF(abs)(f), 2 * DBL_EPSILON * (size + dn));
    VM side = VF(xor)(VF(lt)(f, zero), neg); /* (f < 0) != neg: b moves */
    VD a = VF(sel)(side, t, ta), b = VF(sel)(side, tb, t), mid = half * (a + b);
    VM sb = VF(or)(VF(eq)(mid, a), VF(eq)(mid, b));
    VM dfok = VF(and)(VF(ne)(df, zero), VF(lt)(VF(abs)(df), VF(set1)(INFINITY)));
    VD next = VF(sel)(dfok, mid, t - f / df);
    VD sc = VF(max)(VF(abs)(t), one);
    VM sn = VF(le)(VF(abs)(next - t), DD_D_STEP * sc);
    VD cl = VF(min)(VF(max)(next, VF(min)(a, b)), VF(max)(b, a));
    VM skeep = VF(or)(sa, sb), s1 = VF(or)(skeep, sn);
    int all = (1 << n) - 1;
    int go = VF(bits)(s1) & all;
    VD tn = VF(sel)(skeep, cl, t);
    if (go != all) {
        /* the lanes on: solve_step's next point (a Newton step inside
         * the bracket and at most half the step before, the bracket's
         * width at first; else b, unseen, where the step passes it; else
         * the bracket's middle), then its second step there, as root_dd
         * takes it; the lanes that stop at neither go on alone
         * (root_d_more2_fma) */
        VM ab = VF(lt)(a, b);
        VM inside = VF(or)(VF(and)(ab, VF(and)(VF(gt)(next, a), VF(lt)(next, b))),
                           VF(andnot)(ab, VF(and)(VF(lt)(next, a), VF(gt)(next, b))));
        VM past = VF(or)(VF(and)(ab, VF(le)(b, next)), VF(andnot)(ab, VF(le)(next, b)));
        VM jump = VF(andnot)(inside, VF(andnot)(side, past)), seen = VF(or)(side, jump);
        VM newton = VF(andnot)(VF(gt)(VF(abs)(next - t), half * VF(abs)(tb - ta)), inside);
        VD t2 = VF(sel)(jump, VF(sel)(newton, mid, next), b), prev = VF(abs)(t2 - t);
        VF(eval_dd)(&C, t2, tgt, &f, &df, &dn);
        sa = VF(le)(VF(abs)(f), 2 * DBL_EPSILON * (size + dn));
        VM side2 = VF(xor)(VF(lt)(f, zero), neg);
        VD a2 = VF(sel)(side2, t2, a), b2 = VF(sel)(side2, b, t2);
        mid = half * (a2 + b2);
        sb = VF(or)(VF(eq)(mid, a2), VF(eq)(mid, b2));
        dfok = VF(and)(VF(ne)(df, zero), VF(lt)(VF(abs)(df), VF(set1)(INFINITY)));
        next = VF(sel)(dfok, mid, t2 - f / df);
        sc = VF(max)(VF(abs)(t2), one);
        sn = VF(le)(VF(abs)(next - t2), DD_D_STEP * sc);
        cl = VF(min)(VF(max)(next, VF(min)(a2, b2)), VF(max)(b2, a2));
        skeep = VF(or)(sa, sb);
        tn = VF(sel)(s1, VF(sel)(skeep, cl, t2), tn);
        int go2 = VF(bits)(VF(or)(skeep, sn)) & all & ~go;
        if ((go | go2) != all) {
            double fv[VN], dfv[VN], dnv[VN], av[VN], bv[VN], tv2[VN], pv2[VN];
            int sv = VF(bits)(seen);
            VF(st)(fv, f), VF(st)(dfv, df), VF(st)(dnv, dn), VF(st)(av, a), VF(st)(bv, b);
            VF(st)(tv2, t2), VF(st)(pv2, prev);
            for (int k = 0; k < n; k++) {
                if ((go | go2) >> k & 1)
                    continue;
                aa__offset_rootq *q = r[k];
                int ng = q->fa < 0, unseen = !(sv >> k & 1);
                double size1 = q->fx->dsize[q->coord] + fabs(q->target);
                double t3 = tv2[k], a3 = av[k], b3 = bv[k], prev3 = pv2[k], last;
                solve_step(fv[k], dfv[k], dnv[k], size1, DD_D_STEP, ng, &t3, &a3, &b3, &prev3,
                           &unseen, &last);
                q->t = root_d_more2_fma(q->oc, q->fx, q->coord, q->ta, q->tb, a3, b3, ng,
                                        q->target, t3, prev3, unseen, size1, q->xy, rq_other(q));
            }
        }
        go |= go2;
        if (!go)
            return;
    }
    t = tn;
    /* dd_step at t: its stops (the value 0, the bracket two adjacent
     * doubles, the step rounding to t, the step the last) */
    VD p[4][2], dp[2][2];
    VF(point_parts)(&C, t, p, dp);
    VD P[4], D1 = VF(sel)(cm, dp[0][0], dp[0][1]), D2 = VF(sel)(cm, dp[1][0], dp[1][1]);
    for (int i = 0; i < 4; i++)
        P[i] = VF(sel)(cm, p[i][0], p[i][1]);
    f = ((P[0] - tgt) + P[1]) + (P[2] + P[3]);
    VM za = VF(eq)(f, zero);
    side = VF(xor)(VF(lt)(f, zero), neg);
    VD la = VF(sel)(side, t, ta), lb = VF(sel)(side, tb, t);
    mid = half * (la + lb);
    VM zb = VF(or)(VF(eq)(mid, la), VF(eq)(mid, lb)), zkeep = VF(or)(za, zb);
    dfok = VF(and)(VF(ne)(D1, zero), VF(lt)(VF(abs)(D1), VF(set1)(INFINITY)));
    VD idf = 1 / D1, h2 = -f * idf, c2 = half * D2 * idf;
    VD ch = c2 * h2;
    VD step = h2 - ch * h2;
    next = t + step;
    VM zd = VF(eq)(next, t);
    VM inside = VF(or)(VF(and)(VF(lt)(la, lb), VF(and)(VF(gt)(next, la), VF(lt)(next, lb))),
                       VF(andnot)(VF(lt)(la, lb), VF(and)(VF(lt)(next, la), VF(gt)(next, lb))));
    sc = VF(max)(VF(abs)(t), one);
    VM ze = VF(and)(VF(and)(inside, VF(le)(VF(abs)(h2), VF(set1)(1e-7))),
                    VF(le)(2 * ch * ch * VF(abs)(h2), DD_EST * sc));
    ze = VF(andnot)(VF(or)(zkeep, zd), VF(and)(dfok, ze));
    VM stop = VF(or)(zkeep, VF(and)(dfok, VF(or)(zd, ze)));
    int done = VF(bits)(stop) & go;
    VD hv = VF(sel)(ze, zero, next - t), hxv = VF(sel)(zkeep, step, zero);
    VD tv = VF(sel)(ze, t, next);
    /* dd_out: the sums in double, x, y and the other coordinate's (lane
     * 1 - coord) */
    VD lo[2], Q[4], So = VF(sel)(cm, dp[0][1], dp[0][0]);
    VD S2o = VF(sel)(cm, dp[1][1], dp[1][0]);
    for (int c = 0; c < 2; c++)
        lo[c] = p[2][c] + (p[3][c] + hv * (dp[0][c] + half * dp[1][c] * hv));
    for (int i = 0; i < 4; i++)
        Q[i] = VF(sel)(cm, p[i][1], p[i][0]);
    VD loo = Q[2] + (Q[3] + hxv * (So + half * S2o * hxv));
    double pv[4][2][VN], dpv[2][2][VN], lov[2][VN], qv[2][VN], loov[VN], tt[VN];
    for (int i = 0; i < 2; i++)
        for (int c = 0; c < 2; c++)
            VF(st)(pv[i][c], p[i][c]);
    for (int c = 0; c < 2; c++)
        VF(st)(lov[c], lo[c]);
    VF(st)(qv[0], Q[0]), VF(st)(qv[1], Q[1]);
    VF(st)(loov, loo), VF(st)(tt, tv);
    for (int k = 0; k < n; k++) {
        if (!(done >> k & 1))
            continue;
        aa__offset_rootq *q = r[k];
        if (q->xy) {
            q->xy[0] = ((long double)pv[0][0][k] + pv[1][0][k]) + lov[0][k];
            q->xy[1] = ((long double)pv[0][1][k] + pv[1][1][k]) + lov[1][k];
        }
        if (rq_other(q))
            *q->other = ((long double)qv[0][k] + qv[1][k]) + loov[k];
        q->t = tt[k];
    }
    if (done == go)
        return;
    /* the lanes on: root_dd_loop's next steps (root_dd_more_fma) from
     * dd_step at t again in the lane, on its parts */
    double t0[VN];
    for (int i = 2; i < 4; i++)
        for (int c = 0; c < 2; c++)
            VF(st)(pv[i][c], p[i][c]);
    for (int i = 0; i < 2; i++)
        for (int c = 0; c < 2; c++)
            VF(st)(dpv[i][c], dp[i][c]);
    VF(st)(t0, t);
    for (int k = 0; k < n; k++) {
        if (!(go >> k & 1) || done >> k & 1)
            continue;
        aa__offset_rootq *q = r[k];
        dd_v2 pk[4], dpk[2];
        VF(lane_parts)(pv, dpv, k, pk, dpk);
        int ng = q->fa < 0;
        double t1 = t0[k], la1 = q->ta, lb1 = q->tb, h = 0.0, hx = 0.0;
        dd_step(pk, dpk, (dd_v2){q->target, q->target}, q->coord, ng, &t1, &la1, &lb1, &h, &hx);
        q->t = root_dd_more_fma(q->oc, q->fx, q->coord, q->target, ng, t1, la1, lb1, q->xy,
                                rq_other(q));
    }
}
