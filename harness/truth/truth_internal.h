/*
 * truth_internal.h: what the integration paths of the reference share
 * (truth.c: QAG and the image; truth_crowd.c: crowded pixels;
 * truth_gauss.c: the Gaussian's fixed rule on panels; their local pieces
 * in truth_local.c).  Private to harness/truth.
 */
#ifndef AA_TRUTH_INTERNAL_H
#define AA_TRUTH_INTERNAL_H

#include "truth.h"

#include <gsl/gsl_poly.h>
#include <math.h>

/* A local piece in coordinates relative to the pixel centre (uc, vc):
 * y(t) - vc = y0 + t (by + t (ay + t dy)), x(t) - uc likewise (dy = dx = 0
 * but for cubics, `cubic` set).  A conic piece (`conic` set; ax .. dy are
 * 0) is, in its angle a from a0 to a1 (the piece's s0, s1),
 *     y(a) - vc = ey - er cos a,   x(a) - uc = x0 + ea cos a + eb sin a,
 * x0 being the ellipse centre's x, and top = ey - er, bot = ey + er the
 * heights of its extremes: at height s, with c = cos a = (ey - s)/er,
 *     1 - c = (s - top)/er,  1 + c = (bot - s)/er,
 * each a difference of nearby numbers taken directly, so that next to a
 * turning point, where x moves like the square root of the height, the
 * small factor under the root carries no rounding of c's. */
typedef struct local_piece {
    long double y0, y1, x0, ax, bx, ay, by, dx, dy;
    long double ey, er, ea, eb, top, bot, a0, a1;
    int dir, layer, cubic, conic;
    /* An offset piece (`offset` set; x0 .. dy are 0 but y0, y1): its
     * crossing is solved for on the scene's piece src in long double
     * (aa__offset_solve) at the absolute height vc + s, less uc; oscale is
     * the size of its absolute coordinates (the crossing's rounding). */
    int offset;
    const aa_piece *src;
    long double uc, vc, oscale;
    /* the last crossing (NaN: none), the next one's start: its parameter,
     * its relative height and dy/dt there */
    double hint, hint_s, hint_slope;
    /* on the rows being integrated (truth.c, integrate_intervals): -1 if
     * wholly left of the window, 1 if wholly right (no crossing solved
     * for), 0 if not known so */
    int side;
    long double end_s, end_t, end_x; /* the last row end it was solved at (NaN: none) */
} local_piece;

/* The piece p relative to the centre (uc, vc), in extended precision. */
void truth_set_local(local_piece *q, const aa_piece *p, long double uc, long double vc);
/* The parameter of q where it meets the line at relative height s, in
 * [0, 1]: the cancellation-free root of a quadratic, or for a cubic the one
 * root of y(t) = s, bracketed and polished by Newton in long double; for a
 * conic (a - a0)/(a1 - a0), a its angle there. */
long double truth_t_at(const local_piece *q, long double s);
/* A conic's crossing at relative height s, less its x0 (the centre's x):
 * ea c + eb sqrt((1 - c)(1 + c)), the factors as above (clamped at 0 a
 * rounding outside the ellipse's rows). */
static inline long double truth_conic_part(const local_piece *q, long double s)
{
    long double lo = (s - q->top) / q->er, hi = (q->bot - s) / q->er;
    long double c = (q->ey - s) / q->er, r = lo * hi;
    return q->ea * c + q->eb * sqrtl(r > 0 ? r : 0);
}
/* Where offset piece q lies on the rows [lo, hi] (relative) against the
 * window [-R, R] along x: -1 if wholly left of -R, 1 if wholly right of R,
 * by a margin above the rounding of its crossings; else 0. */
int truth_offset_side(local_piece *q, double lo, double hi, double R);
/* The crossing of q with the line at relative height s, less its x0
 * (inline: the integrand's inner loop). */
long double truth_offset_part(const local_piece *q, long double s);
static inline long double truth_crossing_part(const local_piece *q, long double s)
{
    if (q->conic)
        return truth_conic_part(q, s);
    if (q->offset)
        return truth_offset_part(q, s);
    long double t = truth_t_at(q, s);
    if (q->cubic)
        return t * (q->bx + t * (q->ax + t * q->dx));
    return t * (q->bx + t * q->ax);
}
/* Whether piece p turns at its top (*lo) and bottom (*hi): an end where
 * dy/dt = 0, where x - x_end grows like sqrt(|y - y_end|) (quadratic and
 * cubic arcs split at the roots of y'; conic pieces ending at an extreme of
 * the ellipse, angle 0 or pi). */
void truth_turns(const aa_piece *p, int *lo, int *hi);
/* The roots in (lo, hi), ascending, at which the polynomial p[0] + p[1] x
 * + ... + p[d] x^d (d <= 6) changes sign, by bisection in long double
 * between the roots of its derivative (found the same way); a root of even
 * multiplicity (a touch) is not one.  Returns how many (at most d). */
int truth_sign_roots(const long double *p, int d, long double lo, long double hi,
                     long double *r);
/* A conic piece's part in the rows [lo, hi] (relative heights, inside the
 * piece's) as a rational quadratic: with the angle a = am + 2 atan(t),
 * t in [-T, T] (T = tan((a_hi - a_lo)/4) <= 1),
 *     x - uc = (qx[0] + qx[1] t + qx[2] t^2) / (1 + t^2), y - vc likewise
 * (qy).  Returns 0 if the part is empty. */
typedef struct conic_rational {
    long double qx[3], qy[3], T, am;
} conic_rational;
int truth_conic_rational(const local_piece *q, long double lo, long double hi,
                         conic_rational *r);
/* qsort order of doubles. */
int truth_cmp_double(const void *a, const void *b);
/* Radial filters: the heights (relative to vc, at most 4) where piece p
 * crosses the circle of radius R around (uc, vc); returns how many. */
int truth_circle_heights(const aa_piece *p, double uc, double vc, double R,
                         gsl_poly_complex_workspace *poly, double out[4]);

/* The size of q's numbers, |x0| + |bx| + |ax| + |dx| + |ea| + |eb|: its
 * crossing in long double is off by a few long double epsilons of it (the
 * sum of terms that large cancels to a crossing near the centre). */
double truth_piece_scale(const local_piece *q);
/* Radial filters: the height (relative, inside (lo, hi), not 0) where the
 * local piece q passes closest to the pixel's centre, if it does so inside
 * the circle of radius R; NaN if not.  There the inner integral changes on
 * the scale of that distance (the row integral is singular at the centre). */
double truth_nearest_height(const local_piece *q, double lo, double hi, double R);

/* QAG is asked for this absolute accuracy per pixel and channel: above its
 * rounding floor (50 eps times the integral of |f|, about 1e-14 here) and
 * well below AA_TRUTH_BOUND. */
#define TRUTH_EPSABS 2e-13

/* ------------------------------------------------------------------------
 * Crowded pixels: the outer integral one piece at a time (truth_crowd.c)
 * ------------------------------------------------------------------------ */

/* Pixels whose window holds more local pieces than this take the crowd
 * path.  Up to it the sum over spans (truth.c) is integrated as a whole,
 * with the heights where pieces meet as breakpoints up to TRUTH_MAX_PAIRS
 * pieces; between the two, a window in which two pieces cross (found by
 * the crowd path's sweep, which stops there if none do) goes to the crowd
 * path too: QAG's bisection alone missed such kinks (60 thin crossing
 * quadrilaterals: 1.7e-8 off at a bound of 1e-14; tests/test_area.c,
 * test_crowded_crossings).  72 is the most the patterns' default views
 * reach at 256 x 256 (star's centre under tent, cone and gauss, where the
 * spokes only meet at their ends): their references are as they were. */
#define TRUTH_CROWD 72

typedef struct crowd_piece crowd_piece;
typedef struct crowd_node crowd_node;
typedef struct crowd_event crowd_event;
typedef struct crowd_seg crowd_seg;

/* One thread's workspace for crowded pixels: grown as needed, kept from
 * pixel to pixel (zeroed: empty). */
typedef struct crowd_worker {
    crowd_piece *cp;
    crowd_node *node; /* the order along x, one slot per piece */
    size_t cap_cp;
    int *wl; /* the winding numbers left of each piece in the order */
    crowd_event *heap;
    size_t nheap, cap_heap;
    crowd_seg *seg;
    size_t nseg, cap_seg;
    double *kink; /* the pieces' own split heights */
    size_t nkink, cap_kink;
    int *touched, *meet, *dirty, *scratch, *scratch2;
    size_t cap_meet, cap_dirty, cap_scratch;
    long double *xs; /* x of each piece at a batch's height */
    int *wind;
    int nl;
    gsl_poly_complex_workspace *poly;
    /* crowd_events: the sweep's event heights (relative), and whether they
     * are being kept */
    double *ev;
    size_t nev, cap_ev;
    int record;
} crowd_worker;

void crowd_free(crowd_worker *cw);
/* crowd_pixel's answer when asked for crossed windows only and no two
 * pieces cross inside this one (not an aa_status). */
#define CROWD_DECLINED (-1)
/* The value (channels) and error bound of pixel (uc, vc), whose window
 * [-R, R]^2 around the centre holds the strip's n local pieces; if
 * only_crossed, CROWD_DECLINED (nothing written) unless two of them cross
 * inside it. */
int crowd_pixel(crowd_worker *cw, const aa_scene *scene, const aa_strip *strip,
                const aa_filter *f, double uc, double vc, const aa_piece *const *local, size_t n,
                int grey, int only_crossed, double *value, double *bound);
/* The heights (relative to vc, in (-R, R), ascending, possibly repeated)
 * of every event of crowd_pixel's sweep over the window: where pieces
 * begin, end, cross the window's sides and where two neighbours in the
 * order along x meet (which finds every crossing inside the window), into
 * *hs (the worker's, valid until its next use), their count into *nh; no
 * integration.  Gradient paint takes these as breakpoints of the sum over
 * spans in crowded windows (truth.c). */
int crowd_events(crowd_worker *cw, const aa_scene *scene, const aa_strip *strip,
                 const aa_filter *f, double uc, double vc, const aa_piece *const *local, size_t n,
                 const double **hs, size_t *nh);

/* ------------------------------------------------------------------------
 * The Gaussian: one fixed rule on panels shared by the rows
 * ------------------------------------------------------------------------ */

#define GK_N 21 /* Gauss-Kronrod 10/21 (GSL's qk21) */
#define GK_S 24 /* stored per panel and column: the nodes, then zeros */
#define GL_N 10
/* Pieces steeper than this (|dx/dy|) make G vary on a scale below s and
 * leave the panel to QAG: measured, |K21 - G10| on a panel of 2 s grows
 * from 8e-16 at slope 0.6 to 3e-14 at 1 and 2e-12 at 1.5 (s = 0.5). */
#define FAST_SLOPE 1.0
/* A fixed-rule pixel whose bound exceeds this goes to QAG instead. */
#define FAST_LIMIT (AA_TRUTH_BOUND / 4)
/* Slack on x extents and on the tests for meeting pieces, in pixels. */
#define FAST_TOL 1e-9
/* Pairs tested per piece before a crowd of overlapping pieces is simply
 * left to QAG. */
#define FAST_PAIRS 64
/* Per-thread panel buffers above this many bytes (22 MB for a colour image
 * 4096 wide, s = 0.5): QAG for every pixel. */
#define FAST_MAX_BYTES ((size_t)256 << 20)

enum { PANEL_CONST = 0, PANEL_NODES = 1, PANEL_BAD = 2 };

/* Taylor terms of the tabulated cdf: with steps of at most 1/32 standard
 * deviation, 7 terms leave a truncation error below 1e-18 (6 leave 4e-16;
 * measured against erfcl over |z| <= 10.5: largest error 1.1e-16, the
 * rounding of values near 1). */
#define CDF_TERMS 7
#define CDF_STEPS 32
_Static_assert(CDF_TERMS == 7, "node_crossings writes seven powers");

/* What every thread shares: the rule, the panel grid and the weight tables.
 * Panels have height h = num/den pixels (one of the two is 1) and panel p
 * covers [p h, (p+1) h].  Row j has phase j mod num; its window is covered
 * by np[phase] panels from base(j) + r0[phase], base(j) = (j div num) den. */
typedef struct gauss_plan {
    double x[GK_N], wk[GK_N], wg[GK_N]; /* on [-1, 1], x ascending */
    int num, den, np_max;
    int *np, *r0;         /* per phase */
    double *a, *d, *mass; /* [phase][k][node], [phase][k] */
    double R, lost, peak, s, inv_s;
    double node_err; /* (h + R/2) R / s^2: node heights in the weights */
    /* The cdf in z = t/s, tabulated at z_k = k dz, |k| <= kt, as Phi(z_k)
     * and the Taylor coefficients Phi^(n)(z_k)/n!, n = 1..CDF_TERMS, with
     * dz = 1/(s M): a column to the right is M entries down, so one offset
     * from the grid serves every column a crossing is near. */
    int M;
    long kt;
    double *cdf_tab; /* [2 kt + 1][CDF_TERMS + 1] */
} gauss_plan;

/* A piece meeting the current panel, in extended precision (absolute
 * coordinates), with the x extent of its part in the panel and the columns
 * whose window that extent meets (c0 > c1: none). */
typedef struct band_piece {
    local_piece q;
    const aa_piece *p; /* the scene's piece (meetings of cubics) */
    double xmin, xmax;
    int c0, c1;
} band_piece;

typedef struct node_cross {
    double x;             /* rounded: for sorting and searching */
    int k;                /* band piece */
    int c0, c1;           /* its columns */
    long base;            /* cdf table row for column 0 (x - 1/2 near base/M) */
    double pw[CDF_TERMS]; /* powers of the offset from that row, in z */
} node_cross;

typedef struct key_index {
    double key;
    size_t k;
} key_index;

/* One thread's state for the fixed rule: a ring of `ring` panels, each
 * with per column a kind, the most crossings one node saw, the constant
 * colour (PANEL_CONST) or the inner integral at the nodes (PANEL_NODES). */
typedef struct panel_worker {
    const gauss_plan *plan;
    const aa_filter *f;
    const aa_scene *scene;
    aa_strip *strip;
    int w, nc, ring;
    long lo, hi;
    int valid;
    unsigned char *kind;   /* [ring][w] */
    unsigned short *nnear; /* [ring][w] */
    double *cst;           /* [ring][w][nc] */
    double *g;             /* [ring][w][nc][GK_S] */
    int *near_diff, *bad_diff, *runs;
    size_t nruns;
    size_t *row_cells; /* first cell of each panel of the current row */
    band_piece *bp;
    node_cross *cr; /* [GK_N][cap]: the crossings of each node line */
    double *col;    /* [GK_N][cap][3]: the colour after each */
    size_t nx[GK_N], at[GK_N][2];
    key_index *keys;
    size_t *act;
    int *tail_c0;
    size_t cap;
    int *wind;
    double col_empty[3];
} panel_worker;

/* The plan (rule, panel grid, weight tables) of a Gaussian filter. */
int plan_init(gauss_plan *pl, const aa_filter *f);
void plan_free(gauss_plan *pl);
/* Bytes of one thread's panel buffers for an image w wide of nc channels. */
size_t fast_bytes(const gauss_plan *pl, int w, int nc);
int fast_init(panel_worker *fs, const gauss_plan *pl, const aa_filter *f,
              const aa_scene *scene, int w);
void fast_free(panel_worker *fs);
/* Make the panels row j needs; *phase receives its phase. */
int fast_row(panel_worker *fs, int j, int *phase);
/* Pixel (i, j) by the fixed rule: 1 with value and bound set, 0 if the
 * pixel must go to QAG. */
int fast_pixel(const panel_worker *fs, int j, int phase, int i, int grey, double *value,
               double *bound);

#endif /* AA_TRUTH_INTERNAL_H */
