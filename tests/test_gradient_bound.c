/*
 * test_gradient_bound.c: the bounds of the box reference's path of several
 * gradients (harness/truth/truth.c, "several gradients at a point",
 * gen_bounds and the fold's fold_bounds): every bound S of |e| and D of
 * |e'| it proves on a Bernstein ellipse (or on a real segment) about a
 * piece of a row, e the encoded composite of the span's gradient layers,
 * held above the composite's true modulus there.  The 20-point rule's
 * error bound, and so each pixel's, rests on S (Trefethen's Thm 19.3: M
 * rho^(-2n) with M from S), and the decoding's power piece on A D; a
 * bound too small leaves the reference's values within it but the bound
 * no longer one, which no test of the values sees.
 *
 * Known answers, derived here and not from the code under test: the
 * composite at complex points z of the row, from the scenes' definitions
 * alone (patterns/README.md, "Gradients"; aabench.h, aa_gradient; core.h,
 * aa_scene_set_alpha):
 *  - a linear gradient from P1 to P2 (pixels) has t = ((z, y) - P1).(P2 -
 *    P1) / |P2 - P1|^2, an affine function of z, so it continues to
 *    complex z as it stands; a radial one of nested circles the largest w
 *    with |q - F - w D| = fr + w dr (radial_t: in long double, the square
 *    root's branch points kept off the ellipse by cuts away from the row);
 *    spread: repeat takes t - k, reflect t - k or 1 - (t - k), k = floor(t)
 *    at the piece's middle m (the reference cuts the row at every period's
 *    end and stop, so on the piece k and the stop pair, the pair of
 *    offsets holding t(m), stay the same, and pad beyond the stops is the
 *    end stop's constant paint);
 *  - between stops i and i + 1 the fraction f = (t - o_i) / (o_{i+1} -
 *    o_i) interpolates the opacity and, in sRGB, the stops' encoded
 *    channels (encode: IEC 61966-2-1, written out here); in linear light
 *    the linear channels v, the layer's channel then encode(v): 12.92 v
 *    where v(m) <= 0.0031308 (the stops are cut where v passes it), 1.055
 *    v^(1/2.4) - 0.055 (the principal power, analytic where Re v > 0)
 *    above;
 *  - the layers (added front to back) composite from the back in encoded
 *    values, source over: e := e (1 - a) + a C, a the layer's alpha times
 *    its opacity, from the background's encoded colour; e' by the product
 *    rule along the same steps, with t' = (P2 - P1)_x / |P2 - P1|^2
 *    (negated on a reflected odd period; the radial's from w's formula).
 * The composite is analytic inside every ellipse on which the reference
 * claims a bound (linear layers are entire; the radial's and the power's
 * branch points the reference keeps out), so by the maximum modulus
 * principle |e| and |e'| take their largest values on its boundary (and
 * each radial layer's branch points, disc's roots found here in
 * __float128, are required outside each ellipse: branch_ellipse): 32
 * points of it are evaluated (the two ends of its major axis among them,
 * where a single layer's modulus peaks), each required at most S and D
 * (1e-12 relative and 1e-15 for the rounding of both; the largest excess
 * found is 6.7e-16 relative).  The checks have teeth: on an opaque layer
 * over black the bounds are reached (the largest ratio of |e| to S and of
 * |e'| to D is required above 0.85 on the three ramps: 1.0000 or 0.9000),
 * so a factor left out of a bound shows (tests/README.md gives the
 * defects put in and what each printed).  The probe is told of every
 * bound the reference proves while it integrates a few pixels of each
 * scene (aa__truth_set_gen_probe, truth.h); on the two scenes of most
 * bounds, every 8th is checked, to keep the test within seconds.
 */
#include "core.h"
#include "support.h"
#include "truth.h"

#include <complex.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#define W 8
#define H 6
#define NL 8  /* layers of a scene at most */
#define NZ 32 /* points of each ellipse's boundary */
#define LIN AA_GRADIENT_LINEAR
#define RAD AA_GRADIENT_RADIAL

/* A layer of the scenes: a rectangle over the whole view painted with a
 * gradient of kind AA_GRADIENT_LINEAR (p: x1 y1 x2 y2) or
 * AA_GRADIENT_RADIAL (p: cx cy r fx fy fr), in pixels. */
typedef struct layer {
    int kind;
    double p[6], alpha;
    int spread, lin, nstops;
    const aa_gradient_stop *stops;
} layer;

typedef struct scene {
    const char *name;
    int x0, y0, w, h; /* the pixels integrated, of the W x H view */
    int every;        /* the probe checks one bound in every (1: each of them) */
    aa_rgb bg;
    int n;
    layer L[NL];
} scene;

/* What the probe found: bounds checked, the largest ratios of |e| to S
 * and |e'| to D, the first bound too small. */
typedef struct probe {
    const scene *sc;
    long seen, checked, skipped, folded, segments;
    double worst_e, worst_d;
    double worst_bp; /* the least of branch_ellipse over the radial layers' ellipses */
    double near;     /* the least distance of those rows from a radial layer's P* */
    int bad;
    char msg[512];
} probe;

/* sRGB's encoding (IEC 61966-2-1), written out here. */
static double enc(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

/* The encoded channel of a linear value v on the piece whose value at its
 * middle is vm, and its derivative in v. */
static double complex enc_c(double complex v, double vm, double complex *dv)
{
    if (vm <= 0.0031308) {
        *dv = 12.92;
        return 12.92 * v;
    }
    double complex p = cpow(v, 1.0 / 2.4);
    *dv = 1.055 / 2.4 * p / v;
    return 1.055 * p - 0.055;
}

/* A radial layer's t at x = z on row y, and dt/dz: the largest w with |q
 * - F - w D| = fr + w dr (D = C - F, dr = r - fr; core's aa_gradient),
 * with the focal circle inside the end circle a = D.D - dr^2 < 0 and w =
 * (b - sqrt(disc)) / a, b = (q - F).D + fr dr, c = |q - F|^2 - fr^2,
 * disc = b^2 - a c > 0 along the row.  disc is a quadratic in u = z - fx
 * with complex conjugate roots u1, u1*, so sqrt(disc) = sqrt(P2) s+(u -
 * u1) s-(u - u1*), each root's square root cut along the vertical ray
 * away from the real axis (an ellipse about a real segment that holds
 * neither root meets neither ray): analytic on the ellipse, positive on
 * the row.  tm: t at the real m. */
static double complex radial_t(const layer *g, double complex z, double y, double m, double *tm,
                               double complex *dt)
{
    long double Dx = (long double)g->p[0] - g->p[3], Dy = (long double)g->p[1] - g->p[4];
    long double dr = (long double)g->p[2] - g->p[5], fr = g->p[5];
    long double a = Dx * Dx + Dy * Dy - dr * dr, v = (long double)y - g->p[4], k = v * Dy + fr * dr;
    long double P2 = Dx * Dx - a, P1 = 2.0L * Dx * k, P0 = k * k - a * (v * v - fr * fr);
    long double q = P1 * P1 - 4.0L * P2 * P0;
    assert_true(a < 0.0L && q < 0.0L);
    long double complex u1 = (-P1 + I * sqrtl(-q)) / (2.0L * P2), out = 0.0L;
    const long double complex up = cexpl(-I * acosl(-1.0L) / 4), down = conjl(up);
    for (int k2 = 0; k2 < 2; k2++) {
        long double complex u = k2 ? (long double complex)z - g->p[3] : (long double)m - g->p[3];
        long double complex sd = sqrtl(P2) * csqrtl(I * (u - u1)) * up *
                                 csqrtl(-I * (u - conjl(u1))) * down;
        long double complex b = u * Dx + k, t = (b - sd) / a;
        if (!k2)
            *tm = (double)creall(t);
        else {
            *dt = (double complex)((Dx - (2.0L * P2 * u + P1) / (2.0L * sd)) / a);
            out = t;
        }
    }
    return (double complex)out;
}

/* Layer g's alpha times opacity a and colour C of channel ch at x = z on
 * row y, their derivatives da and dC; tm: t at the piece's middle m. */
static void layer_at(const layer *g, int ch, double complex z, double y, double m,
                     double complex *a, double complex *da, double complex *C,
                     double complex *dC)
{
    double complex t, dt;
    double tm;
    if (g->kind == LIN) {
        double dx = g->p[2] - g->p[0], dy = g->p[3] - g->p[1], l2 = dx * dx + dy * dy;
        t = ((z - g->p[0]) * dx + (y - g->p[1]) * dy) / l2;
        tm = ((m - g->p[0]) * dx + (y - g->p[1]) * dy) / l2;
        dt = dx / l2;
    } else
        t = radial_t(g, z, y, m, &tm, &dt);
    if (g->spread != AA_SPREAD_PAD) {
        double k = floor(tm);
        t -= k, tm -= k;
        if (g->spread == AA_SPREAD_REFLECT && fmod(k, 2.0) != 0.0)
            t = 1.0 - t, tm = 1.0 - tm, dt = -dt;
    }
    const aa_gradient_stop *s = g->stops;
    int n = g->nstops, i = 0;
    double f0 = 0.0, df = 0.0;
    if (tm <= s[0].offset)
        i = 0;
    else if (tm >= s[n - 1].offset)
        i = n - 1;
    else {
        while (i + 2 < n && !(tm < s[i + 1].offset))
            i++;
        df = 1.0 / (s[i + 1].offset - s[i].offset);
        f0 = s[i].offset;
    }
    double complex f = df != 0.0 ? (t - f0) * df : 0.0;
    double fm = df != 0.0 ? (tm - f0) * df : 0.0;
    const aa_gradient_stop *p = &s[i], *q = df != 0.0 ? &s[i + 1] : &s[i];
    *a = g->alpha * (p->opacity + f * (q->opacity - p->opacity));
    *da = g->alpha * (q->opacity - p->opacity) * df * dt;
    double c0 = p->colour.c[ch], c1 = q->colour.c[ch];
    if (g->lin) {
        double complex dv;
        *C = enc_c(c0 + f * (c1 - c0), c0 + fm * (c1 - c0), &dv);
        *dC = dv * (c1 - c0) * df * dt;
    } else {
        *C = enc(c0) + f * (enc(c1) - enc(c0));
        *dC = (enc(c1) - enc(c0)) * df * dt;
    }
}

/* The composite's channel ch at z and its derivative. */
static double complex composite(const scene *sc, int ch, double complex z, double y, double m,
                                double complex *de)
{
    double complex e = enc(sc->bg.c[ch]), d = 0.0;
    for (int l = sc->n - 1; l >= 0; l--) { /* added front to back (core.h) */
        double complex a, da, C, dC;
        layer_at(&sc->L[l], ch, z, y, m, &a, &da, &C, &dC);
        d = d * (1.0 - a) - e * da + da * C + a * dC;
        e = e * (1.0 - a) + a * C;
    }
    *de = d;
    return e;
}

/* Where the branch points z = F_x + u1, u1 = (-P1 +- i sqrt(4 P2 P0 - P1^2))
 * / (2 P2) (disc's roots as radial_t writes them) of radial layer g on
 * row y lie against the ellipse about m of semi-axes A, B: ((Re z - m) /
 * A)^2 + (Im z / B)^2, above 1 outside.  In __float128: near the focus
 * 4 P2 P0 - P1^2 cancels (terms of order 1, the difference of order the
 * square of the row's distance from P*: 1e-18 at 1e-9 px, still 16
 * digits here, where double has none). */
typedef __float128 q128;
static double branch_ellipse(const layer *g, double y, double m, double A, double B)
{
    q128 Dx = (q128)g->p[0] - g->p[3], Dy = (q128)g->p[1] - g->p[4];
    q128 dr = (q128)g->p[2] - g->p[5], fr = g->p[5];
    q128 a = Dx * Dx + Dy * Dy - dr * dr, v = (q128)y - g->p[4], k = v * Dy + fr * dr;
    q128 P2 = Dx * Dx - a, P1 = 2 * Dx * k, P0 = k * k - a * (v * v - fr * fr);
    q128 q = 4 * P2 * P0 - P1 * P1;
    assert_true(a < 0 && q > 0);
    long double re = (long double)(((q128)g->p[3] - m) - P1 / (2 * P2));
    long double im = sqrtl((long double)q) / (long double)(2 * P2);
    return (double)((re / A) * (re / A) + (im / B) * (im / B));
}

static void check_bound(void *ctx, const aa__gen_bound *b)
{
    probe *p = ctx;
    if (b->umode) { /* no cone-case layer here: never */
        p->skipped++;
        return;
    }
    if (p->seen++ % p->sc->every)
        return;
    p->checked++;
    p->folded += b->fold;
    p->segments += b->B == 0.0;
    for (int l = 0; l < p->sc->n && b->B > 0.0; l++) /* the radial layers' branch points out */
        if (p->sc->L[l].kind == RAD) {
            double e = branch_ellipse(&p->sc->L[l], b->y + p->sc->y0, b->m + p->sc->x0, b->A,
                                      b->B);
            const double *q = p->sc->L[l].p; /* P*'s height: F - (fr / dr) D */
            double ys = q[4] - q[5] / (q[2] - q[5]) * (q[1] - q[4]);
            p->worst_bp = fmin(p->worst_bp, e);
            p->near = fmin(p->near, fabs(b->y + p->sc->y0 - ys));
            if (!(e > 1.0) && !p->bad++)
                snprintf(p->msg, sizeof p->msg,
                         "%s: row %.17g, ellipse about %.17g, A %.6g, B %.6g: layer %d's branch "
                         "points inside (%.6g)", p->sc->name, b->y, b->m, b->A, b->B, l, e);
        }
    for (int k = 0; k < NZ; k++) {
        double th = 2.0 * M_PI * k / NZ;
        double complex z = b->m + b->A * cos(th) + I * b->B * sin(th);
        for (int ch = 0; ch < b->nch; ch++) {
            double complex de;
            double complex e = composite(p->sc, ch, z + p->sc->x0, b->y + p->sc->y0,
                                         b->m + p->sc->x0, &de);
            double re = cabs(e) / b->emax[ch], rd = b->dmax[ch] > 0.0 ? cabs(de) / b->dmax[ch]
                                                   : cabs(de) > 0.0 ? INFINITY : 0.0;
            p->worst_e = fmax(p->worst_e, re), p->worst_d = fmax(p->worst_d, rd);
            if ((!(cabs(e) <= b->emax[ch] * (1.0 + 1e-12) + 1e-15) ||
                 !(cabs(de) <= b->dmax[ch] * (1.0 + 1e-12) + 1e-15)) && !p->bad++)
                snprintf(p->msg, sizeof p->msg,
                         "%s: row %.17g, ellipse about %.17g, A %.6g, B %.6g%s, channel %d at "
                         "%.6g%+.6gi: |e| %.10g against S %.10g, |e'| %.10g against D %.10g",
                         p->sc->name, b->y, b->m, b->A, b->B, b->fold ? " (fold)" : "", ch,
                         creal(z), cimag(z), cabs(e), b->emax[ch], cabs(de), b->dmax[ch]);
        }
    }
}

/* The scene's box reference with every bound checked; returns the probe's
 * findings (failing the test on a bound too small). */
static probe run(const scene *sc)
{
    aa_scene *s = aa_scene_new(sc->bg);
    assert_non_null(s);
    for (int l = 0; l < sc->n; l++) {
        const layer *g = &sc->L[l];
        assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
        assert_int_equal(aa_scene_move_to(s, -0.25, -0.25), AA_OK);
        assert_int_equal(aa_scene_line_to(s, 1.25, -0.25), AA_OK);
        assert_int_equal(aa_scene_line_to(s, 1.25, 1.25), AA_OK);
        assert_int_equal(aa_scene_line_to(s, -0.25, 1.25), AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
        aa_gradient gr = {g->kind, g->spread, {0}, {1.0 / W, 0, 0, 1.0 / H, 0, 0}, g->nstops,
                          g->stops};
        memcpy(gr.p, g->p, sizeof gr.p);
        assert_int_equal(aa_scene_set_gradient(s, &gr), AA_OK);
        if (g->lin)
            assert_int_equal(aa_scene_set_gradient_interpolation(s, AA_INTERPOLATE_LINEAR_RGB),
                             AA_OK);
        if (g->alpha < 1.0)
            assert_int_equal(aa_scene_set_alpha(s, g->alpha), AA_OK);
    }
    /* a layer of varying opacity off the view: a scene of one gradient
     * layer in sRGB and no other takes the path of several gradients only
     * with another gradient of varying opacity (truth.c, grad_mode) */
    static const aa_gradient_stop off[2] = {{0.0, {{1, 1, 1}}, 0.0}, {1.0, {{1, 1, 1}}, 1.0}};
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 2.0, 2.0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 2.5, 2.0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 2.5, 2.5), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    aa_gradient go = {AA_GRADIENT_LINEAR, AA_SPREAD_PAD, {16, 16, 20, 16, 0, 0},
                      {1.0 / W, 0, 0, 1.0 / H, 0, 0}, 2, off};
    assert_int_equal(aa_scene_set_gradient(s, &go), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    probe p;
    memset(&p, 0, sizeof p);
    p.sc = sc, p.worst_bp = p.near = INFINITY;
    aa_image ref, bound;
    aa_truth_stats stats;
    aa__truth_set_gen_probe(check_bound, &p);
    support_reference_part(s, W, H, sc->x0, sc->y0, sc->w, sc->h, NULL, &ref, &bound, &stats);
    aa__truth_set_gen_probe(NULL, NULL);
    print_message("%s: %ld bounds checked (%ld on the fold, %ld on real segments), "
                  "largest |e| / S %.4f, |e'| / D %.4f; the reference's largest bound %.2g\n",
                  sc->name, p.checked, p.folded, p.segments, p.worst_e, p.worst_d,
                  stats.max_bound);
    if (p.worst_bp < INFINITY)
        print_message("%s: the branch points at least %.4f of the ellipses' (1 on them), "
                      "rows from %.3g px of P*\n", sc->name, p.worst_bp, p.near);
    if (p.bad)
        fail_msg("%ld of the points too large; the first: %s", (long)p.bad, p.msg);
    assert_int_equal(p.skipped, 0);
    assert_true(p.checked > 0);
    if (!(stats.max_bound <= 1e-12))
        fail_msg("%s: the reference's bound %.3g is above 1e-12", sc->name, stats.max_bound);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
    return p;
}

static const aa_gradient_stop black_white[2] = {{0.0, {{0, 0, 0}}, 1.0},
                                                {1.0, {{1, 1, 1}}, 1.0}};
static const aa_gradient_stop clear_white[2] = {{0.0, {{1, 1, 1}}, 0.0},
                                                {1.0, {{1, 1, 1}}, 1.0}};
static const aa_gradient_stop three[3] = {{0.0, {{0.9, 0.05, 0.3}}, 0.4},
                                          {0.35, {{0.1, 0.8, 0.002}}, 1.0},
                                          {1.0, {{0.6, 0.3, 0.95}}, 0.7}};
static const aa_gradient_stop fade[2] = {{0.2, {{0.05, 0.7, 1.0}}, 0.0},
                                         {0.9, {{1.0, 0.2, 0.01}}, 1.0}};

/* One opaque layer over black: e is the layer's encoded colour, affine in
 * z (sRGB) or 1.055 v^(1/2.4) - 0.055 (linear light); the bounds' ratios
 * must come near 1 there. */
static void test_single(void **state)
{
    (void)state;
    static const scene sc[3] = {
        {"opaque ramp in sRGB", 3, 2, 2, 2, 1, {{0, 0, 0}}, 1,
         {{LIN, {2.5, 1.0, 6.0, 3.5}, 1.0, AA_SPREAD_PAD, 0, 2, black_white}}},
        {"opaque ramp in linear light", 3, 2, 2, 2, 1, {{0, 0, 0}}, 1,
         {{LIN, {2.5, 1.0, 6.0, 3.5}, 1.0, AA_SPREAD_PAD, 1, 2, black_white}}},
        {"white fading in", 3, 2, 2, 2, 1, {{0, 0, 0}}, 1,
         {{LIN, {2.5, 1.0, 6.0, 3.5}, 1.0, AA_SPREAD_PAD, 0, 2, clear_white}}},
    };
    for (int k = 0; k < 3; k++) {
        probe p = run(&sc[k]);
        if (!(p.worst_e > 0.85 && p.worst_d > 0.85))
            fail_msg("%s: the largest ratios %.4f and %.4f: the check is loose", sc[k].name,
                     p.worst_e, p.worst_d);
    }
}

/* Two and three translucent layers, stops of varying opacity, every
 * spread, sRGB and linear light mixed: the products of the composite's
 * terms (gen_bounds). */
static void test_layers(void **state)
{
    (void)state;
    static const scene sc[2] = {
        {"two layers in sRGB", 3, 2, 2, 2, 1, {{0.2, 0.5, 0.05}}, 2,
         {{LIN, {-1.0, 0.5, 9.0, 3.0}, 0.8, AA_SPREAD_REPEAT, 0, 3, three},
          {LIN, {2.0, 5.5, 3.5, 0.5}, 1.0, AA_SPREAD_PAD, 0, 2, fade}}},
        {"three layers, two in linear light", 3, 2, 1, 1, 8, {{0.01, 0.3, 0.6}}, 3,
         {{LIN, {0.5, 0.0, 7.0, 6.0}, 1.0, AA_SPREAD_PAD, 1, 3, three},
          {LIN, {8.0, 1.0, 5.0, 2.0}, 0.7, AA_SPREAD_REFLECT, 0, 2, fade},
          {LIN, {1.0, 5.0, 2.5, 4.0}, 0.6, AA_SPREAD_REPEAT, 1, 3, three}}},
    };
    for (int k = 0; k < 2; k++)
        run(&sc[k]);
}

/* Radial layers of nested circles: t = (b - sqrt(disc)) / a, the branch
 * points of sqrt(disc) off the row (gen_layer_tp's radial bounds), alone
 * over black (the focus, where t is a cone, in the pixels) and at alpha
 * 0.7 over a linear gradient in linear light. */
static void test_radial(void **state)
{
    (void)state;
    static const scene sc[2] = {
        {"an opaque radial gradient", 3, 2, 2, 2, 1, {{0, 0, 0}}, 1,
         {{RAD, {4.0, 3.0, 2.0, 4.6, 3.3, 0.0}, 1.0, AA_SPREAD_REFLECT, 0, 2, black_white}}},
        {"a radial gradient over a linear one", 3, 2, 2, 2, 8, {{0.3, 0.3, 0.3}}, 2,
         {{RAD, {4.0, 3.0, 3.5, 3.2, 2.6, 0.3}, 0.7, AA_SPREAD_REPEAT, 0, 3, three},
          {LIN, {0.5, 0.0, 7.0, 6.0}, 1.0, AA_SPREAD_PAD, 1, 3, three}}},
    };
    for (int k = 0; k < 2; k++)
        run(&sc[k]);
}

/* Rows within 1e-7 px of P* (the focus, 3e-6 px below the pixels' edge
 * y = 3, a cut of the rows' rule: rows from 7.1e-12 px of it; and a
 * focal circle of radius 0.3 whose P* = F - (fr / dr) D lies there, so
 * that p0 = q + (fr / dr) D is a sum, not q alone): there dmin = d0 -
 * d1^2 / (4 d2) in double rounds by more than itself, and the ellipses
 * about the pieces that end at x0 are drawn from the branch points'
 * distance sqrt(dmin / d2) (with that dmin, a row 2.6e-10 px away had
 * them inside its ellipse).  Each ellipse must keep them out
 * (branch_ellipse). */
static void test_focus(void **state)
{
    (void)state;
    static const scene sc[2] = {
        {"rows by the focus", 3, 2, 2, 2, 1, {{0, 0, 0}}, 1,
         {{RAD, {4.0, 3.0, 2.0, 4.6, 3.000003, 0.0}, 1.0, AA_SPREAD_PAD, 0, 2, black_white}}},
        {"rows by P* of a focal circle", 3, 2, 2, 2, 1, {{0, 0, 0}}, 1,
         {{RAD, {4.0, 3.0, 2.0, 4.6, 3.0000025499999996, 0.3}, 1.0, AA_SPREAD_PAD, 0, 2,
           black_white}}},
    };
    for (int k = 0; k < 2; k++) {
        probe p = run(&sc[k]);
        if (!(p.near < 1e-7))
            fail_msg("%s: the nearest row %.3g px from P*: the case is missed", sc[k].name,
                     p.near);
    }
}

/* Six layers, past the five read as 3^n composites: the composite folded
 * layer by layer (fold_bounds). */
static void test_fold(void **state)
{
    (void)state;
    static const scene sc = {"six layers, folded", 3, 2, 2, 2, 1, {{0.4, 0.4, 0.4}}, 6,
                             {{LIN, {0.3, 0.2, 2.9, 1.1}, 0.9, AA_SPREAD_REFLECT, 0, 3, three},
                              {LIN, {-1.0, 0.5, 9.0, 3.0}, 0.8, AA_SPREAD_REPEAT, 1, 3, three},
                              {LIN, {2.0, 5.5, 3.5, 0.5}, 1.0, AA_SPREAD_PAD, 0, 2, fade},
                              {LIN, {8.0, 1.0, 5.0, 2.0}, 0.7, AA_SPREAD_REFLECT, 1, 2, fade},
                              {LIN, {1.0, 5.0, 2.5, 4.0}, 0.6, AA_SPREAD_REPEAT, 0, 2, black_white},
                              {LIN, {0.5, 0.0, 7.0, 6.0}, 0.5, AA_SPREAD_PAD, 1, 3, three}}};
    probe p = run(&sc);
    assert_int_equal(p.folded, p.checked);
}

/* Two layers whose bound is nearly reached: an opaque black-to-white ramp
 * under white fading in at alpha 0.05 along the same axis, over black:
 * e = t + 0.05 t (1 - t), its terms t and 0.05 t of one sign and the
 * third, -0.05 t^2, small, at the ellipse's real end where |t| is largest
 * (the scenes of test_layers reach 0.03 to 0.17 of S, too little to show
 * a bound short by a few times); the ratios must come above 0.85 as the
 * single ramps' do. */
static void test_layers_reached(void **state)
{
    (void)state;
    static const scene sc = {"a ramp under white fading in at 0.05", 3, 2, 2, 2, 1, {{0, 0, 0}}, 2,
                             {{LIN, {2.5, 1.0, 6.0, 3.5}, 0.05, AA_SPREAD_PAD, 0, 2, clear_white},
                              {LIN, {2.5, 1.0, 6.0, 3.5}, 1.0, AA_SPREAD_PAD, 0, 2, black_white}}};
    probe p = run(&sc);
    if (!(p.worst_e > 0.85 && p.worst_d > 0.85))
        fail_msg("%s: the largest ratios %.4f and %.4f: the check is loose", sc.name, p.worst_e,
                 p.worst_d);
}

SUPPORT_MAIN(NULL, NULL, cmocka_unit_test(test_single), cmocka_unit_test(test_layers),
             cmocka_unit_test(test_radial), cmocka_unit_test(test_focus),
             cmocka_unit_test(test_fold), cmocka_unit_test(test_layers_reached))
