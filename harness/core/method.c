/*
 * method.c: the method contract's generic layer (harness/README.md, "The
 * three contracts"): the table in use, parsing and checking specs,
 * instances, and the timed render driver.  A method type only describes
 * itself; this file allocates its state, so a method (or a plug-in) never
 * sizes its own instance, as gsl_rng_alloc does for a gsl_rng_type.
 */
#include "core.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TABLE_MAX 256

/* The table starts empty: the method types are registered into it, the
 * built-in ones when the library starts (aa_method_add_builtin,
 * algorithms/methods.c), then the optional ones and plug-ins'. */
static const aa_method_type *table[TABLE_MAX + 1];
static size_t table_n;
/* the plug-in file each entry of the table was loaded from (NULL: built in) */
static char *files[TABLE_MAX + 1];

#define NO_METHODS                                                                             \
    "no method types are registered: the built-in ones register themselves when "            \
    "algorithms/methods.c is linked in; a program linked with libaabench.a that names none " \
    "of its symbols calls aa_method_add_builtin() first"

const void *const *aa_method_table(void)
{
    static int warned;
    if (!table_n && !warned) {
        warned = 1;
        aa_warn("%s", NO_METHODS);
    }
    return (const void *const *)table;
}

int aa_method_register(const aa_method_type *const *types, const char *origin)
{
    size_t n = 0;
    for (; types[n]; n++) {
        const aa_method_type *t = types[n];
        if (!t->info.name || !t->info.summary || !t->render)
            return aa_fail(AA_EINVAL, "%s: method %zu lacks a name, summary or render", origin, n);
        if (aa_table_find((const void *const *)table, t->info.name))
            return aa_fail(AA_EINVAL, "%s: method \"%s\" is already defined", origin,
                           t->info.name);
        if ((t->flags & AA_METHOD_DISPLAY) && !((const aa_display_method_type *)t)->display)
            return aa_fail(AA_EINVAL, "%s: method \"%s\" is flagged AA_METHOD_DISPLAY but has no "
                                      "display function", origin, t->info.name);
        if (aa_param_count(&t->info) > AA_MAX_PARAMS)
            return aa_fail(AA_EINVAL, "%s: method \"%s\" has more than %d parameters", origin,
                           t->info.name, AA_MAX_PARAMS);
    }
    if (table_n + n > TABLE_MAX)
        return aa_fail(AA_EINVAL, "%s: more than %d methods", origin, TABLE_MAX);
    for (size_t k = 0; k < n; k++)
        table[table_n++] = types[k];
    table[table_n] = NULL;
    return AA_OK;
}

int aa_method_set_file(const aa_method_type *const *types, const char *path)
{
    for (size_t n = 0; types[n]; n++)
        for (size_t k = 0; k < table_n; k++)
            if (table[k] == types[n] && !files[k] && !(files[k] = strdup(path)))
                return aa_fail(AA_ENOMEM, "out of memory");
    return AA_OK;
}

const char *aa_method_file(const aa_method_type *type)
{
    for (size_t k = 0; k < table_n; k++)
        if (table[k] == type)
            return files[k];
    return NULL;
}

/* A method's failure with the context of what failed; a status outside the
 * contract's (aa_status) is named with its number and becomes AA_EFAIL. */
static int method_failed(const aa_method_type *type, const char *what, int st)
{
    if (st < AA_OK || st > AA_EFAIL)
        return aa_fail(AA_EFAIL,
                       "method %s: its %s returned the unknown status %d (the statuses are 0 "
                       "to %d, aabench.h)",
                       type->info.name, what, st, AA_EFAIL);
    return aa_fail_context(st, "method %s", type->info.name);
}

int aa_method_check(const aa_spec *spec, const aa_filter *f)
{
    const aa_method_type *type = (const aa_method_type *)spec->info;
    int st;
    if (type->check && (st = type->check(spec->v, f)))
        return method_failed(type, "check", st);
    return AA_OK;
}

int aa_method_parse(const char *text, const aa_filter *f, aa_spec *out)
{
    if (!table_n)
        return aa_fail(AA_EINVAL, "method \"%s\": %s", aa_echo(text), NO_METHODS);
    int st = aa_spec_parse(text, aa_method_table(), "method", out);
    return st ? st : aa_method_check(out, f);
}

/* A method that does not declare AA_METHOD_FIELDS is refused a field scene
 * (it would see no edges and render the background), and one that does not
 * declare AA_METHOD_GRADIENTS a scene with gradient paint (it would paint
 * each gradient layer with one colour). */
static int check_scene(const aa_method_type *type, const aa_job *job)
{
    const aa_field_type *field = job->placed ? aa_scene_field(job->placed, NULL, NULL, NULL) : NULL;
    if (field && !(type->flags & AA_METHOD_FIELDS))
        return aa_fail(AA_EINVAL,
                       "method %s renders scenes of paths only, and pattern %s is a procedural "
                       "field: use a method that samples it (such as point, supersample or "
                       "jitter)",
                       type->info.name, field->name);
    if (job->placed && aa_scene_has_gradients(job->placed) &&
        !(type->flags & AA_METHOD_GRADIENTS))
        return aa_fail(AA_EINVAL,
                       "method %s draws from the layers' constant colours and the scene has "
                       "gradient paint (linearGradient/radialGradient): use a method that "
                       "samples the picture at points (point, supersample, jitter) or a peer "
                       "with gradients of its own (cairo, agg)",
                       type->info.name);
    return AA_OK;
}

int aa_method_init(aa_method *m, const aa_spec *spec, const aa_job *job)
{
    const aa_method_type *type = (const aa_method_type *)spec->info;
    int st;
    memset(m, 0, sizeof *m);
    if ((st = check_scene(type, job)) || (st = aa_method_check(spec, &job->filter)))
        return st;
    m->type = type;
    m->spec = *spec;
    if (type->size && !(m->state = calloc(1, type->size)))
        return aa_fail(AA_ENOMEM, "out of memory for method %s", type->info.name);
    if (type->init && (st = type->init(m->state, spec->v, job))) {
        aa_method_free(m);
        return method_failed(type, "init", st);
    }
    return AA_OK;
}

int aa_method_render(aa_method *m, const aa_job *job, aa_image *out, aa_counters *counters)
{
    if (!out->v || out->w != job->w || out->h != job->h || out->c != 3)
        return aa_fail(AA_EINVAL, "render needs a %dx%dx3 image", job->w, job->h);
    int st = check_scene(m->type, job);
    if (st)
        return st;
    memset(counters, 0, sizeof *counters);
    st = m->type->render(m->state, m->spec.v, job, out, counters);
    if (st)
        return method_failed(m->type, "render", st);
    /* counts no render can give: negative ones written into the unsigned
     * counters, more expensive pixels than the image has */
    const uint64_t pixels = (uint64_t)job->w * (uint64_t)job->h, neg = UINT64_C(1) << 63;
    if (counters->samples >= neg || counters->expensive_pixels >= neg)
        return aa_fail(AA_EFAIL, "method %s counted a negative number of %s (%lld)",
                       m->type->info.name,
                       counters->samples >= neg ? "samples" : "expensive pixels",
                       (long long)(counters->samples >= neg ? counters->samples
                                                            : counters->expensive_pixels));
    if (counters->expensive_pixels > pixels)
        return aa_fail(AA_EFAIL, "method %s counted %llu expensive pixels in an image of %llu",
                       m->type->info.name, (unsigned long long)counters->expensive_pixels,
                       (unsigned long long)pixels);
    return AA_OK;
}

void aa_method_free(aa_method *m)
{
    if (m->type && m->type->release && m->state)
        m->type->release(m->state);
    free(m->state);
    memset(m, 0, sizeof *m);
}

int aa_method_run(const aa_spec *spec, const aa_job *job, int reps, aa_image *out,
                  aa_counters *counters, double *seconds)
{
    aa_method m;
    int st = aa_method_init(&m, spec, job);
    if (st)
        return st;
    /* touch the output once: page faults are not the method's cost */
    memset(out->v, 0, (size_t)out->w * (size_t)out->h * 3 * sizeof *out->v);
    for (int r = 0; r < reps && !st; r++) {
        double t0 = aa_now();
        st = aa_method_render(&m, job, out, counters);
        if (seconds)
            seconds[r] = aa_now() - t0;
    }
    aa_method_free(&m);
    return st;
}

int aa_method_display(const aa_spec *spec, const aa_job *job, aa_display_frame *frames,
                      int *n)
{
    const aa_method_type *type = (const aa_method_type *)spec->info;
    *n = 0;
    if (!(type->flags & AA_METHOD_DISPLAY))
        return AA_OK;
    const aa_display_method_type *d = (const aa_display_method_type *)type;
    int st = d->display(spec->v, job, frames, n);
    if (st)
        return aa_fail_context(st, "display of method %s", type->info.name);
    if (*n < 0 || *n > AA_DISPLAY_MAX_FRAMES)
        return aa_fail(AA_EFAIL, "method %s shows %d frames (0 to %d)", type->info.name, *n,
                       AA_DISPLAY_MAX_FRAMES);
    double sum = 0.0;
    for (int k = 0; k < *n; k++) {
        const aa_display_frame *f = &frames[k];
        if (!(fabs(f->dx) <= 1.0 && fabs(f->dy) <= 1.0 && f->weight >= 0.0 && isfinite(f->t)))
            return aa_fail(AA_EFAIL, "method %s: frame %d shown at (%g, %g) with weight %g "
                                     "(offsets within [-1, 1], weights not negative)",
                           type->info.name, k, f->dx, f->dy, f->weight);
        sum += f->weight;
    }
    if (*n > 0 && !(fabs(sum - 1.0) <= 1e-12))
        return aa_fail(AA_EFAIL, "method %s: the weights of its frames sum to %.17g, not 1",
                       type->info.name, sum);
    return AA_OK;
}

int aa_job_init(aa_job *job, const aa_scene *pattern, int w, int h, double t, double vx,
                double vy, const aa_filter *f, uint64_t seed, int threads)
{
    memset(job, 0, sizeof *job);
    job->pattern = pattern;
    job->w = w, job->h = h;
    job->t = t, job->vx = vx, job->vy = vy;
    job->filter = *f;
    job->seed = seed;
    job->threads = threads > 0 ? threads : 1;
    if (!(job->placed = aa_scene_place(pattern, w, h, t, vx, vy)))
        return aa_fail_context(AA_EINVAL, "placing the scene");
    return AA_OK;
}

void aa_job_free(aa_job *job)
{
    aa_scene_free((aa_scene *)job->placed);
    job->placed = NULL;
}

double aa_filter_support(const aa_filter *f)
{
    if (f->type == &aa_filter_gauss)
        return 3.0 * f->spec.v[0];
    return f->radius;
}

int aa_thread_count(int threads)
{
    if (threads > 0)
        return threads < AA_MAX_THREADS ? threads : AA_MAX_THREADS;
#ifdef _OPENMP
    int n = omp_get_max_threads(), cap = 4 * omp_get_num_procs();
    if (cap > AA_MAX_THREADS)
        cap = AA_MAX_THREADS;
    return n < 1 ? 1 : n < cap ? n : cap;
#else
    return 1;
#endif
}

void aa_method_value_range(const aa_filter *f, double *lo, double *hi)
{
    aa_filter_range(f, lo, hi);
    *lo *= 2.0;
    *hi = 1.0 + 2.0 * (*hi - 1.0);
}

size_t aa_image_bad_values(const aa_image *im, double lo, double hi, int at[3], double *value)
{
    size_t n = (size_t)im->w * (size_t)im->h * (size_t)im->c, bad = 0;
    for (size_t k = 0; k < n; k++) {
        double v = im->v[k];
        if (v >= lo && v <= hi) /* false for NaN */
            continue;
        if (bad++ == 0) {
            size_t px = k / (size_t)im->c;
            at[0] = (int)(px % (size_t)im->w);
            at[1] = (int)(px / (size_t)im->w);
            at[2] = (int)(k % (size_t)im->c);
            *value = v;
        }
    }
    return bad;
}
