/* Every channel of an OpenEXR into its own plane (exr_planes.h). */
#include "exr_planes.h"

#include <criterion/criterion.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void read_exr(const char *path, exr_planes *out)
{
    exr_context_t ctx;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    cr_assert_eq(exr_start_read(&ctx, path, &init), EXR_ERR_SUCCESS);
    exr_attr_box2i_t dw;
    cr_assert_eq(exr_get_data_window(ctx, 0, &dw), EXR_ERR_SUCCESS);
    out->width = dw.max.x - dw.min.x + 1;
    out->height = dw.max.y - dw.min.y + 1;
    const exr_attr_chlist_t *chl;
    cr_assert_eq(exr_get_channels(ctx, 0, &chl), EXR_ERR_SUCCESS);
    out->nch = chl->num_channels;
    cr_assert_leq(out->nch, EXR_PLANES_MAX);
    for (int c = 0; c < out->nch; c++) {
        snprintf(out->names[c], sizeof out->names[c], "%s", chl->entries[c].name.str);
        cr_assert_eq(chl->entries[c].pixel_type, EXR_PIXEL_FLOAT, "float32 on disk");
        out->planes[c] = calloc((size_t)out->width * out->height, sizeof(float));
    }
    int32_t lines;
    cr_assert_eq(exr_get_scanlines_per_chunk(ctx, 0, &lines), EXR_ERR_SUCCESS);
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    for (int y = dw.min.y, first = 1; y <= dw.max.y; y += lines, first = 0) {
        exr_chunk_info_t cinfo;
        cr_assert_eq(exr_read_scanline_chunk_info(ctx, 0, y, &cinfo), EXR_ERR_SUCCESS);
        cr_assert_eq(first ? exr_decoding_initialize(ctx, 0, &cinfo, &dec) : exr_decoding_update(ctx, 0, &cinfo, &dec),
                     EXR_ERR_SUCCESS);
        for (int c = 0; c < dec.channel_count; c++) {
            int k = 0;
            while (strcmp(out->names[k], dec.channels[c].channel_name) != 0)
                k++;
            dec.channels[c].decode_to_ptr = (uint8_t *)(out->planes[k] + (size_t)(cinfo.start_y - dw.min.y) * out->width);
            dec.channels[c].user_pixel_stride = sizeof(float);
            dec.channels[c].user_line_stride = out->width * (int32_t)sizeof(float);
            dec.channels[c].user_bytes_per_element = sizeof(float);
            dec.channels[c].user_data_type = EXR_PIXEL_FLOAT;
        }
        if (first)
            cr_assert_eq(exr_decoding_choose_default_routines(ctx, 0, &dec), EXR_ERR_SUCCESS);
        cr_assert_eq(exr_decoding_run(ctx, 0, &dec), EXR_ERR_SUCCESS);
    }
    exr_decoding_destroy(ctx, &dec);
    exr_finish(&ctx);
}

int plane_index(const exr_planes *e, const char *name)
{
    for (int c = 0; c < e->nch; c++)
        if (strcmp(e->names[c], name) == 0)
            return c;
    cr_assert_fail("no channel %s", name);
    return -1;
}

int exr_planes_has(const exr_planes *e, const char *name)
{
    for (int c = 0; c < e->nch; c++)
        if (strcmp(e->names[c], name) == 0)
            return 1;
    return 0;
}

void exr_planes_free(exr_planes *e)
{
    for (int c = 0; c < e->nch; c++)
        free(e->planes[c]);
    e->nch = 0;
}
