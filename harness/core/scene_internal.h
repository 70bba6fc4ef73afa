/*
 * scene_internal.h: the scene's private layout and the cubic helpers,
 * shared by scene.c, scene_piece.c and strip.c only.
 */
#ifndef AA_SCENE_INTERNAL_H
#define AA_SCENE_INTERNAL_H

#include "core.h"
#include "path.h"

#include <stdlib.h>
#include <string.h>

typedef struct aa_scene_group {
    int parent;
    double opacity;
} aa_scene_group;

/* A clip region (aa_scene_clip_begin): the union of its member layers
 * [first, first + count), each where its fill rule holds and it is inside
 * its own clip (gate), intersected with the clip `within` (-1: none);
 * depth: the longest chain of clips it consults, itself counted. */
typedef struct aa_scene_clip {
    int first, count, within, depth;
} aa_scene_clip;

/* A gradient paint (aa_scene_set_gradient): its definition with its own
 * stops, the inverse of its map (scene to gradient coordinates), and per
 * stop its sRGB-encoded colour and opacity (enc[4 k .. 4 k + 3]); its
 * interpolation space (aa_scene_set_gradient_interpolation). */
typedef struct aa_scene_gradient {
    aa_gradient g;
    aa_gradient_stop *stops;
    double *enc;
    double inv[6];
    int cone; /* radial, the focal circle not strictly inside the end circle */
    int interpolation; /* aa_interpolation: AA_INTERPOLATE_SRGB or _LINEAR_RGB */
    char source[192]; /* where it was given (aa_scene_set_gradient_source), or "" */
} aa_scene_gradient;

/* The t of gradient sg at scene point (x, y), before the spread (NaN
 * where a radial gradient of the cone case has no circle through the
 * point: the layer paints nothing there), and
 * its colour: sRGB-encoded channels and opacity at spread-mapped t
 * (scene.c). */
double aa__gradient_t(const aa_scene_gradient *sg, double x, double y);
void aa__gradient_paint(const aa_scene_gradient *sg, double t, double out[4]);
double aa__gradient_spread(int spread, double t);
const aa_scene_gradient *aa__scene_layer_paint(const aa_scene *s, int layer);

struct aa_scene {
    aa_rgb background;
    int nlayers, current;
    size_t caplayers;
    aa_rgb *colour;
    aa_fill_rule *rule;
    /* translucency (aa_scene_set_alpha, aa_scene_group_begin): per layer
     * its alpha, its colour sRGB-encoded, and its innermost group (-1: none) */
    double *alpha;
    aa_rgb *encoded;
    int *group;
    aa_scene_group *groups;
    int ngroups, capgroups, open_group, translucent;
    /* clips (aa_scene_clip_begin): per layer the clip gating it (-1:
     * none) and the clip it is a member of (-1: a layer that paints) */
    int *gate, *member;
    aa_scene_clip *clips;
    int nclips, capclips, open_clip;
    /* gradients (aa_scene_set_gradient): per layer the index of its
     * gradient (-1: its colour) */
    int *paint;
    aa_scene_gradient *grads;
    int ngrads, capgrads;

    aa_edge *edges;
    size_t nedges, capedges;
    size_t *contour; /* first edge of each contour, then a sentinel */
    size_t ncontours, capcontours;

    /* path being built */
    int open;
    double startx, starty, penx, peny;
    size_t contour_first;

    int finished, grey, has_bounds;
    aa_piece *pieces;
    size_t npieces;
    double bx0, by0, bx1, by1;

    /* y index: bin b covers [iy0 + b ihb, iy0 + (b+1) ihb] */
    double iy0, ihb;
    size_t nbins;
    size_t *bin_start;   /* nbins + 1 */
    uint32_t *bin_items; /* piece indices */

    /* a field scene (aa_scene_set_field): no layers, the field everywhere */
    const aa_field_type *field;
    double fparam[AA_FIELD_MAX_PARAMS];
    int fnparam;
    double fmap[4]; /* sx, sy, tx, ty: the field's (x, y) is at (sx x + tx, sy y + ty) */

    /* stroke sources (aa_scene_stroke), in the order of their layers */
    aa_stroke_source *strokes;
    size_t nstrokes, capstrokes;
};

/* scene_source.c: free the sources; copy s's into t with their maps
 * composed with x' = sx x + tx, y' = sy y + ty; renumber them after a
 * front layer was inserted (clip to the unit square). */
void aa__scene_strokes_free(aa_scene *s);
int aa__scene_strokes_copy(const aa_scene *s, aa_scene *t, double sx, double sy, double tx,
                           double ty);
void aa__scene_strokes_shift(aa_scene *s, int by);
/* Room for `need` sources; a copy of path, style (its dashes) and map as
 * the source of `layer` into *d (on failure *d is empty). */
int aa__scene_strokes_reserve(aa_scene *s, size_t need);
int aa__stroke_source_copy(aa_stroke_source *d, const aa_path *path, const aa_stroke_style *st,
                           const double m[6], int layer);

/* Call visit(ctx, piece) once for every piece whose closed y range meets
 * [ya, yb]; returns the number of visits that returned non-zero. */
typedef int (*aa__visit)(void *ctx, const aa_piece *p);
size_t aa__scene_gather(const aa_scene *s, double ya, double yb, aa__visit visit, void *ctx);

/* Append an edge from the pen (quad: 0 line, 1 quadratic, 2 cubic, whose
 * second control point is (c2x, c2y)). */
int aa__add_edge3(aa_scene *s, double cx, double cy, double c2x, double c2y, double x, double y,
                  int quad);
/* The cubic's power basis from control points a, c, d, b of one coordinate:
 * v(t) = a + t (k1 + t (k2 + t k3)). */
static inline void aa__cubic_basis(double a, double c, double d, double b, double *k1,
                                   double *k2, double *k3)
{
    *k1 = 3.0 * (c - a);
    *k2 = 3.0 * (a - 2.0 * c + d);
    *k3 = (b - a) + 3.0 * (c - d);
}

/* The roots of k1 + 2 k2 t + 3 k3 t^2 inside (0, 1), ascending
 * (scene_piece.c). */
int aa__cubic_turns(double k1, double k2, double k3, double t[2]);

/* Roots of c[0] + c[1] t + c[2] t^2 + c[3] t^3: the one in [a, b] given
 * values fa, fb of opposite signs there (c monotone on it), and all of
 * those in [lo, hi] (ascending, at most 3), polished to full precision
 * (scene_piece.c). */
double aa__poly3_bracketed(const double c[4], double a, double b, double fa, double fb);
int aa__poly3_roots(const double c[4], double lo, double hi, double *t);

/* A conic piece's x extent for s in [sa, sb] (within [s0, s1]): its ends
 * (the piece's own end points at s0 and s1) and the x turns between
 * (scene_piece.c). */
void aa__conic_xrange(const aa_piece *p, double sa, double sb, double *xmin, double *xmax);
/* The angle s of a conic piece at height y (clamped to [s0, s1]). */
double aa__conic_s_at(const aa_piece *p, double y);
/* aa_scene_arc_to's checks of an arc from the pen (px, py) (scene.c). */
int aa__arc_check(double px, double py, double cx, double cy, double ux, double uy, double vx,
                  double vy, double t0, double t1, double x, double y);

aa_scene *aa__scene_transform(const aa_scene *s, double sx, double sy, double tx, double ty,
                              double hint);

/* Sorts for what the pieces' path order gives nearly sorted one way or the
 * other (a line's crossings, a band's pieces: a contour crosses a line
 * going one way along x and, coming back, the other, as a stroke's outline
 * does; neighbours out of order here and there): AA__NEAR_SORT(name, type,
 * cmp) defines static void name(type *a, size_t n), cmp a qsort comparison
 * under which elements that compare equal are alike.  In chunks of 16, each
 * reversed if it falls from end to end and sorted by insertion (nearly in
 * order then: few moves), a chunk in order with the one before joined to
 * it, and the runs so found merged in pairs, in buffers on the stack up to
 * 512 elements and allocated past that (qsort if they cannot be had). */
#define AA__NEAR_CHUNK 16
#define AA__NEAR_STACK 512
#define AA__NEAR_SORT(name, type, cmp)                                                          \
    static void name(type *a, size_t n)                                                          \
    {                                                                                            \
        type stmp[AA__NEAR_STACK], *tmp = stmp;                                                  \
        size_t srun[AA__NEAR_STACK / AA__NEAR_CHUNK + 2], *run = srun, nr = 0;                  \
        if (n > AA__NEAR_STACK) {                                                                \
            tmp = malloc(n * sizeof *tmp);                                                       \
            run = malloc((n / AA__NEAR_CHUNK + 2) * sizeof *run);                                \
            if (!tmp || !run) {                                                                  \
                free(tmp);                                                                       \
                free(run);                                                                       \
                qsort(a, n, sizeof *a, cmp);                                                     \
                return;                                                                          \
            }                                                                                    \
        }                                                                                        \
        for (size_t i = 0; i < n; i += AA__NEAR_CHUNK) {                                         \
            size_t m = n - i < AA__NEAR_CHUNK ? n - i : AA__NEAR_CHUNK;                          \
            type *q = a + i;                                                                     \
            if (cmp(&q[0], &q[m - 1]) > 0)                                                       \
                for (size_t lo = 0, hi = m - 1; lo < hi; lo++, hi--) {                           \
                    type t = q[lo];                                                              \
                    q[lo] = q[hi], q[hi] = t;                                                    \
                }                                                                                \
            for (size_t k = 1; k < m; k++) {                                                     \
                type v = q[k];                                                                   \
                size_t at = k;                                                                   \
                while (at > 0 && cmp(&q[at - 1], &v) > 0) {                                      \
                    q[at] = q[at - 1];                                                           \
                    at--;                                                                        \
                }                                                                                \
                q[at] = v;                                                                       \
            }                                                                                    \
            if (i == 0 || cmp(&a[i - 1], &a[i]) > 0)                                             \
                run[nr++] = i;                                                                   \
        }                                                                                        \
        run[nr] = n;                                                                             \
        while (nr > 1) {                                                                         \
            size_t m = 0;                                                                        \
            for (size_t r = 0; r < nr; r += 2) {                                                 \
                size_t lo = run[r], mid = run[r + 1], hi = r + 2 <= nr ? run[r + 2] : n;         \
                run[m++] = lo;                                                                   \
                if (r + 1 >= nr)                                                                 \
                    continue;                                                                    \
                /* [lo, mid) copied out, merged with [mid, hi) */                                \
                memcpy(tmp, &a[lo], (mid - lo) * sizeof *a);                                     \
                size_t x = 0, nx = mid - lo, y = mid, o = lo;                                    \
                while (x < nx && y < hi)                                                         \
                    a[o++] = cmp(&a[y], &tmp[x]) < 0 ? a[y++] : tmp[x++];                        \
                while (x < nx)                                                                   \
                    a[o++] = tmp[x++];                                                           \
            }                                                                                    \
            nr = m;                                                                              \
            run[nr] = n;                                                                         \
        }                                                                                        \
        if (tmp != stmp) {                                                                       \
            free(tmp);                                                                           \
            free(run);                                                                           \
        }                                                                                        \
    }

#endif
