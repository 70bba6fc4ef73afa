/*
 * oiio.cpp: the project's only C++, a C interface over OpenImageIO 2.4.
 *
 * OpenImageIO reports failures through return values and geterror(), but
 * it and the libraries under it (OpenEXR, libtiff, libpng wrappers) may also
 * throw, and std::bad_alloc can come from anywhere.  Each entry point runs
 * its body inside guarded(), so no exception reaches C: a C frame cannot be
 * unwound through.
 *
 * Every channel is a value (colour or a bound), never alpha: files are
 * written with no alpha channel and read with "oiio:UnassociatedAlpha", so
 * OpenImageIO never multiplies or divides one channel by another.
 *
 * Built as the module aabench-oiio.so (oiio.h says why), which exports
 * aa__oiio_entry() and nothing else of ours; failures go through the aa_fail
 * the library hands to it (report()).
 */
#include "oiio.h"

#include "core.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include <exception>
#include <memory>
#include <new>
#include <string>

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;
using OIIO::ImageBuf;
namespace ImageBufAlgo = OIIO::ImageBufAlgo;

/* The library's aa_fail, from aa__oiio_entry(). */
static aa__oiio_fail_fn report;

struct aa__oiio_in {
    std::unique_ptr<ImageInput> file;
    std::string path;
};

/* Record OpenImageIO's message for `path`, without its trailing newlines
 * (the command line adds its own). */
static int fail(int status, const char *path, const char *what, std::string detail)
{
    while (!detail.empty() && (detail.back() == '\n' || detail.back() == '\r'))
        detail.pop_back();
    if (detail.empty())
        detail = "no reason given by OpenImageIO";
    return report(status, "%s: %s: %s", path, what, detail.c_str());
}

/* Run `body` and turn any exception into a status. */
template <class Body> static int guarded(const char *path, Body &&body) noexcept
{
    try {
        return body();
    } catch (const std::bad_alloc &) {
        return report(AA_ENOMEM, "%s: out of memory in OpenImageIO", path);
    } catch (const std::exception &e) {
        return report(AA_EIO, "%s: OpenImageIO: %s", path, e.what());
    } catch (...) {
        return report(AA_EFAIL, "%s: unknown exception in OpenImageIO", path);
    }
}

/* Tag the display encoding of integer samples the way OpenImageIO's writers
 * understand it (PNG turns these into an sRGB or a gAMA chunk). */
static void tag_encoding(ImageSpec &spec, double gamma)
{
    if (gamma == 0) {
        spec.attribute("oiio:ColorSpace", "sRGB");
    } else if (gamma == 1) {
        spec.attribute("oiio:ColorSpace", "Linear");
    } else {
        spec.attribute("oiio:ColorSpace", "GammaCorrected");
        spec.attribute("oiio:Gamma", (float)gamma);
    }
}

/* Write pixels of type `given` as `stored` samples. */
static int write_image(const char *path, const char *format, int w, int h, int c,
                       TypeDesc stored, TypeDesc given, const void *pixels, double gamma)
{
    /* The writer comes from the real format: `path` is a temporary name. */
    std::unique_ptr<ImageOutput> out = ImageOutput::create(format);
    if (!out)
        return fail(AA_EIO, path, "no OpenImageIO writer for this format", OIIO::geterror());
    ImageSpec spec(w, h, c, stored);
    spec.alpha_channel = -1;
    if (stored.is_floating_point())
        spec.attribute("oiio:ColorSpace", "Linear");
    else
        tag_encoding(spec, gamma);
    if (!out->open(path, spec))
        return fail(AA_EIO, path, "cannot create", out->geterror());
    bool written = out->write_image(given, pixels);
    std::string why = written ? std::string() : out->geterror();
    /* close() flushes: a full disk may only show here. */
    bool closed = out->close();
    if (!written || !closed)
        return fail(AA_EIO, path, "cannot write", written ? out->geterror() : why);
    return AA_OK;
}

static int write_float(const char *path, const char *format, int w, int h, int c,
                       const double *pixels)
{
    return guarded(path, [&] {
        return write_image(path, format, w, h, c, TypeDesc::FLOAT, TypeDesc::DOUBLE, pixels, 1);
    });
}

static int write_8bit(const char *path, const char *format, int w, int h, int c,
                      const unsigned char *pixels, double gamma)
{
    return guarded(path, [&] {
        return write_image(path, format, w, h, c, TypeDesc::UINT8, TypeDesc::UINT8, pixels,
                           gamma);
    });
}

/* The encoding a file declares for its integer samples (see oiio.h). */
static double declared_gamma(const ImageSpec &spec)
{
    std::string space = spec.get_string_attribute("oiio:ColorSpace");
    if (OIIO::Strutil::iequals(space, "Linear"))
        return 1;
    if (OIIO::Strutil::istarts_with(space, "Gamma")) {
        float g = spec.get_float_attribute("oiio:Gamma", 0.0f);
        if (g > 0)
            return g;
    }
    return 0;
}

static int open_image(const char *path, aa__oiio_in **in, aa__oiio_info *info)
{
    ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<ImageInput> file = ImageInput::open(path, &config);
    if (!file)
        return fail(AA_EIO, path, "cannot read", OIIO::geterror());
    const ImageSpec &spec = file->spec();
    if (spec.deep || spec.depth != 1)
        return report(AA_EIO, "%s: deep and volume images are not supported", path);
    info->w = spec.width;
    info->h = spec.height;
    info->c = spec.nchannels;
    info->is_float = spec.format.is_floating_point();
    info->bits = (int)spec.format.size() * 8;
    info->gamma = declared_gamma(spec);
    std::unique_ptr<aa__oiio_in> handle(new aa__oiio_in);
    handle->file = std::move(file);
    handle->path = path;
    *in = handle.release();
    return AA_OK;
}

static int open_file(const char *path, aa__oiio_in **in, aa__oiio_info *info)
{
    *in = nullptr;
    return guarded(path, [&] { return open_image(path, in, info); });
}

static int read_pixels(aa__oiio_in *in, double *pixels)
{
    const char *path = in->path.c_str();
    return guarded(path, [&] {
        ImageInput &file = *in->file;
        int c = file.spec().nchannels;
        if (!file.read_image(0, 0, 0, c, TypeDesc::DOUBLE, pixels))
            return fail(AA_EIO, path, "cannot read pixels", file.geterror());
        return (int)AA_OK;
    });
}

static void close_file(aa__oiio_in *in)
{
    if (in == nullptr)
        return;
    /* Closing only releases what open took; its status tells nothing the
     * read did not, and a destructor must not let an exception out. */
    try {
        in->file->close();
    } catch (...) {
    }
    delete in;
}

/* The labels' font: Debian's fonts-dejavu-core (scripts/install-deps.sh
 * installs it).  OpenImageIO's own default face is not in Debian. */
#define AA_FONT "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"

/* Draw `text` into a W x H x C double buffer with OpenImageIO's FreeType text
 * renderer, left aligned, top of the text at (x, y).  Used for the labels of
 * montages. */
static int draw_text(double *pixels, int w, int h, int c, int x, int y, const char *text,
                     int size, const float *colour)
{
    return guarded("text", [&] {
        ImageSpec spec(w, h, c, TypeDesc::DOUBLE);
        ImageBuf buf(spec, pixels);
        if (!ImageBufAlgo::render_text(buf, x, y, text, size, AA_FONT, OIIO::cspan<float>(colour, c),
                                       ImageBufAlgo::TextAlignX::Left,
                                       ImageBufAlgo::TextAlignY::Top))
            return fail(AA_EIO, "text", "cannot draw a label (is a font installed?)",
                        buf.geterror());
        return (int)AA_OK;
    });
}

/* The module's one entry point (oiio.h). */
extern "C" const aa__oiio_api *aa__oiio_entry(int version, aa__oiio_fail_fn library_fail)
{
    static const aa__oiio_api api = {write_float, write_8bit, open_file,
                                     read_pixels, close_file, draw_text};
    if (version != AA__OIIO_VERSION || library_fail == nullptr)
        return nullptr;
    report = library_fail;
    return &api;
}
