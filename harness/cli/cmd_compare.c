/*
 * cmd_compare.c: `aabench compare REFERENCE IMAGE`: the error metrics
 * between two image files.
 */
#include "cli.h"

#include <math.h>
#include <string.h>

static void usage(FILE *out)
{
    fprintf(out, "usage: aabench compare REFERENCE IMAGE [--encode E] [--json]\n\n"
                 "Prints the error of IMAGE against REFERENCE (same size and channels; any of\n"
                 ".exr .tif .png .pfm .txt): rmse, mae, max_err and where, psnr, in linear\n"
                 "light and after display encoding; the error spectrum's power in total, below\n"
                 "1/4 cycle per pixel (moire) and above; SSIM on the encoded luma.\n\n"
                 "      --encode E   display encoding: srgb (default), linear or gamma:G\n"
                 "      --json       print one JSON object instead of lines\n");
}

int cmd_compare(int argc, char **argv)
{
    enum { O_ENCODE = 256, O_JSON };
    static const struct option opts[] = {{"encode", required_argument, 0, O_ENCODE},
                                         {"json", no_argument, 0, O_JSON},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    aa_encode enc = {AA_ENCODE_SRGB, 0};
    int c, st, json = 0;
    cli_getopt_reset();
    while ((c = getopt_long(argc, argv, ":h", opts, NULL)) != -1) {
        if (c == O_ENCODE) {
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
    aa_image ref = {0}, img = {0};
    aa_metrics m;
    if ((st = aa_image_read(argv[optind], &ref)) || (st = aa_image_read(argv[optind + 1], &img)) ||
        (st = aa_metrics_compute(&ref, &img, &enc, &m))) {
        aa_image_free(&ref);
        aa_image_free(&img);
        return cli_fail("compare", st);
    }
    if (json)
        printf("{\"rmse\": %.9g, \"mae\": %.9g, \"max_err\": %.9g, \"max_at\": [%d, %d, %d], "
               "\"psnr\": %.9g, \"rmse_enc\": %.9g, \"mae_enc\": %.9g, \"max_err_enc\": %.9g, "
               "\"psnr_enc\": %.9g, \"alias_total\": %.9g, \"alias_low\": %.9g, "
               "\"alias_high\": %.9g, \"ssim\": %.9g}\n",
               m.rmse, m.mae, m.max_err, m.max_at[0], m.max_at[1], m.max_at[2],
               isinf(m.psnr) ? 999.0 : m.psnr, m.rmse_enc, m.mae_enc, m.max_err_enc,
               isinf(m.psnr_enc) ? 999.0 : m.psnr_enc, m.alias_total, m.alias_low, m.alias_high,
               m.ssim);
    else
        printf("size         %dx%dx%d\n"
               "rmse         %.6e   (encoded %.6e)\n"
               "mae          %.6e   (encoded %.6e)\n"
               "max_err      %.6e   at pixel %d %d channel %d (encoded %.6e)\n"
               "psnr         %.3f dB   (encoded %.3f dB)\n"
               "alias_total  %.6e   (below 1/4 cycle/px %.6e, above %.6e)\n"
               "ssim         %.6f\n",
               ref.w, ref.h, ref.c, m.rmse, m.rmse_enc, m.mae, m.mae_enc, m.max_err, m.max_at[0],
               m.max_at[1], m.max_at[2], m.max_err_enc, m.psnr, m.psnr_enc, m.alias_total,
               m.alias_low, m.alias_high, m.ssim);
    aa_image_free(&ref);
    aa_image_free(&img);
    return 0;
}
