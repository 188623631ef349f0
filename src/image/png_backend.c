/* The PNG backend (image_backend.h) over libpng, in the library itself: the
 * format of the photos the tests draw, of every texture and overlay a
 * reconstruction writes and of most renders. It decodes and encodes
 * exactly as the OpenImageIO backend does (the same floats, the same text
 * chunks; tests/test_image_png.c holds the two side by side), so that a
 * process that touches only PNG never loads OpenImageIO's 270 libraries
 * (0.5 s of CPU each time: oiio_backend.h).
 *
 * It declines what OpenImageIO decodes its own way: palettes and samples
 * below 8 bits (expanded to bytes with their own bit depth reported), alpha
 * (premultiplied on reading) and EXIF (an orientation to apply, a focal
 * length to report). libpng reports errors by longjmp: every resource
 * lives in one struct that the error path frees. */
#include "image/png_backend.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* zlib's compression level of every PNG written (0..9) and one row filter,
 * Paeth, on every row instead of libpng's adaptive choice, which tries all
 * five (most of a write's instructions): a photo's overlay and texture
 * come out 4-8% larger for a third of the instructions (docs/BENCHMARKS.md,
 * "Batch throughput"). The OpenImageIO backend writes the same. */
enum { PNG_COMPRESSION_LEVEL = 3 };

typedef struct {
    FILE *file;
    png_structp png;
    png_infop info;
    png_bytep *rows;
    uint8_t *samples; /* the decoded rows, before they become floats */
    int writing;
    char message[200]; /* libpng's last error or warning */
} png_session;

static void on_error(png_structp png, png_const_charp message)
{
    png_session *s = png_get_error_ptr(png);
    snprintf(s->message, sizeof s->message, "%s", message);
    png_longjmp(png, 1);
}

/* Warnings (a bad CRC in an ancillary chunk, ...) do not stop the decode;
 * libpng would print them on stderr. */
static void on_warning(png_structp png, png_const_charp message)
{
    (void)png, (void)message;
}

static void session_end(png_session *s)
{
    if (s->png && s->writing)
        png_destroy_write_struct(&s->png, s->info ? &s->info : NULL);
    else if (s->png)
        png_destroy_read_struct(&s->png, s->info ? &s->info : NULL, NULL);
    free(s->rows);
    free(s->samples);
    if (s->file)
        fclose(s->file);
}

/* Opens path and reads its header when it is a PNG; IMAGE_BACKEND_DECLINED
 * when it is none (or one libpng cannot begin to read: OpenImageIO words
 * that refusal). */
static int read_begin(png_session *s, const char *path, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    s->file = fopen(path, "rb");
    if (!s->file) {
        snprintf(err, errlen, "cannot open: %s", strerror(errno));
        return -1;
    }
    png_byte sig[8];
    if (fread(sig, 1, sizeof sig, s->file) != sizeof sig || png_sig_cmp(sig, 0, sizeof sig) != 0)
        return IMAGE_BACKEND_DECLINED;
    s->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, s, on_error, on_warning);
    s->info = s->png ? png_create_info_struct(s->png) : NULL;
    if (!s->info) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    return 0;
}

/* Whether OpenImageIO is left to decode this PNG (see the top). */
static int declined(png_structp png, png_infop info)
{
    int depth = png_get_bit_depth(png, info), type = png_get_color_type(png, info);
    return depth < 8 || (type & PNG_COLOR_MASK_PALETTE) || (type & PNG_COLOR_MASK_ALPHA) ||
           png_get_valid(png, info, PNG_INFO_tRNS) || png_get_valid(png, info, PNG_INFO_eXIf);
}

/* The words of a decode that failed: a file that ends early says so. */
static void decode_error(const png_session *s, char *err, size_t errlen)
{
    if (feof(s->file) || strstr(s->message, "Not enough image data") || strstr(s->message, "end of file"))
        snprintf(err, errlen, "truncated PNG (the file ends before its image does: %s)", s->message);
    else
        snprintf(err, errlen, "damaged PNG (%s)", s->message[0] ? s->message : "libpng failed");
}

/* Decodes s's image (header read) into img. */
static int decode(png_session *s, image_t *img, char *err, size_t errlen)
{
    png_uint_32 w = png_get_image_width(s->png, s->info), h = png_get_image_height(s->png, s->info);
    int ch = png_get_channels(s->png, s->info), depth = png_get_bit_depth(s->png, s->info);
    /* Callers hold inputs to their own limits; this bounds the buffers. */
    if ((double)w * h > 400e6) {
        snprintf(err, errlen, "image too large to read");
        return -1;
    }
    size_t bytes = (size_t)depth / 8, row = (size_t)w * ch * bytes, n = (size_t)w * h * ch;
    img->data = malloc(n * sizeof(float));
    s->rows = malloc(h * sizeof *s->rows);
    s->samples = malloc((size_t)h * row);
    if (!img->data || !s->rows || !s->samples) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    const uint8_t *raw = s->samples;
    for (png_uint_32 y = 0; y < h; y++)
        s->rows[y] = s->samples + y * row;
    if (depth == 16)
        png_set_swap(s->png); /* native byte order */
    png_set_interlace_handling(s->png);
    png_read_update_info(s->png, s->info);
    png_read_image(s->png, s->rows);
    png_read_end(s->png, NULL);
    if (depth == 16) {
        const uint16_t *u = (const uint16_t *)raw;
        for (size_t i = 0; i < n; i++)
            img->data[i] = u[i] * (1.0f / 65535);
    } else {
        for (size_t i = 0; i < n; i++)
            img->data[i] = raw[i] * (1.0f / 255);
    }
    img->width = (int)w;
    img->height = (int)h;
    img->channels = ch;
    img->bits = depth;
    img->has_alpha = 0;
    return 0;
}

/* Reads the header of the PNG at path, then decodes its pixels into img,
 * or when img is NULL gives its size. */
static int read_png(const char *path, image_t *img, int *width, int *height, int *channels, char *err,
                    size_t errlen)
{
    png_session s;
    int rc = read_begin(&s, path, err, errlen);
    if (rc == 0) {
        if (setjmp(png_jmpbuf(s.png))) {
            decode_error(&s, err, errlen);
            rc = -1;
        } else {
            png_set_sig_bytes(s.png, 8);
            png_init_io(s.png, s.file);
            png_read_info(s.png, s.info);
            if (declined(s.png, s.info)) {
                rc = IMAGE_BACKEND_DECLINED;
            } else if (img) {
                rc = decode(&s, img, err, errlen);
            } else {
                *width = (int)png_get_image_width(s.png, s.info);
                *height = (int)png_get_image_height(s.png, s.info);
                *channels = png_get_channels(s.png, s.info);
            }
        }
    }
    session_end(&s);
    return rc;
}

static int png_probe(const char *path, int *width, int *height, int *channels, char *err, size_t errlen)
{
    return read_png(path, NULL, width, height, channels, err, errlen);
}

/* A PNG it decodes has no EXIF: it declines those with an eXIf chunk. */
static int png_exif_focal_35mm(const char *path, double *mm)
{
    int w, h, ch;
    char err[8];
    *mm = 0;
    return png_probe(path, &w, &h, &ch, err, sizeof err) == 0 ? 0 : IMAGE_BACKEND_DECLINED;
}

static int png_read(const char *path, image_t *img, char *err, size_t errlen)
{
    memset(img, 0, sizeof *img);
    int rc = read_png(path, img, NULL, NULL, NULL, err, errlen);
    if (rc != 0) {
        free(img->data);
        img->data = NULL;
    }
    return rc;
}

static int is_png_name(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && !strcasecmp(dot, ".png");
}

/* "YYYY:MM:DD HH:MM:SS" (EXIF's DateTime, as the renderer writes it) as
 * PNG's tIME chunk; 0 when it is not that. */
static int parse_date_time(const char *text, png_time *t)
{
    int y, mo, d, h, mi, s;
    if (sscanf(text, "%d:%d:%d %d:%d:%d", &y, &mo, &d, &h, &mi, &s) != 6)
        return 0;
    *t = (png_time){(png_uint_16)y, (png_byte)mo, (png_byte)d, (png_byte)h, (png_byte)mi, (png_byte)s};
    return 1;
}

/* The text attributes as OpenImageIO writes them: DateTime as tIME,
 * ImageDescription as the "Description" keyword, the rest by name. */
static void set_text(png_session *s, const image_text *text, int ntext, png_textp chunks)
{
    int n = 0;
    for (int i = 0; i < ntext; i++) {
        png_time t;
        if (!strcmp(text[i].name, "DateTime") && parse_date_time(text[i].value, &t)) {
            png_set_tIME(s->png, s->info, &t);
            continue;
        }
        chunks[n] = (png_text){.compression = PNG_TEXT_COMPRESSION_NONE,
                               .key = (char *)(!strcmp(text[i].name, "ImageDescription") ? "Description"
                                                                                          : text[i].name),
                               .text = (char *)text[i].value,
                               .text_length = strlen(text[i].value)};
        n++;
    }
    if (n)
        png_set_text(s->png, s->info, chunks, n);
}

static int png_write(const char *format_path, const char *file, int w, int h, int ch, image_sample_type type,
                     const void *pixels, const image_text *text, int ntext, char *err, size_t errlen)
{
    if (!is_png_name(format_path) || type == IMAGE_F32 || ch == 2 || ch == 4 || ch < 1 || ch > 4)
        return IMAGE_BACKEND_DECLINED; /* PNG holds no floats; alpha is OpenImageIO's */
    static const int color_of[] = {0, PNG_COLOR_TYPE_GRAY, 0, PNG_COLOR_TYPE_RGB};
    png_session s = {.writing = 1};
    png_text *chunks = malloc((size_t)(ntext > 0 ? ntext : 1) * sizeof *chunks);
    s.file = fopen(file, "wb");
    s.rows = malloc((size_t)h * sizeof *s.rows);
    int rc = -1;
    if (!s.file)
        snprintf(err, errlen, "cannot create: %s", strerror(errno));
    else if (!chunks || !s.rows || !(s.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &s, on_error, on_warning)) ||
             !(s.info = png_create_info_struct(s.png)))
        snprintf(err, errlen, "out of memory");
    else if (setjmp(png_jmpbuf(s.png))) {
        snprintf(err, errlen, "cannot write the PNG (%s)", s.message);
    } else {
        int depth = type == IMAGE_U16 ? 16 : 8;
        size_t row = (size_t)w * ch * (depth / 8);
        for (int y = 0; y < h; y++)
            s.rows[y] = (png_bytep)pixels + (size_t)y * row;
        png_init_io(s.png, s.file);
        png_set_compression_level(s.png, PNG_COMPRESSION_LEVEL);
        png_set_filter(s.png, PNG_FILTER_TYPE_BASE, PNG_FILTER_PAETH);
        png_set_IHDR(s.png, s.info, (png_uint_32)w, (png_uint_32)h, depth, color_of[ch], PNG_INTERLACE_NONE,
                     PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
        set_text(&s, text, ntext, chunks);
        png_write_info(s.png, s.info);
        if (depth == 16)
            png_set_swap(s.png); /* from native byte order */
        png_write_image(s.png, s.rows);
        png_write_end(s.png, NULL);
        rc = 0;
    }
    if (s.file && fclose(s.file) != 0 && rc == 0) {
        snprintf(err, errlen, "cannot write: %s", strerror(errno));
        rc = -1;
    }
    s.file = NULL;
    session_end(&s);
    free(chunks);
    return rc;
}

const image_backend png_backend = {png_probe, png_exif_focal_35mm, png_read, png_write};
