/*
 * cmd_export.c: `aabench export`: a pattern's scene as an SVG document, in
 * pixel units, as the methods see it at that size (core.h, "SVG").
 */
#include "cli.h"

#include <stdlib.h>
#include <string.h>

static void usage(FILE *out)
{
    fprintf(out,
            "usage: aabench export -p PATTERN [-s WxH] -o OUT.svg [options]\n\n"
            "Writes the pattern's scene placed on a WxH image as SVG: width and height W and\n"
            "H, viewBox 0 0 W H, a rectangle of the background, one <path> per layer (the\n"
            "back layer first) with its fill-rule, lines as L, quadratic arcs as Q, cubic\n"
            "arcs as C and elliptical arcs as A (in pieces of at most 90 degrees), numbers\n"
            "with 17 significant digits; colours as rgb() percentages of\n"
            "the sRGB-encoded linear colour. A stroke is written as the stroke (its path,\n"
            "fill none, the stroke's properties and its map as transform=matrix()), so\n"
            "that a renderer strokes it itself. Clips (an SVG's clipPath) are <clipPath>\n"
            "elements in a <defs>, each clipped layer with clip-path. Field patterns\n"
            "(zoneplate) have no paths and are refused.\n\n"
            "  -p, --pattern SPEC   pattern, e.g. crow ('aabench list patterns')\n"
            "                       or svg:file=scene.svg or text:ppem=12 (drawn in pixels)\n"
            "  -s, --size WxH       image size in pixels (default: an svg file's own size times\n"
            "                       its scale)\n"
            "  -o, --out FILE.svg   the document\n"
            "      --time T         time in frames (default 0)\n"
            "      --motion VX,VY   motion in pixels per frame (default 0,0)\n"
            "      --mask           every layer white over black (a one-layer scene's coverage,\n"
            "                       what the external method gives a renderer)\n"
            "  -q, --quiet          print nothing on success\n\n"
            "Exit status: 0 done, 2 bad input (a field pattern included), 3 input/output\n"
            "error.\n");
}

typedef struct export_args {
    const char *pattern, *size, *out;
    double t, vx, vy;
    int mask, quiet;
} export_args;

/* Returns -1 to go on, or the exit code to stop with. */
static int parse(int argc, char **argv, export_args *a)
{
    enum { O_TIME = 256, O_MOTION, O_MASK };
    static const struct option opts[] = {
        {"pattern", required_argument, 0, 'p'}, {"size", required_argument, 0, 's'},
        {"out", required_argument, 0, 'o'},     {"time", required_argument, 0, O_TIME},
        {"motion", required_argument, 0, O_MOTION}, {"mask", no_argument, 0, O_MASK},
        {"quiet", no_argument, 0, 'q'},         {"help", no_argument, 0, 'h'},
        {0, 0, 0, 0}};
    int c, st = AA_OK;
    cli_getopt_reset();
    aa_options_seen seen = {0};
    while ((c = getopt_long(argc, argv, ":p:s:o:qh", opts, NULL)) != -1) {
        if ((st = aa_option_once(&seen, c, optarg, opts, NULL)))
            return cli_fail("export", st);
        switch (c) {
        case 'p': a->pattern = optarg; break;
        case 's': a->size = optarg; break;
        case 'o': a->out = optarg; break;
        case 'q': a->quiet = 1; break;
        case O_TIME: st = aa_parse_real("--time", optarg, -1e9, 1e9, &a->t); break;
        case O_MOTION: st = aa_parse_pair("--motion", optarg, -1e6, 1e6, &a->vx, &a->vy); break;
        case O_MASK: a->mask = 1; break;
        case 'h': usage(stdout); return 0;
        default: return cli_bad_option("export", c, argv);
        }
        if (st)
            return cli_fail("export", st);
    }
    if (optind < argc) {
        fprintf(stderr, "aabench export: unexpected argument \"%s\"\n", argv[optind]);
        return 2;
    }
    if (!a->pattern || !a->out) {
        fprintf(stderr, "aabench export: -p PATTERN and -o OUT.svg are required\n");
        usage(stderr);
        return 2;
    }
    return -1;
}

int cmd_export(int argc, char **argv)
{
    export_args a;
    memset(&a, 0, sizeof a);
    int st, code = parse(argc, argv, &a);
    if (code >= 0)
        return code;
    aa_spec pattern;
    int w, h;
    if ((st = aa_pattern_parse(a.pattern, &pattern)) || (st = cli_view_size(a.size, &pattern, &w, &h)) ||
        (st = cli_check_output_file(a.out, ".svg")))
        return cli_fail("export", st);
    aa_scene *scene = NULL, *placed = NULL;
    char ps[4096], desc[4400];
    if ((st = aa_pattern_scene_at(&pattern, w, h, &scene)) || (st = aa_spec_format(&pattern, ps, sizeof ps)))
        goto done;
    if (aa_scene_field(scene, NULL, NULL, NULL)) {
        st = aa_fail(AA_EINVAL,
                     "pattern %s is a procedural field: it has no paths to write as SVG (every "
                     "other pattern can be exported)",
                     pattern.info->name);
        goto done;
    }
    if (!(placed = aa_scene_place(scene, w, h, a.t, a.vx, a.vy))) {
        st = aa_fail(AA_ENOMEM, "out of memory placing the scene");
        goto done;
    }
    snprintf(desc, sizeof desc, "aabench %s: %s placed at %dx%d, time %.17g, motion %.17g,%.17g%s",
             AA_VERSION, ps, w, h, a.t, a.vx, a.vy,
             a.mask ? "; every layer white over black (mask)" : "");
    st = aa_scene_svg_write(a.out, placed, w, h, a.mask ? AA_SVG_MASK : AA_SVG_COLOURS, desc);
    if (!st && !a.quiet)
        printf("wrote %s: %s, %dx%d, %d layer%s\n", a.out, ps, w, h,
               aa_scene_layer_count(placed), aa_scene_layer_count(placed) == 1 ? "" : "s");
done:
    aa_scene_free(placed);
    aa_scene_free(scene);
    return st ? cli_fail("export", st) : 0;
}
