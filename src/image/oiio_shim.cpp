// OpenImageIO behind the extern "C" interface of image/image_backend.h
// (image/oiio_backend.h), built as its own shared object (libceladon-oiio.so).
// It calls nothing of libceladon's: it is loaded into programs that link
// libceladon statically.
extern "C" {
#include "image/oiio_backend.h"
}

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <string>

using namespace OIIO;

// zlib's compression level of every PNG written (0..9), and its row filter
// (libpng's PNG_FILTER_PAETH).
enum { PNG_COMPRESSION_LEVEL = 3, PNG_ROW_FILTER = 0x80 };

static void set_err(char *err, size_t errlen, const std::string &msg)
{
    if (!err || !errlen)
        return;
    // One line: OIIO messages may span several.
    std::string line = msg.empty() ? "unknown image error" : msg;
    for (char &c : line)
        if (c == '\n' || c == '\r')
            c = ' ';
    while (!line.empty() && line.back() == ' ')
        line.pop_back();
    std::snprintf(err, errlen, "%s", line.c_str());
}

// Every entry point runs its body through this: OpenImageIO and the format
// libraries under it may throw (a 36-byte GIF makes its reader throw
// std::length_error from ImageInput::open), and no exception may cross into C.
template <typename Body> static int guarded(char *err, size_t errlen, Body body)
{
    try {
        return body();
    } catch (const std::exception &e) {
        set_err(err, errlen, std::string("the image library failed on this file: ") + e.what());
    } catch (...) {
        set_err(err, errlen, "the image library failed on this file");
    }
    return -1;
}

static int probe(const char *path, int *width, int *height, int *channels, char *err, size_t errlen)
{
    auto in = ImageInput::open(path);
    if (!in) {
        set_err(err, errlen, geterror());
        return -1;
    }
    const ImageSpec &spec = in->spec();
    *width = spec.width;
    *height = spec.height;
    *channels = spec.nchannels;
    in->close();
    return 0;
}

static int guarded_probe(const char *path, int *width, int *height, int *channels, char *err, size_t errlen)
{
    return guarded(err, errlen, [&] { return probe(path, width, height, channels, err, errlen); });
}

static int exif_focal_35mm(const char *path, double *mm)
{
    *mm = 0;
    char err[8];
    guarded(err, sizeof err, [&] {
        auto in = ImageInput::open(path);
        if (!in) {
            (void)geterror(); // retrieved, so that none is left pending
            return 0;
        }
        *mm = in->spec().get_float_attribute("Exif:FocalLengthIn35mmFilm", 0.0f);
        in->close();
        return 0;
    });
    if (!(*mm > 0 && *mm < 1e5))
        *mm = 0;
    return 0;
}

// Decodes all pixels of the open file as floats into dst and closes it.
// read_image converts any format; 8-bit files without alpha are decoded as
// bytes and scaled here instead (v * (1/255), the very float OpenImageIO's
// conversion gives, which is several times slower). With alpha, OpenImageIO
// premultiplies, and must do so in float.
static int decode_floats(ImageInput *in, const ImageSpec &spec, float *dst, char *err, size_t errlen)
{
    const size_t n = (size_t)spec.width * spec.height * spec.nchannels;
    const bool bytes = spec.format == TypeDesc::UINT8 && spec.alpha_channel < 0;
    // Freed however the decoder returns, by a throw too.
    std::unique_ptr<unsigned char, decltype(&std::free)> owner(bytes ? (unsigned char *)std::malloc(n) : nullptr,
                                                               std::free);
    unsigned char *u = owner.get();
    if (bytes && !u) {
        set_err(err, errlen, "out of memory");
        return -1;
    }
    bool ok = bytes ? in->read_image(0, 0, 0, spec.nchannels, TypeDesc::UINT8, u)
                    : in->read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, dst);
    if (!ok || in->has_error()) {
        set_err(err, errlen, in->has_error() ? in->geterror() : std::string("cannot decode pixels (truncated or corrupt)"));
        return -1;
    }
    size_t i = 0;
    for (; bytes && i + 16 <= n; i += 16) // fixed-length inner loop: vectorised at -O2
        for (int k = 0; k < 16; k++)
            dst[i + k] = u[i + k] * (1.0f / 255);
    for (; bytes && i < n; i++)
        dst[i] = u[i] * (1.0f / 255);
    in->close();
    return 0;
}

// The returned image's float pixels.
static int alloc_pixels(image_t *img, size_t n, char *err, size_t errlen)
{
    img->data = (float *)std::malloc(n * sizeof(float));
    if (!img->data) {
        set_err(err, errlen, "out of memory");
        return -1;
    }
    return 0;
}

// Size and format fields of an image read from a file of the given spec.
static int finish_read(image_t *img, const ImageSpec &spec, int width, int height, int channels)
{
    img->width = width;
    img->height = height;
    img->channels = channels;
    img->bits = (int)spec.format.size() * 8;
    int bps = spec.get_int_attribute("oiio:BitsPerSample", 0);
    if (bps > 0)
        img->bits = bps;
    img->has_alpha = spec.alpha_channel >= 0 && spec.alpha_channel == channels - 1;
    return 0;
}

static void free_pixels(image_t *img)
{
    std::free(img->data);
    img->data = nullptr;
}

static int read_image(const char *path, image_t *img, char *err, size_t errlen)
{
    auto in = ImageInput::open(path);
    if (!in) {
        set_err(err, errlen, geterror());
        return -1;
    }
    ImageSpec spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1) {
        set_err(err, errlen, "not a 2D image");
        return -1;
    }
    // Refuse absurd sizes before allocating (callers apply their own limits too).
    if ((double)spec.width * spec.height > 400e6 || spec.nchannels > 16) {
        set_err(err, errlen, "image too large to read");
        return -1;
    }
    // Upright images (most photos) decode straight into the returned buffer:
    // no ImageBuf, no second copy of the pixels.
    int orientation = spec.get_int_attribute("Orientation", 1);
    if (orientation == 1) {
        if (alloc_pixels(img, (size_t)spec.width * spec.height * spec.nchannels, err, errlen))
            return -1;
        if (decode_floats(in.get(), spec, img->data, err, errlen)) {
            free_pixels(img);
            return -1;
        }
        return finish_read(img, spec, spec.width, spec.height, spec.nchannels);
    }
    // Otherwise through an ImageBuf of floats, reoriented.
    ImageSpec fspec = spec;
    fspec.set_format(TypeDesc::FLOAT);
    ImageBuf buf(fspec);
    if (decode_floats(in.get(), spec, (float *)buf.localpixels(), err, errlen))
        return -1;

    // EXIF orientation (2..8): ImageBufAlgo::reorient rotates/flips the pixels
    // so that "up" in the returned image is up in the scene.
    buf.specmod().attribute("Orientation", orientation);
    ImageBuf fixed;
    if (!ImageBufAlgo::reorient(fixed, buf)) {
        set_err(err, errlen, "cannot apply EXIF orientation: " + fixed.geterror());
        return -1;
    }
    const ImageSpec &out = fixed.spec();
    if (alloc_pixels(img, (size_t)out.width * out.height * out.nchannels, err, errlen))
        return -1;
    fixed.get_pixels(ROI(0, out.width, 0, out.height, 0, 1, 0, out.nchannels), TypeDesc::FLOAT, img->data);
    return finish_read(img, spec, out.width, out.height, out.nchannels);
}

static int guarded_read(const char *path, image_t *img, char *err, size_t errlen)
{
    std::memset(img, 0, sizeof *img);
    int rc = guarded(err, errlen, [&] { return read_image(path, img, err, errlen); });
    if (rc != 0)
        free_pixels(img);
    return rc;
}

static int write_pixels(const char *format_path, const char *file, int w, int h, int ch, TypeDesc type,
                        const void *pixels, const image_text *text, int ntext, char *err, size_t errlen)
{
    auto out = ImageOutput::create(format_path);
    if (!out) {
        set_err(err, errlen, geterror());
        return -1;
    }
    ImageSpec spec(w, h, ch, type);
    if (ch == 4 || ch == 2)
        spec.alpha_channel = ch - 1;
    // PNG: zlib level 3 (OpenImageIO's default is 6) and the Paeth filter on
    // every row instead of libpng's adaptive choice, which tries all five
    // (most of a write's instructions). A museum photo's overlay and texture
    // come out 4-8% larger for a third of the instructions
    // (docs/BENCHMARKS.md, "Batch throughput").
    spec.attribute("png:compressionLevel", PNG_COMPRESSION_LEVEL);
    spec.attribute("png:filter", PNG_ROW_FILTER);
    for (int i = 0; i < ntext; i++)
        spec.attribute(text[i].name, text[i].value);
    if (!out->open(file, spec) || !out->write_image(type, pixels) || !out->close()) {
        set_err(err, errlen, out->geterror());
        return -1;
    }
    return 0;
}

static int guarded_write(const char *format_path, const char *file, int w, int h, int ch, image_sample_type type,
                         const void *pixels, const image_text *text, int ntext, char *err, size_t errlen)
{
    TypeDesc t = type == IMAGE_U8 ? TypeDesc::UINT8 : type == IMAGE_U16 ? TypeDesc::UINT16 : TypeDesc::FLOAT;
    return guarded(err, errlen,
                   [&] { return write_pixels(format_path, file, w, h, ch, t, pixels, text, ntext, err, errlen); });
}

extern "C" const image_backend celadon_oiio_image_backend = {guarded_probe, exif_focal_35mm, guarded_read, guarded_write};
