/* See jpeg_memory.h. libjpeg's default error handler exits the process;
 * this one jumps back out of the encoder, which is then destroyed. */
#include "museum/jpeg_memory.h"

#include <setjmp.h>
#include <stdio.h> /* before jpeglib.h, which uses FILE */
#include <stdlib.h>
#include <string.h>

#include <jpeglib.h>

typedef struct {
    struct jpeg_error_mgr mgr;
    jmp_buf escape;
} error_trap;

static void on_error(j_common_ptr cinfo)
{
    error_trap *t = (error_trap *)(void *)cinfo->err;
    longjmp(t->escape, 1);
}

int jpeg_encode_rgb(const uint8_t *rgb, int width, int height, int quality, uint8_t **jpeg, size_t *len)
{
    *jpeg = NULL;
    *len = 0;
    if (width < 1 || height < 1 || width > JPEG_MAX_DIMENSION || height > JPEG_MAX_DIMENSION)
        return -1;
    struct jpeg_compress_struct c;
    error_trap trap;
    unsigned char *out = NULL;
    unsigned long out_len = 0;
    c.err = jpeg_std_error(&trap.mgr);
    trap.mgr.error_exit = on_error;
    if (setjmp(trap.escape)) {
        jpeg_destroy_compress(&c);
        free(out);
        return -1;
    }
    jpeg_create_compress(&c);
    jpeg_mem_dest(&c, &out, &out_len);
    c.image_width = (JDIMENSION)width;
    c.image_height = (JDIMENSION)height;
    c.input_components = 3;
    c.in_color_space = JCS_RGB;
    jpeg_set_defaults(&c);
    jpeg_set_quality(&c, quality, TRUE);
    jpeg_start_compress(&c, TRUE);
    while (c.next_scanline < c.image_height) {
        JSAMPROW row = (JSAMPROW)(rgb + (size_t)c.next_scanline * (size_t)width * 3);
        jpeg_write_scanlines(&c, &row, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    *jpeg = malloc(out_len);
    if (!*jpeg) {
        free(out);
        return -1;
    }
    memcpy(*jpeg, out, out_len);
    *len = out_len;
    free(out);
    return 0;
}
