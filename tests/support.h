/*
 * support.h: what the tests share besides scenes (scenes.h) and known
 * answers (oracle.h): rendering a method or the reference of a view,
 * comparing images, running the command under test, temporary folders
 * and files.  Failures inside these helpers fail the running test
 * (cmocka), with the message of the library where there is one.
 */
#ifndef AA_TEST_SUPPORT_H
#define AA_TEST_SUPPORT_H

#include "bench.h"
#include "oracle.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <sys/types.h>

/* ---- the test program ---- */

/* A test program's main (expanded after the tests, where cmocka.h is
 * included): the cmocka tests given (cmocka_unit_test(name), ...) run as
 * one group with the group set-up and tear-down (NULL: none); the exit
 * status is the number of tests that failed. */
#define SUPPORT_MAIN(setup, teardown, ...)                                                         \
    int main(void)                                                                                 \
    {                                                                                              \
        const struct CMUnitTest tests[] = {__VA_ARGS__};                                           \
        return cmocka_run_group_tests(tests, setup, teardown);                                     \
    }

/* ---- rendering ---- */

/* The status of parsing the method spec (aa_method_parse) under the filter
 * spec `filter` (NULL: the box; a filter that does not parse fails the
 * test); the spec into *spec (may be NULL). */
int support_parse_method(const char *method, const char *filter, aa_spec *spec);

/* What to render: a w x h image at time t (frames) moving (vx, vy) pixels a
 * frame, through the filter spec `filter` (NULL: the box).  `seed` and
 * `frame_only` go to the job (aabench.h, aa_job).  `threads`: for a method
 * at least 1 (<= 0 counts as 1); for the reference <= 0 is OpenMP's
 * default. */
typedef struct support_view {
    int w, h;
    double t, vx, vy;
    const char *filter;
    uint64_t seed;
    int threads;
    int frame_only;
} support_view;

/* Render the method spec on a scene in pattern units.  Returns the status
 * of parsing the spec against the filter or of the render (the message in
 * aa_last_error()); the image is allocated w x h x 3 only on AA_OK.
 * `c` may be NULL. */
int support_render_view(const char *method, const aa_scene *scene, const support_view *v,
                        aa_image *out, aa_counters *c);
/* The same, failing the test (with the method's message) unless it renders. */
void support_render_must(const char *method, const aa_scene *scene, const support_view *v,
                         aa_image *out, aa_counters *c);
/* The common case: still, seed 1, through `filter` (NULL: the box). */
void support_render(const char *method, const aa_scene *scene, const char *filter, int w,
                    int h, int threads, aa_image *out, aa_counters *c);

/* The reference (aa_truth_render) of a scene in pattern units placed for
 * the view (`seed` and `frame_only` unused); `bound` (1 channel) and
 * `stats` may be NULL. */
void support_reference(const aa_scene *scene, const support_view *v, aa_image *out,
                       aa_image *bound, aa_truth_stats *stats);
/* The scene mapped (x' = (sw x - x0) / w, y' likewise) so that the pixels
 * [x0, x0 + w) x [y0, y0 + h) of its sw x sh view make a w x h view of
 * their own: the same picture on the same pixel squares, the rest of it
 * still there for a filter's cells that reach beyond them (free it). */
aa_scene *support_scene_part(const aa_scene *s, int sw, int sh, int x0, int y0, int w, int h);
/* The reference of those pixels alone, as support_reference of that view
 * (still, one thread): a check of a few pixels need not integrate the
 * view's others. */
void support_reference_part(const aa_scene *s, int sw, int sh, int x0, int y0, int w, int h,
                            const char *filter, aa_image *out, aa_image *bound,
                            aa_truth_stats *stats);
/* Fails the test if an image (3 channels) is more than tol from the
 * reference r anywhere, naming the pixel and channel; returns the largest
 * difference. */
double support_within_reference(const char *what, const char *filter, const aa_image *got,
                                const aa_image *r, double tol);
/* `method` on the scene s (pattern units) at w x h under `filter`, at 2 and
 * 1 threads, within 1e-12 of the reference everywhere and the same bits
 * on both; prints and returns the largest difference. */
double support_method_against_reference(const char *method, const char *what, const aa_scene *s,
                                        int w, int h, const char *filter);
/* The same on the pixels [x0, x0 + w) x [y0, y0 + h) of the scene's sw x
 * sh view (support_scene_part). */
double support_method_against_part(const char *method, const char *what, const aa_scene *s,
                                   int sw, int sh, int x0, int y0, int w, int h,
                                   const char *filter);
/* The same under each filter of fl (NULL-ended); prints and returns the
 * largest difference over them. */
double support_method_against_filters(const char *method, const char *what, const aa_scene *s,
                                      int w, int h, const char *const *fl);
/* The reference of the placed scene s at w x h under `filter` by the
 * reference's path `mode` (aa__truth_render_mode: 0 its own choice), one
 * thread, into img (3 channels) and bound (1); fails the test if it is
 * refused or a bound exceeds AA_TRUTH_BOUND. */
void support_reference_mode(const aa_scene *s, int w, int h, const char *filter, int mode,
                            aa_image *img, aa_image *bound);
/* Fails the test unless the reference's value `got` (bound b) is within
 * b + err of the answer `want` (err: the answer's own error); the
 * difference goes into *worst. */
void support_check_value(const char *what, const char *filter, int i, int j, double got, double b,
                         double want, double err, double *worst);
/* The same for a pattern spec. */
void support_pattern_reference(const char *pattern, const support_view *v, aa_image *out,
                               aa_image *bound, aa_truth_stats *stats);

/* 1 if the scene model holds cubic Bezier arcs (aa_scene_cubic_to accepts
 * one), else 0 with the scene's reason in aa_last_error(): tests of cubic
 * scenes skip until it does. */
int support_scene_holds_cubics(void);

/* ---- comparing images (same size and channels) ---- */

/* Root mean square of the differences over every value. */
double support_rmse(const aa_image *a, const aa_image *b);
/* The largest |a - b| over every value (NaN counts as infinitely large);
 * the pixel where it is goes to *wi, *wj (may be NULL). */
double support_max_diff(const aa_image *a, const aa_image *b, int *wi, int *wj);
/* 1 if the two images are the same bit for bit. */
int support_same_image(const aa_image *a, const aa_image *b);
/* The mean of channel ch over the pixels: for the box, the pattern's
 * integral over the view. */
double support_channel_mean(const aa_image *im, int ch);

/* ---- plane geometry for the stroke tests' closed forms ---- */

struct aa_path;
/* The signed area of the polygon of n points xy[0..2n) (x, y pairs) by the
 * shoelace formula: positive when it turns from +x towards +y. */
double support_shoelace(const double *xy, int n);
/* Where the lines p + s d and q + t e meet (d and e not parallel). */
void support_line_meet(const double p[2], const double d[2], const double q[2],
                       const double e[2], double out[2]);
/* The area of what path p (pattern units, inside the unit square) fills
 * under the nonzero rule: the mean of its exact box reference on 64 x 64
 * pixels, white on black (to about 1e-14). */
double support_fill_area(const struct aa_path *p);

/* The scene of the svg pattern at w x h of a document whose root, of that
 * width and height, holds `body`, written to dir/name.svg; fails the test
 * (naming body) if it is refused. */
aa_scene *support_svg_scene(const char *dir, const char *name, const char *body, int w, int h);

/* ---- checks shared by several tests ---- */

/* Every pixel of img, a box-filtered image of crow with parameters p,
 * against tests/oracle.c's closed form: fails the test (naming `what`)
 * where channel 0 is more than tol off or the channels differ; returns the
 * largest difference. */
double support_check_crow_box(const char *what, const oracle_crow *p, const aa_image *img,
                              double tol);
/* The methods' RMSE against the reference of the view falls in the order
 * given, each strictly below the one before; prints each. */
void support_check_rmse_order(const char *what, const aa_scene *scene, const support_view *v,
                              const char *const *methods, int n);

/* ---- figures ---- */

/* In a figure's caption, what follows the first `field` ("rmse: ") after
 * "panel N:" for N = `panel` (1-based); fails the test if either is
 * missing. */
const char *support_caption_field(const char *caption, int panel, const char *field);

/* ---- the command under test ---- */

/* Seconds a command may run before it is killed, or $AABENCH_TEST_TIMEOUT. */
#define SUPPORT_TIMEOUT 300

/* Run the command under test ($AABENCH, set by scripts/run-tests.sh) with
 * args (NULL-terminated, without the program name): fork and exec, its
 * standard output and error captured together into out (cap bytes with the
 * final NUL; out may be NULL to discard them).  Returns the exit status, or
 * 128 + the signal that ended it.  interrupt_ms > 0 sends SIGINT that many
 * milliseconds after the start.  Fails the test if $AABENCH is not set, the
 * command cannot be started, or it runs past the time-out (then killed).
 * Every start is an exec of the binary: under ASan it is a sanitized
 * process of its own (about 0.1 s a start, most of it LeakSanitizer's
 * check at its end), so a test starts it only for what the binary does. */
int support_aabench_interrupted(const char *const *args, int interrupt_ms, char *out,
                                size_t cap);
int support_aabench(const char *const *args, char *out, size_t cap);
/* support_aabench with the wait status (WIFEXITED, WTERMSIG...). */
int support_aabench_wait_status(const char *const *args, char *out, size_t cap);

/* Start the command under test with args (as above), `env` ("NAME=value"
 * or NULL) added to its environment, its standard output into the file
 * `out` and its error into the file `err` (NULL: /dev/null); returns its
 * pid without waiting (for tests that signal the command or run several at
 * once).  Fails the test if $AABENCH is not set or there is no fork. */
pid_t support_aabench_spawn(const char *const *args, const char *env, const char *out,
                            const char *err);
/* As support_aabench_spawn, with standard output and error into the open
 * descriptors fd_out and fd_err (kept open here), and, if fsize > 0,
 * RLIMIT_FSIZE set to fsize with SIGXFSZ ignored (a full disk without
 * root). */
pid_t support_aabench_start(const char *const *args, const char *env, int fd_out, int fd_err,
                            unsigned long long fsize);

/* waitpid(), again when a signal interrupts it. */
pid_t support_waitpid(pid_t pid, int *status, int options);
/* Wait for the child pid: its exit status, or 128 + the signal that ended it. */
int support_wait(pid_t pid);

/* ---- checks in a child process ---- */

/* Run body(arg) in a forked child, which ends with what it returns: fails
 * the test if that is not 0 or a signal ends the child.  The body checks
 * with SUPPORT_CHILD_CHECK, not cmocka: a cmocka assertion in the child
 * would go on to run the parent's remaining tests there. */
void support_in_child(int (*body)(void *arg), void *arg);

/* In such a body: on failure, say what and return nonzero. */
#define SUPPORT_CHILD_CHECK(cond)                                                              \
    do {                                                                                       \
        if (!(cond)) {                                                                         \
            fprintf(stderr, "%s:%d: failed: %s (last error: %s)\n", __FILE__, __LINE__, #cond, \
                    aa_last_error());                                                          \
            return 1;                                                                          \
        }                                                                                      \
    } while (0)

/* ---- temporary folders and files ---- */

/* Make a fresh folder $TMPDIR/aabench-TAG-XXXXXX (TMPDIR unset: /tmp) and
 * put its path in buf; 0 on success, -1 with errno on failure. */
int support_tmpdir(char *buf, size_t len, const char *tag);

/* `run ARGS...` (args[0] "run", NULL-terminated) through the library's run
 * folder in this process, as the command does but for its printing: the
 * library's status (its message: aa_last_error()).  cache: the references'
 * cache, NULL for the default; failed (may be NULL): the cases that failed.
 * A test runs so what the command's own start does not check, sparing a
 * process and, where images are written, an OpenImageIO load. */
int support_lib_run(const char *const *args, const char *cache, size_t *failed);
/* Remove a file or a folder and everything under it (links are removed,
 * not followed); 0 on success. */
int support_rmtree(const char *path);
/* Write len bytes to path (fails the test if it cannot). */
void support_write_file(const char *path, const void *data, size_t len);
/* The whole content of a small file, NUL-terminated, in a buffer of the
 * caller's; *len (may be NULL) gets its length.  Fails the test if the file
 * cannot be read or does not fit. */
char *support_read_file(const char *path, char *buf, size_t cap, size_t *len);
/* The entries of a folder besides ".", ".." and `except` (may be NULL);
 * -1 if it cannot be read. */
int support_count_entries(const char *dir, const char *except);
/* The path of the one reference cache file (ref-*.bin) in the cache folder
 * dir into path; fails the test if there is none or more than one. */
void support_cache_file(const char *dir, char *path, size_t len);
/* A cmocka group tear-down for a group whose set-up made a temporary
 * folder and put its path in *state: removes it. */
int support_teardown_dir(void **state);

/* ---- text written piece by piece ---- */

/* A text (what a sink of the library was given, say) of at most 64 KiB. */
typedef struct support_text {
    char buf[65536];
    size_t n;
} support_text;
/* Append to the text t as printf would; fails the test if it does not fit.
 * Returns AA_OK (a sink's status). */
int support_put(support_text *t, const char *fmt, ...) AA_PRINTF(2, 3);
/* A path's commands appended to the support_text ctx, each " M x y", " L x
 * y", " Q cx cy x y", " C ax ay bx by x y" or " Z" (%.17g): the path
 * callbacks of a sink (the SVG reader's aa_svg_sink). */
int support_put_move(void *ctx, double x, double y);
int support_put_line(void *ctx, double x, double y);
int support_put_quad(void *ctx, double cx, double cy, double x, double y);
int support_put_cubic(void *ctx, double ax, double ay, double bx, double by, double x, double y);
int support_put_close(void *ctx);
/* 1 if `name` is one of the words of `list` (separated by single spaces). */
int support_names(const char *list, const char *name);

/* ---- random numbers ---- */

/* The next number of a xorshift64 stream of state *s (nonzero; Marsaglia,
 * "Xorshift RNGs", J. Stat. Softw. 8(14), 2003, shifts 13, 7, 17): the new
 * state's top 53 bits over 2^53, in [0, 1).  The tests' own fixed streams,
 * each seeded in its test; apart from the library's aa_rng, which some of
 * them test. */
double support_xorshift(uint64_t *s);
/* The same scaled to [a, b]: a + (b - a) support_xorshift(s). */
double support_uniform(uint64_t *s, double a, double b);

/* ---- the point-in-stroke check ---- */

/* The distance from p to a stroke's path by an oracle of the test's own
 * (*unsure set where the oracle cannot tell, e.g. on a butt end's line). */
typedef double (*support_distance_fn)(const void *ctx, double px, double py, int *unsure);
/* npts points drawn uniformly in box = {x0, y0, x1, y1} from the stream
 * *rng (support_xorshift; the test's own seed), each inside the stroke iff
 * its distance is at most h (the stroke's definition, SVG 2's stroke shape
 * of a round or butt stroke), against the scene s at m(p) (m NULL: p;
 * white above 0.5 is inside).  Points the oracle is unsure of, or within
 * 1e-7 of h, are left out.  Prints what it tested; fails on any
 * disagreement, and unless more than a twentieth of the points tested but
 * not all are inside. */
void support_stroke_check(const char *what, const aa_scene *s, const double box[4], double h,
                          const double *m, int npts, uint64_t *rng,
                          support_distance_fn distance, const void *ctx);

#endif
