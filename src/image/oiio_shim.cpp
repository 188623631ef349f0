// The one C++ file: OpenImageIO behind the extern "C" API of celadon/image.h.
extern "C" {
#include "celadon/image.h"
#include "celadon/atomic_file.h"
}

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

using namespace OIIO;

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

extern "C" int image_probe(const char *path, int *width, int *height, int *channels, char *err, size_t errlen)
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

extern "C" int image_read(const char *path, image_t *img, char *err, size_t errlen)
{
    std::memset(img, 0, sizeof *img);
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
    // The buffer holds floats whatever the file's format (read_image converts).
    ImageSpec fspec = spec;
    fspec.set_format(TypeDesc::FLOAT);
    ImageBuf buf(fspec);
    if (!in->read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, buf.localpixels()) || in->has_error()) {
        set_err(err, errlen, in->has_error() ? in->geterror() : std::string("cannot decode pixels (truncated or corrupt)"));
        return -1;
    }
    in->close();

    // EXIF orientation (1..8): ImageBufAlgo::reorient rotates/flips the pixels
    // so that "up" in the returned image is up in the scene.
    int orientation = spec.get_int_attribute("Orientation", 1);
    if (orientation != 1) {
        buf.specmod().attribute("Orientation", orientation);
        ImageBuf fixed;
        if (!ImageBufAlgo::reorient(fixed, buf)) {
            set_err(err, errlen, "cannot apply EXIF orientation: " + fixed.geterror());
            return -1;
        }
        buf = std::move(fixed);
    }
    const ImageSpec &out = buf.spec();
    size_t n = (size_t)out.width * out.height * out.nchannels;
    img->data = (float *)std::malloc(n * sizeof(float));
    if (!img->data) {
        set_err(err, errlen, "out of memory");
        return -1;
    }
    buf.get_pixels(ROI(0, out.width, 0, out.height, 0, 1, 0, out.nchannels), TypeDesc::FLOAT, img->data);
    img->width = out.width;
    img->height = out.height;
    img->channels = out.nchannels;
    img->bits = (int)spec.format.size() * 8;
    int bps = spec.get_int_attribute("oiio:BitsPerSample", 0);
    if (bps > 0)
        img->bits = bps;
    img->has_alpha = spec.alpha_channel >= 0 && spec.alpha_channel == out.nchannels - 1;
    return 0;
}

static int write_pixels(const char *path, int w, int h, int ch, TypeDesc type, const void *pixels, char *err,
                        size_t errlen)
{
    char tmp[4200];
    atomic_temp_name(path, tmp, sizeof tmp);
    auto out = ImageOutput::create(path);
    if (!out) {
        set_err(err, errlen, geterror());
        return -1;
    }
    ImageSpec spec(w, h, ch, type);
    if (ch == 4 || ch == 2)
        spec.alpha_channel = ch - 1;
    if (!out->open(tmp, spec) || !out->write_image(type, pixels) || !out->close()) {
        set_err(err, errlen, out->geterror());
        std::remove(tmp);
        return -1;
    }
    if (std::rename(tmp, path) != 0) {
        set_err(err, errlen, std::string("cannot rename into place: ") + std::strerror(errno));
        std::remove(tmp);
        return -1;
    }
    return 0;
}

extern "C" int image_write_u8(const char *path, int width, int height, int channels, const uint8_t *pixels,
                              char *err, size_t errlen)
{
    return write_pixels(path, width, height, channels, TypeDesc::UINT8, pixels, err, errlen);
}

extern "C" int image_write_u16(const char *path, int width, int height, int channels, const uint16_t *pixels,
                               char *err, size_t errlen)
{
    return write_pixels(path, width, height, channels, TypeDesc::UINT16, pixels, err, errlen);
}
