/*
 * cmd_compare.c: `aabench compare REFERENCE IMAGE`: the error metrics
 * between two image files.
 */
#include "cli.h"

#include <math.h>
#include <string.h>

static void usage(FILE *out)
{
    fprintf(out, "usage: aabench compare REFERENCE IMAGE [--encode E] [--json] [-o PICTURE]\n"
                 "                       [-p PATTERN [-f FILTER]]\n\n"
                 "Prints the error of IMAGE against REFERENCE (same size and channels; any of\n"
                 ".exr .tif .png .pfm .txt): rmse, mae, max_err and where, psnr, in linear\n"
                 "light and after display encoding; the error spectrum's power in total, below\n"
                 "1/4 cycle per pixel (moire) and above; SSIM on the encoded luma; FLIP\n"
                 "(LDR-FLIP, Andersson et al. 2020, at 67 pixels per degree: a 0.7 m wide\n"
                 "3840-pixel monitor seen from 0.7 m, the images shown through the encoding);\n"
                 "the edge RMSE, over the pixels whose filter support meets an edge of the\n"
                 "scene PATTERN (at the images' size, under FILTER, default box) or, without\n"
                 "-p, over the pixels of REFERENCE that differ from a 4-neighbour.  Pixels\n"
                 "holding NaN or infinity in either image are counted (nonfinite) and left out;\n"
                 "when every pixel is left out there is no figure: each is n/a (null in JSON)\n"
                 "and the exit status is 1.  Sizes and the memory needed are checked from the\n"
                 "headers before any pixel is read.\n\n"
                 "      --encode E   display encoding: srgb (default), linear or gamma:G\n"
                 "      --json       print one JSON object instead of lines\n"
                 "  -o, --output P   write a picture of the error: P.png the signed error map\n"
                 "                   (auto-scaled, colour bar), P-flip.png FLIP's map and\n"
                 "                   P-worst.png the worst 32x32 region zoomed (P without .png)\n"
                 "  -p, --pattern S  the scene of the images, for the edge pixels\n"
                 "  -f, --filter F   its filter (default box)\n\n"
                 "Exit status: 0 compared, 1 no pixel could be compared, 2 bad input or\n"
                 "usage, 3 input/output error.\n");
}

/* A JSON number, or null for NaN and infinities (JSON has neither). */
static void json_num(double v)
{
    if (isfinite(v))
        printf("%.9g", v);
    else
        printf("null");
}

/* Before any pixel is read: what comparing the two files will hold (both
 * images, then the error spectrum or SSIM's lumas), from their headers,
 * against the memory this process may take.  (Files of different sizes
 * are refused once read, so that a damaged file is reported as such.) */
static int check_sizes(const char *rpath, const char *ipath)
{
    int rw, rh, rc, iw, ih, ic, st;
    if ((st = aa_image_file_size(rpath, &rw, &rh, &rc)) ||
        (st = aa_image_file_size(ipath, &iw, &ih, &ic)))
        return st;
    char what[160];
    if (rw == iw && rh == ih && rc == ic)
        snprintf(what, sizeof what, "comparing two %dx%dx%d images", rw, rh, rc);
    else
        snprintf(what, sizeof what, "reading a %dx%dx%d and a %dx%dx%d image", rw, rh, rc, iw,
                 ih, ic);
    double need = (double)rw * rh * rc * sizeof(double) + (double)iw * ih * ic * sizeof(double);
    if (rw == iw && rh == ih && rc == ic)
        need += aa_metrics_bytes(rw, rh);
    return aa_memory_check(need, what);
}

/* The picture's path without its .png. */
static const char *stem_of(const char *output)
{
    static char stem[4096];
    size_t n = strlen(output);
    if (n >= 4 && !strcmp(output + n - 4, ".png"))
        n -= 4;
    snprintf(stem, sizeof stem, "%.*s", (int)n, output);
    return stem;
}

static int output_check(const char *output)
{
    size_t n = strlen(output);
    if (n >= 4 && strcmp(output + n - 4, ".png") && strchr(output + n - 4, '.'))
        return aa_fail(AA_EINVAL, "-o %s: the pictures are PNG files (name them .png, or give no "
                       "extension)", aa_echo(output));
    if (n + strlen("-worst.png") >= 4096)
        return aa_fail(AA_EINVAL, "-o: a path of %zu characters is too long", n);
    return AA_OK;
}

/* The edge RMSE: from the scene when given, else from the reference. */
static int edges(const aa_spec *pattern, const aa_filter *filter, const aa_image *ref,
                 const aa_image *img, aa_metrics *m)
{
    if (m->nonfinite == (size_t)ref->w * (size_t)ref->h) /* nothing to compare */
        return AA_OK;
    if (!pattern)
        return aa_metrics_edges(NULL, 0.5, ref, img, m);
    aa_scene *scene = NULL, *placed = NULL;
    int st = aa_pattern_scene_at(pattern, ref->w, ref->h, &scene);
    if (!st && !(placed = aa_scene_place(scene, ref->w, ref->h, 0, 0, 0)))
        st = aa_fail(AA_ENOMEM, "out of memory placing the scene");
    if (!st)
        st = aa_metrics_edges(placed, aa_filter_support(filter), ref, img, m);
    aa_scene_free(placed);
    aa_scene_free(scene);
    return st;
}

/* P.png, P-flip.png and P-worst.png. */
static int pictures(const char *output, const aa_image *ref, const aa_image *img,
                    const aa_encode *enc)
{
    char stem[4096], path[4200];
    snprintf(stem, sizeof stem, "%s", stem_of(output));
    aa_image pic = {0}, map = {0}, a = {0}, b = {0};
    double flip;
    int st;
    /* FLIP wants finite values: a pixel holding NaN is shown as 0 in both */
    if ((st = aa_image_alloc(&a, ref->w, ref->h, ref->c)) ||
        (st = aa_image_alloc(&b, ref->w, ref->h, ref->c)))
        goto done;
    for (size_t k = 0; k < (size_t)ref->w * ref->h * (size_t)ref->c; k++) {
        int keep = isfinite(ref->v[k]) && isfinite(img->v[k]);
        a.v[k] = keep ? ref->v[k] : 0, b.v[k] = keep ? img->v[k] : 0;
    }
    snprintf(path, sizeof path, "%s.png", stem);
    if ((st = aa_error_picture(&a, &b, "image - reference (linear)", &pic, NULL)) ||
        (st = aa_picture_write(path, &pic)))
        goto done;
    aa_image_free(&pic);
    snprintf(path, sizeof path, "%s-flip.png", stem);
    if ((st = aa_flip(&a, &b, enc, AA_FLIP_PPD, &flip, &map)) ||
        (st = aa_flip_picture(&map, "FLIP (67 pixels per degree)", &pic)) ||
        (st = aa_picture_write(path, &pic)))
        goto done;
    aa_image_free(&pic);
    snprintf(path, sizeof path, "%s-worst.png", stem);
    if (!(st = aa_worst_picture(&a, &b, enc, &pic, NULL, NULL)))
        st = aa_picture_write(path, &pic);
done:
    aa_image_free(&pic);
    aa_image_free(&map);
    aa_image_free(&a);
    aa_image_free(&b);
    return st;
}

int cmd_compare(int argc, char **argv)
{
    enum { O_ENCODE = 256, O_JSON };
    static const struct option opts[] = {{"encode", required_argument, 0, O_ENCODE},
                                         {"json", no_argument, 0, O_JSON},
                                         {"output", required_argument, 0, 'o'},
                                         {"pattern", required_argument, 0, 'p'},
                                         {"filter", required_argument, 0, 'f'},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    aa_encode enc = {AA_ENCODE_SRGB, 0};
    int c, st, json = 0;
    const char *output = NULL, *pattern = NULL, *filter = NULL;
    cli_getopt_reset();
    aa_options_seen seen = {0};
    while ((c = getopt_long(argc, argv, ":ho:p:f:", opts, NULL)) != -1) {
        if ((st = aa_option_once(&seen, c, optarg, opts, NULL)))
            return cli_fail("compare", st);
        if (c == 'o') {
            output = optarg;
        } else if (c == 'p') {
            pattern = optarg;
        } else if (c == 'f') {
            filter = optarg;
        } else if (c == O_ENCODE) {
            if ((st = aa_encode_parse(optarg, &enc)))
                return cli_fail("compare", st);
        } else if (c == O_JSON) {
            json = 1;
        } else if (c == 'h') {
            usage(stdout);
            return 0;
        } else {
            return cli_bad_option("compare", c, argv);
        }
    }
    if (argc - optind != 2) {
        fprintf(stderr, "aabench compare: needs two image files, REFERENCE and IMAGE\n");
        usage(stderr);
        return 2;
    }
    const char *rpath = argv[optind], *ipath = argv[optind + 1];
    if (filter && !pattern) {
        fprintf(stderr, "aabench compare: -f names the filter of the scene -p names: give both\n");
        return 2;
    }
    aa_spec pspec;
    aa_filter fspec;
    if (pattern && ((st = aa_pattern_parse(pattern, &pspec)) ||
                    (st = aa_filter_parse(filter ? filter : "box", &fspec))))
        return cli_fail("compare", st);
    if (output && (st = output_check(output)))
        return cli_fail("compare", st);
    if ((st = check_sizes(rpath, ipath)))
        return cli_fail("compare", st);
    aa_image ref = {0}, img = {0};
    aa_metrics m;
    if ((st = aa_image_read(rpath, &ref)) || (st = aa_image_read(ipath, &img)) ||
        (st = aa_metrics_compare(&ref, &img, &enc, &m)) ||
        (st = edges(pattern ? &pspec : NULL, &fspec, &ref, &img, &m)) ||
        (output && (st = pictures(output, &ref, &img, &enc)))) {
        aa_image_free(&ref);
        aa_image_free(&img);
        return cli_fail("compare", st);
    }
    /* No pixel to compare: every figure is NaN, none is printed. */
    int none = m.nonfinite == (size_t)ref.w * (size_t)ref.h;
    if (json) {
        /* JSON has no NaN and no infinity: those are null.  Identical
         * images keep their PSNR of 999 (infinite); images that differ only
         * where a value is not finite have none (null), and `nonfinite`
         * counts those pixels. */
        double psnr = m.psnr == INFINITY ? 999.0 : m.psnr;
        double psnr_enc = m.psnr_enc == INFINITY ? 999.0 : m.psnr_enc;
        const struct {
            const char *key;
            double v;
        } nums[] = {{"rmse", m.rmse},         {"mae", m.mae},
                    {"max_err", m.max_err},   {"psnr", psnr},
                    {"rmse_enc", m.rmse_enc}, {"mae_enc", m.mae_enc},
                    {"max_err_enc", m.max_err_enc}, {"psnr_enc", psnr_enc},
                    {"alias_total", m.alias_total}, {"alias_low", m.alias_low},
                    {"alias_high", m.alias_high},   {"ssim", m.ssim},
                    {"flip", m.flip},               {"edge_rmse", m.edge_rmse}};
        for (size_t k = 0; k < sizeof nums / sizeof nums[0]; k++) {
            printf("%s\"%s\": ", k ? ", " : "{", nums[k].key);
            json_num(nums[k].v);
            if (!strcmp(nums[k].key, "max_err"))
                printf(", \"max_at\": [%d, %d, %d]", m.max_at[0], m.max_at[1], m.max_at[2]);
        }
        printf(", \"edge_pixels\": %zu, \"edges_from\": \"%s\", \"nonfinite\": %zu}\n",
               m.edge_pixels, pattern ? "scene" : "reference", m.nonfinite);
    } else if (none) {
        printf("size         %dx%dx%d\n", ref.w, ref.h, ref.c);
        static const char *const names[] = {"rmse", "mae", "max_err", "psnr", "alias_total",
                                            "ssim", "flip", "edge_rmse"};
        for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
            printf("%-12s n/a\n", names[k]);
        printf("nonfinite    %zu pixel%s: every pixel holds NaN or infinity in either image, "
               "none can be compared\n", m.nonfinite, m.nonfinite == 1 ? "" : "s");
    } else {
        printf("size         %dx%dx%d\n"
               "rmse         %.6e   (encoded %.6e)\n"
               "mae          %.6e   (encoded %.6e)\n"
               "max_err      %.6e   at pixel %d %d channel %d (encoded %.6e)\n"
               "psnr         %.3f dB   (encoded %.3f dB)\n"
               "alias_total  %.6e   (below 1/4 cycle/px %.6e, above %.6e)\n"
               "ssim         %.6f\n"
               "flip         %.6f   (mean LDR-FLIP at %.1f pixels per degree)\n"
               "edge_rmse    %.6e   (over %zu edge pixels, from the %s)\n",
               ref.w, ref.h, ref.c, m.rmse, m.rmse_enc, m.mae, m.mae_enc, m.max_err, m.max_at[0],
               m.max_at[1], m.max_at[2], m.max_err_enc, m.psnr, m.psnr_enc, m.alias_total,
               m.alias_low, m.alias_high, m.ssim, m.flip, AA_FLIP_PPD, m.edge_rmse, m.edge_pixels,
               pattern ? "scene" : "reference's pixels that differ from a neighbour");
        if (output)
            printf("pictures     %s.png, %s-flip.png, %s-worst.png\n", stem_of(output),
                   stem_of(output), stem_of(output));
        if (m.nonfinite)
            printf("nonfinite    %zu pixel%s hold NaN or infinity in either image: left out of "
                   "the figures above\n", m.nonfinite, m.nonfinite == 1 ? "" : "s");
    }
    aa_image_free(&ref);
    aa_image_free(&img);
    if (none)
        fprintf(stderr, "aabench compare: no pixel can be compared (in every one, either "
                        "image holds a value that is not finite)\n");
    return none ? 1 : 0;
}
