/* jpeg_add_exif_focal_35mm: see exif_jpeg.h. */
#include "exif_jpeg.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void put16le(unsigned char *p, unsigned v)
{
    p[0] = (unsigned char)(v & 0xff);
    p[1] = (unsigned char)(v >> 8);
}

static void put32le(unsigned char *p, unsigned long v)
{
    put16le(p, (unsigned)(v & 0xffff));
    put16le(p + 2, (unsigned)(v >> 16));
}

int jpeg_add_exif_focal_35mm(const char *path, unsigned focal_mm)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *jpg = n > 2 ? malloc((size_t)n) : NULL;
    int ok = jpg && fread(jpg, 1, (size_t)n, f) == (size_t)n && jpg[0] == 0xff && jpg[1] == 0xd8;
    fclose(f);
    if (!ok) {
        free(jpg);
        return -1;
    }
    /* TIFF: header (8 bytes), IFD0 at 8 (one entry: 18 bytes), the Exif
     * IFD at 26 (one entry: 18 bytes); each entry is tag, type, count and
     * the value (or its offset) in 4 bytes. */
    unsigned char tiff[44] = {'I', 'I', 42, 0};
    put32le(tiff + 4, 8);
    put16le(tiff + 8, 1);
    put16le(tiff + 10, 0x8769); /* ExifIFDPointer */
    put16le(tiff + 12, 4);      /* LONG */
    put32le(tiff + 14, 1);
    put32le(tiff + 18, 26);
    put32le(tiff + 22, 0); /* no next IFD */
    put16le(tiff + 26, 1);
    put16le(tiff + 28, 0xa405); /* FocalLengthIn35mmFilm */
    put16le(tiff + 30, 3);      /* SHORT */
    put32le(tiff + 32, 1);
    put16le(tiff + 36, focal_mm);
    put32le(tiff + 40, 0);
    unsigned len = 2 + 6 + sizeof tiff; /* the length field counts itself */
    unsigned char app1[4 + 6] = {0xff, 0xe1, (unsigned char)(len >> 8), (unsigned char)(len & 0xff),
                                 'E', 'x', 'i', 'f', 0, 0};
    f = fopen(path, "wb");
    ok = f && fwrite(jpg, 1, 2, f) == 2 && fwrite(app1, 1, sizeof app1, f) == sizeof app1 &&
         fwrite(tiff, 1, sizeof tiff, f) == sizeof tiff && fwrite(jpg + 2, 1, (size_t)n - 2, f) == (size_t)n - 2;
    if (f && fclose(f) != 0)
        ok = 0;
    free(jpg);
    return ok ? 0 : -1;
}
