/*
 * oracle.h - an independent second derivation of the `crow` reference image,
 * the cut cone's volume, polygon areas by clipping, and cubic Bezier arcs'
 * points, curvature and arc length (at the end).
 *
 * The harness computes reference values of Crow's parabolic moire pattern by
 * its own quadrature; the tests compare it with this file's values, which are
 * derived only from patterns/README.md ("Coordinates and pixel values",
 * "Filters", `crow`) and share no code with the harness.
 *
 * Units: x, y in pattern units (the image shows [0,1]^2, y down); a pixel
 * (i, j) of a W x H image covers [i/W, (i+1)/W] x [j/H, (j+1)/H].  Filter
 * sizes R and S are in pixel units.  Any integers i, j are accepted: pixels
 * outside the image see the black background, as patterns/README.md defines it.
 *
 * Every function rejects invalid parameters (oracle_crow_valid() == 0, W or
 * H < 1, R or S not positive and finite): oracle_crow_point() returns 0 and
 * the others return NAN with *err = INFINITY.
 */
#ifndef AABENCH_TESTS_ORACLE_H
#define AABENCH_TESTS_ORACLE_H

typedef struct oracle_crow {
	int curves;  /* N, the number of arcs */
	double kmax; /* C, curvature coefficient of arc 0 */
	double gap0; /* spacing of arcs 0 and 1 at mid-height */
	double gap1; /* spacing of arcs N-2 and N-1 at mid-height */
} oracle_crow;

/* The defaults of patterns/README.md, `crow`: 96, 0.6, 4/256, 0.5/256. */
oracle_crow oracle_crow_defaults(void);

/* 1 if N is even and >= 2, all numbers finite and no two neighbouring arcs
 * touch anywhere on 0 <= y <= 1, else 0.  For C >= 0 this is exactly
 * the rule g_k - C/(4(N-1)) > 0 of patterns/README.md, `crow`; for C < 0 the
 * closest approach is at mid-height and g_k > 0 is required as well. */
int oracle_crow_valid(const oracle_crow *p);

/* The pattern at (x, y): 1 white, 0 black.  Black outside [0,1]^2.  A point
 * exactly on an arc may go either way. */
int oracle_crow_point(const oracle_crow *p, double x, double y);

/* Box-filter value of pixel (i, j) in closed form (alternating sum over arcs
 * of the exact area right of each arc inside the pixel), computed in long
 * double: within 1.1e-16 of a __float128 reference on every pixel tried. */
double oracle_crow_box(const oracle_crow *p, int W, int H, int i, int j);

/* Tent (tent:r=R) and untruncated Gaussian (gauss:s=S) values of pixel
 * (i, j), by brute force: the integral along x in closed form, the integral
 * along y by composite Simpson on a fine uniform grid.  *err (may be NULL)
 * receives an upper estimate of this function's own error: the difference
 * between Simpson on n and 2n panels, plus rounding, plus (Gaussian) the
 * filter mass left out by truncation at 9 S.  For the default pattern on
 * 64 x 64 and 256 x 256 images *err is at most 3.2e-11 (tent R = 0.5, 1;
 * Gaussian S = 0.5, 1), at about 0.5 ms (tent) and 1-3 ms (Gaussian) per
 * pixel, 13 ms at worst. */
double oracle_crow_tent(const oracle_crow *p, int W, int H, int i, int j,
			double R, double *err);
double oracle_crow_gauss(const oracle_crow *p, int W, int H, int i, int j,
			 double S, double *err);

/* Fraction of the cone filter's volume (cone:r=R) beyond a line at distance
 * delta R from its centre:
 *   (1/pi) (acos delta - 2 delta sqrt(1 - delta^2)
 *           + delta^3 ln((1 + sqrt(1 - delta^2)) / delta)),
 * 1 - C(-delta) for delta < 0.  Derived in polar coordinates (the
 * derivation is in tests/test_cone.c, which checks it by quadrature). */
double oracle_cone_cut(double delta);

/* ---- the hexagon display ----
 *
 * Vertex v of the hexagon of radius r whose vertex 0 is at `angle` degrees,
 * worked out independently of hexagon.c: vertex 0 from the angle, then each
 * next vertex by the rotation matrix [c -s; s c] of 60 degrees (y down, so
 * positive angles turn clockwise on the screen). */
void oracle_hexagon_vertex(double r, double angle, int v, double *dx, double *dy);

/* ---- polygons: areas by clipping ----
 *
 * The area of a polygon inside a pixel or another convex polygon, by
 * Sutherland-Hodgman clipping and the shoelace formula: a second way to the
 * box value of scenes of straight edges, sharing nothing with the scene
 * model, the reference or the methods.  Clipping by a half-plane is exact
 * for any polygon whose part inside is one piece (convex ones always);
 * oracle_poly_intersect needs q convex.  A result with more than
 * ORACLE_POLY_MAX vertices aborts. */
#define ORACLE_POLY_MAX 64

typedef struct oracle_poly {
    int n;
    double x[ORACLE_POLY_MAX], y[ORACLE_POLY_MAX];
} oracle_poly;

/* p clipped to the half-plane a x + b y <= c. */
oracle_poly oracle_poly_clip(const oracle_poly *p, double a, double b, double c);
/* p clipped to the inside of convex q (either orientation). */
oracle_poly oracle_poly_intersect(const oracle_poly *p, const oracle_poly *q);
/* p with x scaled by sx and y by sy (pattern units to pixels: W, H). */
oracle_poly oracle_poly_scaled(const oracle_poly *p, double sx, double sy);
/* The area enclosed (shoelace; the absolute value, either orientation). */
double oracle_poly_area(const oracle_poly *p);
/* The area of p inside the rectangle [x0, x1] x [y0, y1]. */
double oracle_poly_area_in_rect(const oracle_poly *p, double x0, double y0, double x1, double y1);

/* ---- cubic Bezier arcs, control points c = x0 y0 x1 y1 x2 y2 x3 y3 ---- */

/* The point B(t) and its derivative B'(t), from the Bernstein form. */
void oracle_cubic_at(const double c[8], double t, double *x, double *y, double *dx, double *dy);
/* The signed curvature (x' y'' - y' x'') / |B'|^3 at t. */
double oracle_cubic_curvature(const double c[8], double t);
/* The arc length from t = a to b, by GSL's adaptive Gauss-Kronrod (61
 * points) of |B'(t)| to 1e-13 relative; NAN if it cannot say so. */
double oracle_cubic_length(const double c[8], double a, double b);

/* The perimeter of the ellipse of semi-axes a and b, by the Gauss-Kummer
 * series P = pi (a + b) sum_n binom(1/2, n)^2 h^n, h = ((a - b)/(a + b))^2,
 * summed until a term is below 1e-20 of the sum. */
double oracle_ellipse_perimeter(double a, double b);

/* A parametric curve for the distance oracle: its point (x, y) at t and a
 * direction (dx, dy) along it there (the tangent or any nonzero multiple
 * of it; at a cusp the limit direction). */
typedef void (*oracle_curve_fn)(const void *ctx, double t, double *x, double *y, double *dx,
                                double *dy);
/* The least distance from p to the curve on t0 .. t1 at the t where
 * p - C(t) is perpendicular to the direction (sign changes of
 * (p - C) . D at n samples, each bisected 60 times), and to its ends when
 * `ends`; without `ends`, *unsure is set when p lies on an end's normal
 * line (within 1e-7) no farther than h + 1e-7 from it, where a butt end's
 * region cannot be told.  INFINITY if there is no foot. */
double oracle_curve_feet(oracle_curve_fn at, const void *ctx, double t0, double t1, int n,
                         double px, double py, int ends, double h, int *unsure);

#endif
