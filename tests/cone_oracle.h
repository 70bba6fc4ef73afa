/*
 * cone_oracle.h: the picture of a radial gradient of the cone case (the
 * focal circle not strictly inside the end circle) for the tests' known
 * answers (tests/test_gradient_cone_truth.c, tests/test_gradient_cone_filter.c),
 * derived from SVG 2's definition and the circles' geometry and sharing no
 * code with the harness.  A gradient is p[] = cx cy r fx fy fr in pixels
 * (the identity map).
 */
#ifndef AABENCH_TESTS_CONE_ORACLE_H
#define AABENCH_TESTS_CONE_ORACLE_H

/* A half-plane nx x + ny y + k >= 0 (long double: the areas' own rounding
 * stays far below the reference's). */
typedef struct co_half {
    long double nx, ny, k;
} co_half;

/* The half-planes bounding the painted region of p[] (at most 2), how
 * many (0: the whole plane, the end circle strictly inside the focal
 * one); *wedge 1 and the apex P into apex[] when the region is a wedge.
 * With r > fr the wedge from the external centre of similitude P = (r F -
 * fr C) / (r - fr) opening towards C, bounded by the circles' external
 * tangents (half-angle asin((r - fr) / |C - F|)); fr > r the same
 * opening away from C; |C - F| = |r - fr| (touching inside) the
 * half-plane beyond the line through P perpendicular to F C; r = fr the
 * strip of half-width r about the line F C. */
int co_region(const double p[6], co_half *hp, int *wedge, double apex[2]);

/* t at (x, y) by SVG 2's definition: the largest root, of radius fr + t
 * dr >= 0, of |q - F - t D| = fr + t dr (squared, in long double); NAN
 * where none qualifies (the point unpainted). */
double co_t(const double p[6], double x, double y);

/* The area of the rectangle [x0, x1] x [y0, y1] inside the nh
 * half-planes (Sutherland-Hodgman, then the shoelace formula). */
double co_clipped_area(double x0, double y0, double x1, double y1, const co_half *hp, int nh);

/* Where the half-plane's line meets the line x = at (col) or y = at: the
 * other coordinate into out[0]; 0 if parallel, else 1. */
int co_line_meet(const co_half *h, int col, double at, double *out);

/* Where the circle t = tau of p[] (radius fr + tau dr, if >= 0) meets the
 * line x = at (col) or y = at: the other coordinates into out[0, 1];
 * how many (0 or 2). */
int co_circle_meet(const double p[6], double tau, int col, double at, double *out);

/* The height where the circle t = tau touches the half-plane's line: the
 * foot of the perpendicular from its centre. */
double co_touch_y(const double p[6], double tau, const co_half *h);

#endif
