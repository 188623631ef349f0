/* Float channels and string attributes of a scanline OpenEXR (exr_read.h). */
#include "render/exr_read.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "render/exr_error.h"
#include "render/exr_metadata.h"

struct exr_in {
    exr_context_t ctx;
    char path[4096];
    int width, height;
};

exr_in *exr_in_open(const char *path, char *err, size_t errlen)
{
    char why[256];
    if (input_check(path, INPUT_MAX_DATA_BYTES, NULL, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s: %s", path, why);
        return NULL;
    }
    exr_in *e = calloc(1, sizeof *e);
    if (!e)
        abort();
    snprintf(e->path, sizeof e->path, "%s", path);
    exr_error_clear();
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_error_remember;
    exr_result_t rv = exr_start_read(&e->ctx, path, &init);
    int parts = 0;
    exr_storage_t storage = EXR_STORAGE_LAST_TYPE;
    exr_attr_box2i_t dw;
    memset(&dw, 0, sizeof dw);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_count(e->ctx, &parts);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_storage(e->ctx, 0, &storage);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_data_window(e->ctx, 0, &dw);
    if (rv != EXR_ERR_SUCCESS) {
        snprintf(err, errlen, "%s: cannot read as OpenEXR: %s", path, exr_error_text(rv));
        exr_in_close(e);
        return NULL;
    }
    if (parts != 1 || storage != EXR_STORAGE_SCANLINE || dw.min.x != 0 || dw.min.y != 0) {
        snprintf(err, errlen, "%s: not a single-part scanline OpenEXR with its data window at (0, 0)", path);
        exr_in_close(e);
        return NULL;
    }
    e->width = dw.max.x + 1;
    e->height = dw.max.y + 1;
    return e;
}

void exr_in_close(exr_in *e)
{
    if (!e)
        return;
    if (e->ctx)
        exr_finish(&e->ctx);
    free(e);
}

void exr_in_size(const exr_in *e, int *width, int *height)
{
    *width = e->width;
    *height = e->height;
}

const char *exr_in_attr(const exr_in *e, const char *name)
{
    const char *s = NULL;
    int32_t len = 0;
    return exr_attr_get_string(e->ctx, 0, name, &len, &s) == EXR_ERR_SUCCESS ? s : NULL;
}

void exr_in_metadata(const exr_in *e, film_metadata *meta) { exr_metadata_read(e->ctx, 0, meta); }

int exr_in_has_channel(const exr_in *e, const char *name)
{
    const exr_attr_chlist_t *cl = NULL;
    if (exr_get_channels(e->ctx, 0, &cl) != EXR_ERR_SUCCESS)
        return 0;
    for (int c = 0; c < cl->num_channels; c++)
        if (!strcmp(cl->entries[c].name.str, name))
            return cl->entries[c].x_sampling == 1 && cl->entries[c].y_sampling == 1;
    return 0;
}

int exr_in_channel_count(const exr_in *e)
{
    const exr_attr_chlist_t *cl = NULL;
    return exr_get_channels(e->ctx, 0, &cl) == EXR_ERR_SUCCESS ? cl->num_channels : 0;
}

const char *exr_in_channel_name(const exr_in *e, int i)
{
    const exr_attr_chlist_t *cl = NULL;
    exr_get_channels(e->ctx, 0, &cl);
    return cl->entries[i].name.str;
}

exr_const_context_t exr_in_context(const exr_in *e) { return e->ctx; }

/* Points each decoded channel that is one of names at its place in pixels. */
static void aim_channels(exr_decode_pipeline_t *dec, const exr_chunk_info_t *ci, int width, int nch,
                         const char *const *names, float *pixels)
{
    for (int c = 0; c < dec->channel_count; c++) {
        exr_coding_channel_info_t *ch = &dec->channels[c];
        ch->decode_to_ptr = NULL;
        for (int k = 0; k < nch; k++)
            if (!strcmp(names[k], ch->channel_name)) {
                ch->decode_to_ptr = (uint8_t *)(pixels + ((size_t)ci->start_y * width) * nch + k);
                ch->user_pixel_stride = nch * (int32_t)sizeof(float);
                ch->user_line_stride = width * nch * (int32_t)sizeof(float);
                ch->user_bytes_per_element = sizeof(float);
                ch->user_data_type = EXR_PIXEL_FLOAT;
            }
    }
}

int exr_in_read(exr_in *e, int nch, const char *const *names, float *pixels, char *err, size_t errlen)
{
    for (int k = 0; k < nch; k++)
        if (!exr_in_has_channel(e, names[k])) {
            snprintf(err, errlen, "%s: has no channel %s", e->path, names[k]);
            return -1;
        }
    exr_error_clear();
    int32_t lines = 1;
    exr_result_t rv = exr_get_scanlines_per_chunk(e->ctx, 0, &lines);
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    int initialized = 0;
    for (int y = 0; rv == EXR_ERR_SUCCESS && y < e->height; y += lines) {
        exr_chunk_info_t ci;
        rv = exr_read_scanline_chunk_info(e->ctx, 0, y, &ci);
        if (rv != EXR_ERR_SUCCESS)
            break;
        rv = initialized ? exr_decoding_update(e->ctx, 0, &ci, &dec) : exr_decoding_initialize(e->ctx, 0, &ci, &dec);
        if (rv != EXR_ERR_SUCCESS)
            break;
        aim_channels(&dec, &ci, e->width, nch, names, pixels);
        if (!initialized) {
            initialized = 1;
            rv = exr_decoding_choose_default_routines(e->ctx, 0, &dec);
            if (rv != EXR_ERR_SUCCESS)
                break;
        }
        rv = exr_decoding_run(e->ctx, 0, &dec);
    }
    if (initialized) {
        exr_result_t d = exr_decoding_destroy(e->ctx, &dec);
        if (rv == EXR_ERR_SUCCESS)
            rv = d;
    }
    if (rv == EXR_ERR_SUCCESS)
        return 0;
    snprintf(err, errlen, "%s: cannot decode: %s", e->path, exr_error_text(rv));
    return -1;
}
