/*
 * oiio.cpp: the project's only C++, a C interface over OpenImageIO 2.4.
 *
 * OpenImageIO reports failures through return values and geterror(), but
 * not always both: its TIFF reader returns true from read_image() for a
 * file cut short (the missing strips read as black) and its PNG writer
 * returns true from write_image() and close() when the disk is full,
 * leaving the failure in the object's error state only.  So every call is
 * followed by a look at that state (call_error()), and a call is a success
 * only when it returned true and left no error behind.
 *
 * Writes do not let OpenImageIO open the file: it would write through a
 * stdio FILE whose last buffer is flushed, and whose close fails, where
 * nobody looks.  Every writer takes an IOProxy (the "oiio:ioproxy"
 * attribute), ours: it writes with pwrite(2) on a descriptor we opened,
 * remembers the first failure (ENOSPC, EFBIG, EIO...) and is closed by us,
 * checked.
 *
 * It and the libraries under it (OpenEXR, libtiff, libpng wrappers) may
 * also throw, and std::bad_alloc can come from anywhere.  Each entry point
 * runs its body inside guarded(), which catches everything (catch (...)
 * included), so no exception reaches C: a C frame cannot be unwound
 * through.  Exceptions thrown while the module is being loaded (by the
 * static constructors of the libraries under OpenImageIO, when memory is
 * short) happen before any of our code runs; image.c guards against those
 * (oiio.h).
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

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include <cerrno>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>

#include <fcntl.h>
#include <unistd.h>

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
    /* A reader may say the same for every strip of a file cut short: the
     * first line, and how many more. */
    size_t first = detail.find('\n');
    if (first != std::string::npos) {
        size_t more = 0;
        for (size_t k = first; k < detail.size(); k++)
            more += detail[k] == '\n';
        detail = detail.substr(0, first) + " (and " + std::to_string(more) + " more line" +
                 (more == 1 ? "" : "s") + ")";
    }
    if (detail.empty())
        detail = "no reason given by OpenImageIO";
    return report(status, "%s: %s: %s", path, what, detail.c_str());
}

/* Run `body` and turn any exception into a status: AA_ENOMEM for memory,
 * AA_EFAIL for anything else.  Recording the message allocates nothing. */
template <class Body> static int guarded(const char *path, Body &&body) noexcept
{
    try {
        return body();
    } catch (const std::bad_alloc &) {
        return report(AA_ENOMEM, "%s: out of memory in OpenImageIO", path);
    } catch (const std::exception &e) {
        return report(AA_EFAIL, "%s: OpenImageIO failed: %s", path, e.what());
    } catch (...) {
        return report(AA_EFAIL, "%s: unknown exception in OpenImageIO", path);
    }
}

/* The error an ImageInput, ImageOutput or ImageBuf holds after a call: `ok`
 * is what the call returned.  Empty when the call succeeded and left no
 * error; otherwise the message, or a placeholder when there is none.  The
 * message itself is looked at, not has_error(): OpenImageIO 2.4's TIFF
 * writer leaves a message that has_error() does not see after close(). */
template <class File> static std::string call_error(File &file, bool ok)
{
    std::string why = file.geterror();
    if (ok && why.empty())
        return why;
    return why.empty() ? std::string("the call failed and OpenImageIO gave no reason") : why;
}

/* OpenImageIO 2.4's TIFF writer, with the libtiff of Debian 12, fails to
 * write the Exif directory it adds for the DateTime stamp, every time, and
 * says so (the image and its main directory are whole: TIFFClose writes
 * them afterwards).  That one message is not a failure of ours; a real I/O
 * error behind it is seen by the descriptor all the same (FdOutput). */
static std::string without_exif_note(const char *format, std::string why)
{
    static const std::string note = "failed TIFFWriteCustomDirectory() of the Exif data";
    if (format[0] != 't')
        return why;
    std::string kept;
    size_t start = 0;
    while (start <= why.size()) {
        size_t end = why.find('\n', start);
        if (end == std::string::npos)
            end = why.size();
        std::string line = why.substr(start, end - start);
        if (!line.empty() && line != note)
            kept += (kept.empty() ? "" : "\n") + line;
        start = end + 1;
    }
    return kept;
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

/* The file a writer writes through: a descriptor of ours, written with
 * pwrite(2) at the proxy's position, never buffered, so nothing is left to
 * flush where a failure would go unseen.  The first failure is kept (its
 * errno) and every later call fails too.  The writers call these from C
 * (libpng's and libtiff's callbacks): nothing here throws. */
class FdOutput final : public OIIO::Filesystem::IOProxy {
public:
    FdOutput(const std::string &path, int fd) : IOProxy(path, Write), m_fd(fd) {}
    ~FdOutput() override
    {
        if (m_fd >= 0)
            ::close(m_fd);
    }
    FdOutput(const FdOutput &) = delete;
    FdOutput &operator=(const FdOutput &) = delete;
    const char *proxytype() const override { return "aabench-fd"; }
    /* A writer may close its proxy itself: the result is kept. */
    void close() noexcept override
    {
        if (m_fd < 0)
            return;
        if (::close(m_fd) != 0)
            failed(errno);
        m_fd = -1;
    }
    bool opened() const noexcept override { return m_fd >= 0; }
    bool seek(int64_t offset) noexcept override
    {
        if (offset < 0) {
            failed(EINVAL);
            return false;
        }
        m_pos = offset;
        return true;
    }
    size_t write(const void *buf, size_t size) noexcept override
    {
        size_t n = pwrite(buf, size, m_pos);
        m_pos += (int64_t)n;
        return n;
    }
    size_t pwrite(const void *buf, size_t size, int64_t offset) noexcept override
    {
        const char *p = static_cast<const char *>(buf);
        size_t done = 0;
        if (m_fd < 0) {
            failed(EBADF);
            return 0;
        }
        while (done < size) {
            ssize_t k = ::pwrite(m_fd, p + done, size - done, (off_t)offset + (off_t)done);
            if (k < 0 && errno == EINTR)
                continue;
            if (k <= 0) {
                failed(k < 0 ? errno : EIO);
                break;
            }
            done += (size_t)k;
        }
        if ((int64_t)(offset + (int64_t)done) > m_end)
            m_end = offset + (int64_t)done;
        return done;
    }
    /* TIFF writers may read back what they wrote. */
    size_t read(void *buf, size_t size) noexcept override
    {
        size_t n = pread(buf, size, m_pos);
        m_pos += (int64_t)n;
        return n;
    }
    size_t pread(void *buf, size_t size, int64_t offset) noexcept override
    {
        char *p = static_cast<char *>(buf);
        size_t done = 0;
        while (m_fd >= 0 && done < size) {
            ssize_t k = ::pread(m_fd, p + done, size - done, (off_t)offset + (off_t)done);
            if (k < 0 && errno == EINTR)
                continue;
            if (k < 0)
                failed(errno);
            if (k <= 0)
                break;
            done += (size_t)k;
        }
        return done;
    }
    size_t size() const noexcept override { return (size_t)m_end; }
    void flush() const noexcept override {}
    /* 0, or the errno of the first failure. */
    int error_number() const { return m_errno; }

private:
    void failed(int err) noexcept
    {
        if (m_errno == 0)
            m_errno = err ? err : EIO;
    }
    int m_fd;
    int64_t m_end = 0;
    int m_errno = 0;
};

struct aa__oiio_out {
    std::string path;
    std::unique_ptr<FdOutput> io;
    std::unique_ptr<ImageOutput> file;
    std::string format;
    int w = 0, c = 0, next_row = 0, height = 0;
    TypeDesc given;
};

/* The failure of a write: the descriptor's errno when a write failed (the
 * root cause: the writer's own message is often only "Write error"), else
 * OpenImageIO's message. */
static int write_failed(const aa__oiio_out *out, const char *what, const std::string &detail)
{
    const char *path = out->path.c_str();
    if (out->io->error_number() != 0)
        return report(AA_EIO, "%s: %s: %s", path, what, std::strerror(out->io->error_number()));
    return fail(AA_EIO, path, what, detail);
}

static int start_output(const char *path, const char *format, int w, int h, int c, int is_float,
                        double gamma, aa__oiio_out **result)
{
    std::unique_ptr<aa__oiio_out> out(new aa__oiio_out);
    out->path = path;
    out->format = format;
    out->w = w;
    out->c = c;
    out->height = h;
    out->given = is_float ? TypeDesc::DOUBLE : TypeDesc::UINT8;
    /* The writer comes from the real format: `path` is a temporary name. */
    out->file = ImageOutput::create(format);
    if (!out->file)
        return fail(AA_EIO, path, "no OpenImageIO writer for this format", OIIO::geterror());
    if (!out->file->supports("ioproxy"))
        return report(AA_EIO, "%s: the OpenImageIO writer for %s cannot write through a checked "
                      "file", path, format);
    /* O_EXCL: never write through a name someone else has just made. */
    int fd = ::open(path, O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0)
        return report(AA_EIO, "%s: cannot create: %s", path, std::strerror(errno));
    out->io.reset(new FdOutput(path, fd));
    ImageSpec spec(w, h, c, is_float ? TypeDesc::FLOAT : TypeDesc::UINT8);
    spec.alpha_channel = -1;
    if (is_float)
        spec.attribute("oiio:ColorSpace", "Linear");
    else
        tag_encoding(spec, gamma);
    /* OpenEXR's ZIP compression is lossless: the floats read back bit for
     * bit, in a run's images/ at a fraction of the size.  At zlib's level 6
     * rather than OpenEXR's default 4: a sampled image (few distinct values)
     * takes half the bytes, and the default suite's 66 .exr files 28.6 MB
     * instead of 35.1, written in about the same time; level 9 takes 10
     * times as long for 8% less. */
    if (!std::strcmp(format, "exr"))
        spec.attribute("compression", "zip:6");
    OIIO::Filesystem::IOProxy *proxy = out->io.get();
    spec.attribute("oiio:ioproxy", TypeDesc::PTR, &proxy);
    bool ok = out->file->open(path, spec);
    std::string why = call_error(*out->file, ok);
    if (!why.empty() || out->io->error_number() != 0)
        return write_failed(out.get(), "cannot create", why);
    *result = out.release();
    return AA_OK;
}

static int out_open(const char *path, const char *format, int w, int h, int c, int is_float,
                    double gamma, aa__oiio_out **out)
{
    *out = nullptr;
    return guarded(path, [&] { return start_output(path, format, w, h, c, is_float, gamma, out); });
}

static int out_rows(aa__oiio_out *out, int y0, int y1, const void *pixels)
{
    return guarded(out->path.c_str(), [&] {
        if (y0 != out->next_row || y1 <= y0 || y1 > out->height)
            return report(AA_EFAIL, "%s: rows %d to %d written out of order", out->path.c_str(),
                          y0, y1);
        bool ok = out->file->write_scanlines(y0, y1, 0, out->given, pixels);
        std::string why = call_error(*out->file, ok);
        if (!why.empty() || out->io->error_number() != 0)
            return write_failed(out, "cannot write", why);
        out->next_row = y1;
        return (int)AA_OK;
    });
}

/* Free `out` whatever happens: the writer first (its destructor may still
 * write through the proxy), then the proxy. */
static void release(aa__oiio_out *out) noexcept
{
    try {
        out->file.reset();
    } catch (...) {
    }
    delete out;
}

static int out_close(aa__oiio_out *out)
{
    int status = guarded(out->path.c_str(), [&] {
        if (out->next_row != out->height)
            return report(AA_EFAIL, "%s: closed after %d of %d rows", out->path.c_str(),
                          out->next_row, out->height);
        /* close() writes what the writer still holds (PNG's last chunks,
         * TIFF's directory): a full disk may only show here. */
        bool ok = out->file->close();
        std::string why = without_exif_note(out->format.c_str(), call_error(*out->file, ok));
        if (!why.empty() || out->io->error_number() != 0)
            return write_failed(out, "cannot write", why);
        out->file.reset();
        /* and close(2), which can report a deferred write error (NFS) */
        out->io->close();
        if (out->io->error_number() != 0)
            return write_failed(out, "cannot write", "");
        return (int)AA_OK;
    });
    release(out);
    return status;
}

static void out_abort(aa__oiio_out *out)
{
    if (out != nullptr)
        release(out);
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
    std::string why = call_error(*file, true);
    if (!why.empty())
        return fail(AA_EIO, path, "cannot read", why);
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
        /* The TIFF reader returns true for strips it could not read (a file
         * cut short) and leaves the failure in its error state. */
        bool ok = file.read_image(0, 0, 0, c, TypeDesc::DOUBLE, pixels);
        std::string why = call_error(file, ok);
        if (!why.empty())
            return fail(AA_EIO, path, "cannot read pixels", why);
        /* Closing reads nothing more, but a reader may report here what
         * went wrong before. */
        ok = file.close();
        why = call_error(file, ok);
        if (!why.empty())
            return fail(AA_EIO, path, "cannot read pixels", why);
        return (int)AA_OK;
    });
}

static void close_file(aa__oiio_in *in)
{
    if (in == nullptr)
        return;
    /* Only releases what open took (read_pixels closed and checked the file
     * when it read); nothing may throw out of here. */
    try {
        in->file->close();
    } catch (...) {
    }
    try {
        delete in;
    } catch (...) {
    }
}

/* The labels' font: Debian's fonts-dejavu-core (scripts/install-deps.sh
 * installs it).  OpenImageIO's own default face is not in Debian. */
#define AA_FONT "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"

/* Draw `text` into a W x H x C double buffer with OpenImageIO's FreeType text
 * renderer, left aligned, its line's top at (x, y): the baseline 0.8 size
 * below, wherever the text's own glyphs reach (aligning their tops would
 * set "point" lower than "(box)").  Used for the labels of montages and
 * error maps. */
static int draw_text(double *pixels, int w, int h, int c, int x, int y, const char *text,
                     int size, const float *colour)
{
    return guarded("text", [&] {
        ImageSpec spec(w, h, c, TypeDesc::DOUBLE);
        ImageBuf buf(spec, pixels);
        bool ok = ImageBufAlgo::render_text(buf, x, y + (int)lround(0.8 * size), text, size,
                                            AA_FONT, OIIO::cspan<float>(colour, c),
                                            ImageBufAlgo::TextAlignX::Left,
                                            ImageBufAlgo::TextAlignY::Baseline);
        std::string why = call_error(buf, ok);
        if (!why.empty())
            return fail(AA_EIO, "text", "cannot draw a label (is a font installed?)", why);
        return (int)AA_OK;
    });
}

/* The module's one entry point (oiio.h). */
extern "C" const aa__oiio_api *aa__oiio_entry(int version, aa__oiio_fail_fn library_fail)
{
    static const aa__oiio_api api = {out_open,  out_rows,   out_close, out_abort, open_file,
                                     read_pixels, close_file, draw_text};
    if (version != AA__OIIO_VERSION || library_fail == nullptr)
        return nullptr;
    report = library_fail;
    return &api;
}
