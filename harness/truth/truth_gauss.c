/*
 * truth_gauss.c: the reference under the Gaussian by one fixed rule on
 * panels shared by the rows (truth.c's opening comment, "The Gaussian",
 * describes the method).  A pixel the rule declines goes to QAG (truth.c).
 */
#include "truth_internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_integration.h>

#ifdef _OPENMP
#include <omp.h>
#endif

typedef struct probe {
    double x[32];
    int n;
} probe;

static double probe_record(double x, void *params)
{
    probe *pr = params;
    if (pr->n < 32)
        pr->x[pr->n] = x;
    pr->n++;
    return 0.0;
}

static double probe_indicator(double x, void *params)
{
    return x == *(const double *)params ? 1.0 : 0.0;
}

/* The 21-point Kronrod rule and its embedded 10-point Gauss rule, read from
 * GSL itself: the nodes where qk21 evaluates on [-1, 1], each weight as
 * qk21's value for the indicator of its node, and the Gauss weights from
 * GSL's Gauss-Legendre table. */
static int gauss_rule(gauss_plan *pl)
{
    probe pr = {{0}, 0};
    gsl_function F = {probe_record, &pr};
    double res, err, rabs, rasc;
    gsl_integration_qk21(&F, -1.0, 1.0, &res, &err, &rabs, &rasc);
    if (pr.n != GK_N)
        return aa_fail(AA_EFAIL, "qk21 evaluated %d points, not %d", pr.n, GK_N);
    qsort(pr.x, GK_N, sizeof *pr.x, truth_cmp_double);
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(GL_N);
    if (!t)
        return aa_fail(AA_ENOMEM, "out of memory for a Gauss-Legendre table");
    int ng = 0;
    double sk = 0.0, sg = 0.0;
    for (int k = 0; k < GK_N; k++) {
        double x = pr.x[k];
        gsl_function G = {probe_indicator, &x};
        pl->x[k] = x;
        gsl_integration_qk21(&G, -1.0, 1.0, &pl->wk[k], &err, &rabs, &rasc);
        pl->wg[k] = 0.0;
        for (size_t i = 0; i < GL_N; i++) {
            double xi, wi;
            gsl_integration_glfixed_point(-1.0, 1.0, i, &xi, &wi, t);
            if (fabs(xi - x) < 1e-14)
                pl->wg[k] = wi, ng++;
        }
        sk += pl->wk[k];
        sg += pl->wg[k];
    }
    gsl_integration_glfixed_table_free(t);
    if (ng != GL_N || fabs(sk - 2.0) > 1e-14 || fabs(sg - 2.0) > 1e-14)
        return aa_fail(AA_EFAIL, "the Gauss-Kronrod 10/21 rule read from GSL is inconsistent");
    return AA_OK;
}

void plan_free(gauss_plan *pl)
{
    free(pl->cdf_tab);
    free(pl->np);
    free(pl->r0);
    free(pl->a);
    free(pl->d);
    free(pl->mass);
    memset(pl, 0, sizeof *pl);
}

static double panel_edge(const gauss_plan *pl, long p)
{
    return (double)p * pl->num / pl->den;
}

/* Height of node m of panel p, in extended precision. */
static long double node_height(const gauss_plan *pl, long p, int m)
{
    return ((long double)p * pl->num + (1.0L + pl->x[m]) * 0.5L * pl->num) / pl->den;
}

/* The tabulated cdf (see gauss_plan), over the z a near crossing can have:
 * |x - uc| <= R + the widest extent of a piece that is not steep. */
static int cdf_table(gauss_plan *pl, double h)
{
    double s = pl->s;
    pl->M = 1;
    while (pl->M < CDF_STEPS / s && pl->M < (1 << 24))
        pl->M *= 2; /* a power of two: k / M is exact */
    long double dz = 1.0L / ((long double)s * pl->M);
    double zmax = (pl->R + FAST_SLOPE * h + 1.0) / s;
    pl->kt = (long)ceil(zmax / (double)dz) + 2;
    size_t rows = 2 * (size_t)pl->kt + 1;
    pl->cdf_tab = malloc(rows * (CDF_TERMS + 1) * sizeof *pl->cdf_tab);
    if (!pl->cdf_tab)
        return aa_fail(AA_ENOMEM, "out of memory for the cdf table");
    for (size_t r = 0; r < rows; r++) {
        long double z = ((long double)r - pl->kt) * dz;
        long double phi = expl(-0.5L * z * z) / sqrtl(2.0L * 3.141592653589793238462643L);
        double *t = pl->cdf_tab + r * (CDF_TERMS + 1);
        t[0] = (double)(0.5L * erfcl(-z / sqrtl(2.0L)));
        /* Phi^(n) = (-1)^(n-1) He_(n-1)(z) phi(z), Hermite by recurrence */
        long double he0 = 1.0L, he1 = z, fact = 1.0L;
        for (int n = 1; n <= CDF_TERMS; n++) {
            fact *= n;
            long double he = n == 1 ? he0 : he1;
            t[n] = (double)((n % 2 ? 1.0L : -1.0L) * he * phi / fact);
            if (n >= 2) {
                long double next = z * he1 - (n - 1) * he0;
                he0 = he1;
                he1 = next;
            }
        }
    }
    return AA_OK;
}

int plan_init(gauss_plan *pl, const aa_filter *f)
{
    memset(pl, 0, sizeof *pl);
    int st = gauss_rule(pl);
    if (st)
        return st;
    /* Panels of at most 2 s, aligned with the pixel grid: |K21 - G10| is
     * then below 1e-15 a panel for slopes up to 0.6 (crow's steepest). */
    double two_s = 2.0 * f->spec.v[0];
    if (two_s >= 1.0)
        pl->num = (int)floor(two_s), pl->den = 1;
    else
        pl->num = 1, pl->den = (int)ceil(1.0 / two_s);
    pl->R = f->radius;
    pl->s = f->spec.v[0];
    pl->inv_s = 1.0 / pl->s;
    pl->lost = f->lost;
    pl->peak = aa_filter_weight(f, 0.0);
    double h = (double)pl->num / pl->den;
    pl->node_err = (h + 0.5 * pl->R) * pl->R / (pl->s * pl->s);
    int phases = pl->num;
    pl->np = calloc((size_t)phases, sizeof *pl->np);
    pl->r0 = calloc((size_t)phases, sizeof *pl->r0);
    if (!pl->np || !pl->r0) {
        plan_free(pl);
        return aa_fail(AA_ENOMEM, "out of memory for the Gaussian plan");
    }
    for (int ph = 0; ph < phases; ph++) {
        double vrel = ph + 0.5; /* the centre, relative to (j div num) num */
        double lo = floor((vrel - pl->R) / h), hi = ceil((vrel + pl->R) / h) - 1.0;
        pl->r0[ph] = (int)lo;
        pl->np[ph] = (int)(hi - lo) + 1;
        if (pl->np[ph] > pl->np_max)
            pl->np_max = pl->np[ph];
    }
    size_t cells = (size_t)phases * (size_t)pl->np_max;
    pl->a = calloc(cells * GK_S, sizeof *pl->a);
    pl->d = calloc(cells * GK_S, sizeof *pl->d);
    pl->mass = calloc(cells, sizeof *pl->mass);
    if (!pl->a || !pl->d || !pl->mass) {
        plan_free(pl);
        return aa_fail(AA_ENOMEM, "out of memory for the Gaussian plan");
    }
    if ((st = cdf_table(pl, h))) {
        plan_free(pl);
        return st;
    }
    for (int ph = 0; ph < phases; ph++) {
        double vrel = ph + 0.5;
        for (int k = 0; k < pl->np[ph]; k++) {
            size_t cell = (size_t)ph * (size_t)pl->np_max + (size_t)k;
            long r = pl->r0[ph] + k;
            double start = panel_edge(pl, r) - vrel, end = panel_edge(pl, r + 1) - vrel;
            pl->mass[cell] = aa_filter_cdf(f, end) - aa_filter_cdf(f, start);
            for (int m = 0; m < GK_N; m++) {
                double rel = start + (1.0 + pl->x[m]) * 0.5 * h;
                double wv = 0.5 * h * aa_filter_weight(f, rel);
                pl->a[cell * GK_S + m] = pl->wk[m] * wv;
                pl->d[cell * GK_S + m] = (pl->wk[m] - pl->wg[m]) * wv;
            }
        }
    }
    return AA_OK;
}


void fast_free(panel_worker *fs)
{
    aa_strip_free(fs->strip);
    free(fs->kind);
    free(fs->nnear);
    free(fs->cst);
    free(fs->g);
    free(fs->row_cells);
    free(fs->near_diff);
    free(fs->bad_diff);
    free(fs->runs);
    free(fs->bp);
    free(fs->cr);
    free(fs->keys);
    free(fs->act);
    free(fs->tail_c0);
    free(fs->col);
    free(fs->wind);
    memset(fs, 0, sizeof *fs);
}

/* Bytes a thread's panel buffers take. */
size_t fast_bytes(const gauss_plan *pl, int w, int nc)
{
    size_t cells = (size_t)pl->np_max * (size_t)w;
    return cells * (1 + sizeof(unsigned short) + (size_t)nc * (GK_S + 1) * sizeof(double));
}

int fast_init(panel_worker *fs, const gauss_plan *pl, const aa_filter *f,
                     const aa_scene *scene, int w)
{
    memset(fs, 0, sizeof *fs);
    fs->plan = pl;
    fs->f = f;
    fs->scene = scene;
    fs->w = w;
    fs->nc = aa_scene_is_grey(scene) ? 1 : 3;
    fs->ring = pl->np_max;
    size_t cells = (size_t)fs->ring * (size_t)w, nc = (size_t)fs->nc;
    int nl = aa_scene_layer_count(scene);
    fs->strip = aa_strip_new(scene);
    fs->kind = malloc(cells);
    fs->nnear = malloc(cells * sizeof *fs->nnear);
    fs->cst = malloc(cells * nc * sizeof *fs->cst);
    fs->g = malloc(cells * nc * GK_S * sizeof *fs->g);
    fs->row_cells = malloc((size_t)fs->ring * sizeof *fs->row_cells);
    fs->near_diff = malloc(((size_t)w + 1) * sizeof *fs->near_diff);
    fs->bad_diff = malloc(((size_t)w + 1) * sizeof *fs->bad_diff);
    fs->runs = malloc(((size_t)w + 1) * sizeof *fs->runs);
    fs->wind = calloc((size_t)(nl > 0 ? nl : 1), sizeof *fs->wind);
    if (!fs->strip || !fs->kind || !fs->nnear || !fs->cst || !fs->g || !fs->row_cells ||
        !fs->near_diff || !fs->bad_diff || !fs->runs || !fs->wind) {
        fast_free(fs);
        return aa_fail(AA_ENOMEM, "out of memory for the Gaussian panels");
    }
    aa_rgb c = aa_scene_colour_of(scene, fs->wind);
    memcpy(fs->col_empty, c.c, sizeof fs->col_empty);
    return AA_OK;
}

static int fast_reserve(panel_worker *fs, size_t n)
{
    if (n < 16)
        n = 16; /* never empty: no null arrays for qsort and friends */
    if (n <= fs->cap)
        return AA_OK;
    size_t cap = 2 * n;
    void *p[6];
    p[0] = realloc(fs->bp, cap * sizeof *fs->bp);
    if (p[0])
        fs->bp = p[0];
    p[1] = realloc(fs->cr, GK_N * cap * sizeof *fs->cr);
    if (p[1])
        fs->cr = p[1];
    p[2] = realloc(fs->keys, cap * sizeof *fs->keys);
    if (p[2])
        fs->keys = p[2];
    p[3] = realloc(fs->act, cap * sizeof *fs->act);
    if (p[3])
        fs->act = p[3];
    p[4] = realloc(fs->col, GK_N * 3 * cap * sizeof *fs->col);
    if (p[4])
        fs->col = p[4];
    p[5] = realloc(fs->tail_c0, cap * sizeof *fs->tail_c0);
    if (p[5])
        fs->tail_c0 = p[5];
    for (int k = 0; k < 6; k++)
        if (!p[k])
            return aa_fail(AA_ENOMEM, "out of memory for a panel of %zu pieces", n);
    fs->cap = cap;
    return AA_OK;
}

static size_t ring_slot(const panel_worker *fs, long p)
{
    long r = p % fs->ring;
    return (size_t)(r < 0 ? r + fs->ring : r);
}

/* The columns whose window [i + 1/2 - R, i + 1/2 + R] meets [a, b]: from
 * c0, the first whose window reaches a, to c1, the last whose window starts
 * before b.  So a piece is wholly left of column i's window when c1 < i and
 * wholly right when c0 > i, also when it falls between two windows (c0 =
 * c1 + 1).  Clamped to [-1, w]. */
static void column_range(const panel_worker *fs, double a, double b, int *c0, int *c1)
{
    double lo = ceil(a - FAST_TOL - fs->plan->R - 0.5);
    double hi = floor(b + FAST_TOL + fs->plan->R - 0.5);
    *c0 = (int)fmin(fmax(lo, -1.0), (double)fs->w);
    *c1 = (int)fmin(fmax(hi, -1.0), (double)fs->w);
}

/* Count the columns c0..c1 (those in the image) in a difference array. */
static void mark(const panel_worker *fs, int *diff, int c0, int c1)
{
    c0 = c0 < 0 ? 0 : c0;
    c1 = c1 > fs->w - 1 ? fs->w - 1 : c1;
    if (c0 <= c1)
        diff[c0]++, diff[c1 + 1]--;
}

/* Steeper than FAST_SLOPE anywhere on [lo, hi]?  dx/dy is a ratio of
 * linear functions of t, so monotone between the piece's ends. */
static int steep(const aa_piece *p, double lo, double hi)
{
    if (p->kind == AA_PIECE_CUBIC) {
        /* dx/dy is not monotone along a cubic: the slope holds on [ta, tb]
         * when both FAST_SLOPE y'(t) - x'(t) and FAST_SLOPE y'(t) + x'(t),
         * quadratics in t, stay positive there: at the ends and at a
         * minimum inside */
        double ta = aa_piece_t_at(p, lo), tb = aa_piece_t_at(p, hi);
        for (int sg = -1; sg <= 1; sg += 2) {
            double a = FAST_SLOPE * p->by - sg * p->bx;
            double b = 2.0 * (FAST_SLOPE * p->ay - sg * p->ax);
            double c = 3.0 * (FAST_SLOPE * p->dy - sg * p->dx);
            double ga = a + ta * (b + ta * c), gb = a + tb * (b + tb * c);
            if (!(ga > 0.0) || !(gb > 0.0))
                return 1;
            if (c > 0.0) {
                double tv = -b / (2.0 * c);
                if (tv > ta && tv < tb && !(a + tv * (b + tv * c) > 0.0))
                    return 1;
            }
        }
        return 0;
    }
    double ts[2] = {aa_piece_t_at(p, lo), aa_piece_t_at(p, hi)};
    for (int k = 0; k < 2; k++) {
        double dy = p->by + 2.0 * p->ay * ts[k], dx = p->bx + 2.0 * p->ax * ts[k];
        if (!(dy > 0.0) || !(fabs(dx) <= FAST_SLOPE * dy))
            return 1;
    }
    return 0;
}

/* x(v) = X + S tau + Q tau^2 with tau = v - lo, for a piece whose y is
 * linear in its parameter (lines; arcs with ay = 0, such as crow's). */
static void as_quadratic(const local_piece *q, long double lo, long double *X, long double *S,
                         long double *Q)
{
    long double u = (lo - q->y0) / q->by;
    *X = q->x0 + u * (q->bx + q->ax * u);
    *S = (q->bx + 2 * q->ax * u) / q->by;
    *Q = q->ax / (q->by * q->by);
}

static int sign_tol(long double d)
{
    return d > FAST_TOL ? 1 : (d < -FAST_TOL ? -1 : 0);
}

/* May pieces a and b meet strictly inside the panel (va, vb), where both
 * are present?  Exact for pieces with x quadratic in y; any other pair
 * whose extents overlap is assumed to meet. */
static int may_meet(const band_piece *a, const band_piece *b, double va, double vb)
{
    long double lo = fmaxl(va, fmaxl(a->q.y0, b->q.y0));
    long double hi = fminl(vb, fminl(a->q.y1, b->q.y1));
    if (!(lo < hi))
        return 0;
    if (a->q.cubic || b->q.cubic || a->q.conic || b->q.conic || a->q.offset || b->q.offset) {
        /* the scene's meetings: roots of a cubic against a line, bisection
         * on exact extents (to 1e-12, a touch counted) against an arc; a
         * conic's (its own columns are QAG's already) */
        double ys[1];
        return aa_piece_meet(a->p, b->p, (double)lo, (double)hi, ys, 1) > 0;
    }
    if (a->q.ay != 0 || b->q.ay != 0)
        return 1;
    long double Xa, Sa, Qa, Xb, Sb, Qb;
    as_quadratic(&a->q, lo, &Xa, &Sa, &Qa);
    as_quadratic(&b->q, lo, &Xb, &Sb, &Qb);
    long double X = Xb - Xa, S = Sb - Sa, Q = Qb - Qa, L = hi - lo;
    int s0 = sign_tol(X), s1 = sign_tol(X + L * (S + L * Q));
    if (s0 * s1 < 0 || (s0 == 0 && s1 == 0))
        return 1;
    if (Q != 0) {
        long double t = -S / (2 * Q);
        if (t > 0 && t < L) {
            int sm = sign_tol(X + t * (S + t * Q));
            if (sm == 0 || (s0 && sm != s0) || (s1 && sm != s1))
                return 1;
        }
    }
    return 0;
}

static int cmp_key(const void *a, const void *b)
{
    const key_index *p = a, *q = b;
    if (p->key != q->key)
        return p->key < q->key ? -1 : 1;
    return p->k < q->k ? -1 : (p->k > q->k);
}

/* Mark the columns near pieces that may meet inside the panel: a sweep over
 * the x extents, testing the pairs that overlap. */
static void mark_meetings(panel_worker *fs, size_t nb, double va, double vb)
{
    if (nb < 2)
        return;
    for (size_t k = 0; k < nb; k++)
        fs->keys[k].key = fs->bp[k].xmin, fs->keys[k].k = k;
    qsort(fs->keys, nb, sizeof *fs->keys, cmp_key);
    size_t nact = 0;
    for (size_t s = 0; s < nb; s++) {
        const band_piece *b = &fs->bp[fs->keys[s].k];
        size_t keep = 0, tested = 0;
        int crowd = 0;
        for (size_t t = 0; t < nact; t++) {
            const band_piece *a = &fs->bp[fs->act[t]];
            if (a->xmax < b->xmin - FAST_TOL)
                continue; /* left behind for good: extents sorted by xmin */
            fs->act[keep++] = fs->act[t];
            if (crowd || ++tested > FAST_PAIRS) {
                crowd = 1;
                mark(fs, fs->bad_diff, a->c0, a->c1);
            } else if (may_meet(a, b, va, vb)) {
                mark(fs, fs->bad_diff, a->c0, a->c1);
                mark(fs, fs->bad_diff, b->c0, b->c1);
            }
        }
        if (crowd)
            mark(fs, fs->bad_diff, b->c0, b->c1);
        nact = keep;
        fs->act[nact++] = fs->keys[s].k;
    }
}

static int cmp_cross(const node_cross *a, const node_cross *b)
{
    if (a->x != b->x)
        return a->x < b->x ? -1 : 1;
    return a->k < b->k ? -1 : (a->k > b->k);
}

static int cmp_cross_q(const void *a, const void *b)
{
    return cmp_cross(a, b);
}

/* The crossings of node line m (height v) by the panel's pieces, sorted by
 * (x, piece), the colour after each, and where each falls in the cdf
 * table.  Pieces come sorted by their left end, so the crossings are nearly
 * sorted: insertion sort, or qsort past a budget of moves. */
static void node_crossings(panel_worker *fs, size_t nb, int m, long double v)
{
    node_cross *cr = fs->cr + (size_t)m * fs->cap;
    double *col = fs->col + (size_t)m * 3 * fs->cap;
    const gauss_plan *pl = fs->plan;
    size_t n = 0;
    for (size_t k = 0; k < nb; k++) {
        const band_piece *b = &fs->bp[k];
        if (!(v >= b->q.y0 && v < b->q.y1))
            continue;
        node_cross *c = &cr[n++];
        long double part = truth_crossing_part(&b->q, v);
        c->x = (double)(b->q.x0 + part);
        c->k = (int)k;
        c->c0 = b->c0;
        c->c1 = b->c1;
        /* x - 1/2 = base/M + s dz.  x0 - (1/2 + base/M) is exact in long
         * double (both have few bits), so dz carries one rounding of x's
         * small part and none of its magnitude. */
        double xr = (c->x - 0.5) * pl->M + 0.5;
        long base = fabs(xr) < 1e15 ? (long)xr : 0;
        c->base = base - (xr < (double)base); /* floor */
        long double off = (b->q.x0 - (0.5L + (long double)c->base / pl->M)) + part;
        double dz = (double)off * pl->inv_s, dz2 = dz * dz, dz4 = dz2 * dz2;
        c->pw[0] = dz, c->pw[1] = dz2, c->pw[2] = dz2 * dz, c->pw[3] = dz4;
        c->pw[4] = dz4 * dz, c->pw[5] = dz4 * dz2, c->pw[6] = dz4 * c->pw[2];
    }
    size_t moves = 0, budget = 8 * n + 64;
    for (size_t k = 1; k < n; k++) {
        node_cross c = cr[k];
        size_t at = k;
        while (at > 0 && cmp_cross(&cr[at - 1], &c) > 0) {
            cr[at] = cr[at - 1];
            at--;
            moves++;
        }
        cr[at] = c;
        if (moves > budget) {
            qsort(cr, n, sizeof *cr, cmp_cross_q);
            break;
        }
    }
    int nl = aa_scene_layer_count(fs->scene);
    memset(fs->wind, 0, (size_t)(nl > 0 ? nl : 1) * sizeof *fs->wind);
    for (size_t k = 0; k < n; k++) {
        const local_piece *q = &fs->bp[cr[k].k].q;
        fs->wind[q->layer] += q->dir;
        aa_rgb c = aa_scene_colour_of(fs->scene, fs->wind);
        memcpy(col + 3 * k, c.c, sizeof c.c);
    }
    fs->nx[m] = n;
}

/* The cdf at x - uc for crossing c and column i: from the table, or (far
 * outside it, where it is 0 or 1 to within 1e-20, and which a near
 * crossing never is) from the filter itself. */
static double cross_cdf(const panel_worker *fs, const node_cross *c, int i)
{
    const gauss_plan *pl = fs->plan;
    long row = c->base - (long)i * pl->M + pl->kt;
    if (row >= 0 && row <= 2 * pl->kt) {
        const double *t = pl->cdf_tab + (size_t)row * (CDF_TERMS + 1);
        double sum = 0.0;
        for (int n = CDF_TERMS; n >= 1; n--)
            sum += t[n] * c->pw[n - 1];
        return t[0] + sum;
    }
    return aa_filter_cdf(fs->f, c->x - (i + 0.5));
}

/* The pieces near column i (their extent in the panel meets the window)
 * among the crossings cr[a..b) of a node line, sorted: they must be a run
 * cr[e..f), every crossing before it of a piece wholly left of the window
 * and every one after it (to b) of a piece wholly right.  Then the colours
 * after each crossing are those of the full line.  Returns 0 if the pieces
 * are not so ordered (the column then goes to QAG). */
static int near_run(const node_cross *cr, size_t a, size_t b, int i, size_t *e, size_t *f)
{
    size_t s = a;
    while (s < b && cr[s].c1 < i)
        s++;
    size_t t = s;
    while (t < b && cr[t].c0 <= i && i <= cr[t].c1)
        t++;
    for (size_t u = t; u < b; u++)
        if (cr[u].c0 <= i)
            return 0;
    *e = s, *f = t;
    return 1;
}

/* The inner integral of column i on node line m, whose near crossings are
 * cr[e..f): the integral over the whole line of the colours the near run
 * defines (the window's colours, extended beyond it on either side), a
 * smooth function of the near crossings.  Writes it to g[ch * GK_S]. */
static void node_value(const panel_worker *fs, int m, size_t e, size_t f, int i, double *g)
{
    const node_cross *cr = fs->cr + (size_t)m * fs->cap;
    const double *col = fs->col + (size_t)m * 3 * fs->cap;
    const double *cb = e > 0 ? col + 3 * (e - 1) : fs->col_empty;
    if (fs->nc == 1) {
        double acc = cb[0];
        if (e < f) {
            double prev = cross_cdf(fs, &cr[e], i);
            acc = cb[0] * prev;
            for (size_t t = e + 1; t <= f; t++) {
                double next = t < f ? cross_cdf(fs, &cr[t], i) : 1.0;
                acc += col[3 * (t - 1)] * (next - prev);
                prev = next;
            }
        }
        g[0] = acc;
        return;
    }
    double acc[3] = {cb[0], cb[1], cb[2]};
    if (e < f) {
        double prev = cross_cdf(fs, &cr[e], i);
        for (int ch = 0; ch < 3; ch++)
            acc[ch] = cb[ch] * prev;
        for (size_t t = e + 1; t <= f; t++) {
            double next = t < f ? cross_cdf(fs, &cr[t], i) : 1.0;
            for (int ch = 0; ch < 3; ch++)
                acc[ch] += col[3 * (t - 1) + ch] * (next - prev);
            prev = next;
        }
    }
    for (int ch = 0; ch < 3; ch++)
        g[ch * GK_S] = acc[ch];
}

static void zero_pad(const panel_worker *fs, double *gi)
{
    for (int ch = 0; ch < fs->nc; ch++)
        for (int m = GK_N; m < GK_S; m++)
            gi[ch * GK_S + m] = 0.0;
}

/* Do all node lines of the panel cross the same pieces in the same order?
 * (No piece begins or ends inside, none meets another: the usual case.) */
static int same_order(const panel_worker *fs)
{
    size_t n = fs->nx[0];
    for (int m = 1; m < GK_N; m++) {
        if (fs->nx[m] != n)
            return 0;
        const node_cross *a = fs->cr, *b = fs->cr + (size_t)m * fs->cap;
        for (size_t t = 0; t < n; t++)
            if (a[t].k != b[t].k)
                return 0;
    }
    return 1;
}

/* The node columns when every node line has the same order: the near run
 * of a column is then the same on every line, found once per column by
 * pointers that only move right.  Same values as columns_general. */
static void columns_same_order(panel_worker *fs, unsigned char *kind, unsigned short *nnear,
                               double *g)
{
    const node_cross *cr = fs->cr;
    size_t n = fs->nx[0], e = 0, f = 0;
    /* the smallest c0 from each position on: the pieces after a run must
     * all be wholly right of the window */
    int *tail = fs->tail_c0;
    for (size_t t = n; t-- > 0;)
        tail[t] = t + 1 < n && tail[t + 1] < cr[t].c0 ? tail[t + 1] : cr[t].c0;
    for (size_t r = 0; r + 1 < fs->nruns; r += 2) {
        for (int i = fs->runs[r]; i < fs->runs[r + 1]; i++) {
            while (e < n && cr[e].c1 < i)
                e++;
            if (f < e)
                f = e;
            while (f < n && cr[f].c0 <= i)
                f++;
            int ok = f >= n || tail[f] > i;
            for (size_t t = e; t < f && ok; t++)
                ok = cr[t].c1 >= i;
            if (!ok || kind[i] != PANEL_NODES) {
                kind[i] = ok ? kind[i] : PANEL_BAD;
                continue;
            }
            double *gi = g + (size_t)i * (size_t)fs->nc * GK_S;
            for (int m = 0; m < GK_N; m++)
                node_value(fs, m, e, f, i, gi + m);
            zero_pad(fs, gi);
            nnear[i] = (unsigned short)(f - e < 65535 ? f - e : 65535);
        }
    }
}

/* The node columns in general: per column and node line, the crossings
 * within `reach` of the window, then their near run. */
static void columns_general(panel_worker *fs, double reach, unsigned char *kind,
                            unsigned short *nnear, double *g)
{
    for (int m = 0; m < GK_N; m++)
        fs->at[m][0] = fs->at[m][1] = 0;
    for (size_t r = 0; r + 1 < fs->nruns; r += 2) {
        for (int i = fs->runs[r]; i < fs->runs[r + 1]; i++) {
            double uc = i + 0.5;
            double *gi = g + (size_t)i * (size_t)fs->nc * GK_S;
            zero_pad(fs, gi);
            for (int m = 0; m < GK_N; m++) {
                const node_cross *cr = fs->cr + (size_t)m * fs->cap;
                size_t nx = fs->nx[m], a = fs->at[m][0], b = fs->at[m][1], e, f;
                while (a < nx && cr[a].x < uc - reach)
                    a++;
                if (b < a)
                    b = a;
                while (b < nx && cr[b].x <= uc + reach)
                    b++;
                fs->at[m][0] = a, fs->at[m][1] = b;
                if (kind[i] != PANEL_NODES)
                    continue;
                if (!near_run(cr, a, b, i, &e, &f)) {
                    kind[i] = PANEL_BAD;
                    continue;
                }
                node_value(fs, m, e, f, i, gi + m);
                if (f - e > nnear[i])
                    nnear[i] = (unsigned short)(f - e < 65535 ? f - e : 65535);
            }
        }
    }
}

/* Compute panel p into its ring slot. */
static int fast_panel(panel_worker *fs, long p)
{
    const gauss_plan *pl = fs->plan;
    int w = fs->w, nc = fs->nc;
    size_t slot = ring_slot(fs, p), base = slot * (size_t)w;
    unsigned char *kind = fs->kind + base;
    unsigned short *nnear = fs->nnear + base;
    double *cst = fs->cst + base * (size_t)nc;
    double *g = fs->g + base * (size_t)nc * GK_S;
    double va = panel_edge(pl, p), vb = panel_edge(pl, p + 1);
    int st = aa_strip_begin(fs->strip, va, vb);
    if (st)
        return st;
    aa_strip_window(fs->strip, -INFINITY, INFINITY);
    size_t n;
    const aa_piece *const *list = aa_strip_local(fs->strip, &n);
    if ((st = fast_reserve(fs, n)))
        return st;
    memset(fs->near_diff, 0, ((size_t)w + 1) * sizeof *fs->near_diff);
    memset(fs->bad_diff, 0, ((size_t)w + 1) * sizeof *fs->bad_diff);
    /* The inner integral G of a column is analytic on the panel unless a
     * piece near it ends inside, is flat inside, is steep, or meets
     * another; those columns are marked for QAG, and so are the columns
     * near a conic piece (the rule's estimate is not trusted with its
     * square roots). */
    size_t nb = 0;
    double reach = 0.0; /* widest extent of a piece that is not marked */
    for (size_t k = 0; k < n; k++) {
        const aa_piece *q = list[k];
        int c0, c1;
        if (!q->dir) { /* flat strictly inside the panel */
            column_range(fs, q->xmin, q->xmax, &c0, &c1);
            mark(fs, fs->bad_diff, c0, c1);
            continue;
        }
        double lo = fmax(va, q->y0), hi = fmin(vb, q->y1);
        if (!(lo < hi))
            continue; /* begins at the panel's bottom: meets no node line */
        band_piece *b = &fs->bp[nb++];
        aa_piece_xrange(q, lo, hi, &b->xmin, &b->xmax);
        column_range(fs, b->xmin, b->xmax, &b->c0, &b->c1);
        truth_set_local(&b->q, q, 0, 0);
        b->p = q;
        mark(fs, fs->near_diff, b->c0, b->c1);
        if (q->kind == AA_PIECE_CONIC || q->kind == AA_PIECE_OFFSET ||
            (q->y0 > va && q->y0 < vb) ||
            (q->y1 > va && q->y1 < vb) || steep(q, lo, hi))
            mark(fs, fs->bad_diff, b->c0, b->c1);
        else
            reach = fmax(reach, b->xmax - b->xmin);
    }
    mark_meetings(fs, nb, va, vb);
    int nearc = 0, badc = 0, prev = PANEL_CONST;
    fs->nruns = 0;
    for (int i = 0; i < w; i++) {
        nearc += fs->near_diff[i];
        badc += fs->bad_diff[i];
        kind[i] = badc ? PANEL_BAD : (nearc ? PANEL_NODES : PANEL_CONST);
        nnear[i] = 0;
        if (kind[i] == PANEL_NODES && prev != PANEL_NODES)
            fs->runs[fs->nruns++] = i;
        if (kind[i] != PANEL_NODES && prev == PANEL_NODES)
            fs->runs[fs->nruns++] = i;
        prev = kind[i];
    }
    if (prev == PANEL_NODES)
        fs->runs[fs->nruns++] = w;
    reach += pl->R + 2 * FAST_TOL;
    for (int m = 0; m < GK_N; m++)
        node_crossings(fs, nb, m, node_height(pl, p, m));
    /* constant columns: no piece near, one colour on the window */
    const node_cross *mid = fs->cr + (size_t)(GK_N / 2) * fs->cap;
    const double *midcol = fs->col + (size_t)(GK_N / 2) * 3 * fs->cap;
    size_t at = 0, nmid = fs->nx[GK_N / 2];
    for (int i = 0; i < w; i++) {
        if (kind[i] != PANEL_CONST)
            continue;
        while (at < nmid && mid[at].x < i + 0.5)
            at++;
        const double *c = at > 0 ? midcol + 3 * (at - 1) : fs->col_empty;
        for (int ch = 0; ch < nc; ch++)
            cst[(size_t)i * nc + ch] = c[ch];
    }
    /* the others, column by column so that each writes its own block */
    if (same_order(fs))
        columns_same_order(fs, kind, nnear, g);
    else
        columns_general(fs, reach, kind, nnear, g);
    return AA_OK;
}

/* Make sure the panels of row j are in the ring, and note where. */
int fast_row(panel_worker *fs, int j, int *phase)
{
    const gauss_plan *pl = fs->plan;
    int ph = j % pl->num;
    long lo = (long)(j / pl->num) * pl->den + pl->r0[ph], hi = lo + pl->np[ph] - 1;
    if (!fs->valid || lo < fs->lo || lo > fs->hi + 1) {
        fs->lo = lo;
        fs->hi = lo - 1;
        fs->valid = 1;
    }
    while (fs->hi < hi) {
        long p = fs->hi + 1;
        if (p - fs->lo + 1 > fs->ring)
            fs->lo = p - fs->ring + 1; /* its slot is reused */
        int st = fast_panel(fs, p);
        if (st) {
            fs->valid = 0;
            return st;
        }
        fs->hi = p;
    }
    for (int k = 0; k < pl->np[ph]; k++)
        fs->row_cells[k] = ring_slot(fs, lo + k) * (size_t)fs->w;
    *phase = ph;
    return AA_OK;
}

/* sum a[m] g[m] and sum d[m] g[m] over GK_S values: pairs of doubles in
 * three independent chains each (the order is fixed, so the result does
 * not depend on where or by whom it is computed). */
typedef double v2d __attribute__((vector_size(16)));

static void dot2(const double *a, const double *d, const double *g, double *s, double *e)
{
    v2d sa[3] = {{0, 0}, {0, 0}, {0, 0}}, sd[3] = {{0, 0}, {0, 0}, {0, 0}};
    for (int m = 0; m < GK_S; m += 6) {
        for (int c = 0; c < 3; c++) {
            v2d av, dv, gv;
            memcpy(&av, a + m + 2 * c, sizeof av);
            memcpy(&dv, d + m + 2 * c, sizeof dv);
            memcpy(&gv, g + m + 2 * c, sizeof gv);
            sa[c] += av * gv;
            sd[c] += dv * gv;
        }
    }
    v2d ts = sa[0] + sa[1] + sa[2], td = sd[0] + sd[1] + sd[2];
    *s = ts[0] + ts[1];
    *e = td[0] + td[1];
}

/* Pixel i of the current row: the fixed rule's value and bound, or 0 if a
 * panel is marked or the bound is too large for it. */
int fast_pixel(const panel_worker *fs, int j, int phase, int i, int grey, double *value,
                      double *bound)
{
    const gauss_plan *pl = fs->plan;
    int np = pl->np[phase], nc = fs->nc, nmax = 0;
    size_t cell0 = (size_t)phase * (size_t)pl->np_max;
    for (int k = 0; k < np; k++)
        if (fs->kind[fs->row_cells[k] + (size_t)i] == PANEL_BAD)
            return 0;
    double val[3] = {0, 0, 0}, est[3] = {0, 0, 0};
    for (int k = 0; k < np; k++) {
        size_t cell = fs->row_cells[k] + (size_t)i;
        if (fs->kind[cell] == PANEL_CONST) {
            for (int ch = 0; ch < nc; ch++)
                val[ch] += pl->mass[cell0 + (size_t)k] * fs->cst[cell * (size_t)nc + (size_t)ch];
            continue;
        }
        if (fs->nnear[cell] > nmax)
            nmax = fs->nnear[cell];
        const double *a = pl->a + (cell0 + (size_t)k) * GK_S;
        const double *d = pl->d + (cell0 + (size_t)k) * GK_S;
        for (int ch = 0; ch < nc; ch++) {
            const double *g = fs->g + (cell * (size_t)nc + (size_t)ch) * GK_S;
            double s, e;
            dot2(a, d, g, &s, &e);
            val[ch] += s;
            est[ch] += fabs(e);
        }
    }
    double worst = fmax(est[0], fmax(est[1], est[2]));
    /* Rounding (colours in [0, 1], weights summing to 1): the dot products
     * and the weights; per node value, 2 ulps per tabulated cdf and the
     * sum over the near crossings; the node heights, exact within a few
     * ulps in the weights and an ulp of long double in G. */
    double rnd = DBL_EPSILON * ((double)(np * (GK_N + 1) + 4 + 3 * (nmax + 1)) + pl->node_err) +
                 LDBL_EPSILON * (j + pl->R + 2.0) * (double)(nmax + 1) * pl->peak * FAST_SLOPE;
    double b = worst + 2.0 * pl->lost + rnd;
    if (!(b <= FAST_LIMIT))
        return 0;
    for (int ch = 0; ch < 3; ch++)
        value[ch] = val[grey ? 0 : ch];
    *bound = b;
    return 1;
}
