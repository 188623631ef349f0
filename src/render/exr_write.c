/* Float32 OpenEXR output through the OpenEXR 3 core C API (openexr.h). */
#include <errno.h>
#include <openexr.h>
#include <stdio.h>
#include <string.h>

#include "core/core.h"
#include "celadon/film.h"

/* The library reports details through a callback; keep the last one. */
static _Thread_local char exr_message[256];

static void remember_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    snprintf(exr_message, sizeof exr_message, "%s", msg ? msg : exr_get_default_error_message(code));
}

/* Encodes every chunk of the part; channel pointers into the interleaved
 * buffer are matched by name since the file stores channels sorted. */
static exr_result_t write_chunks(exr_context_t ctx, int part, int width, int height, int nch,
                                 const char *const *names, const float *pixels)
{
    int32_t lines;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctx, part, &lines);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    int initialized = 0;
    for (int y = 0; rv == EXR_ERR_SUCCESS && y < height; y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_write_scanline_chunk_info(ctx, part, y, &cinfo);
        if (rv != EXR_ERR_SUCCESS)
            break;
        rv = initialized ? exr_encoding_update(ctx, part, &cinfo, &enc)
                         : exr_encoding_initialize(ctx, part, &cinfo, &enc);
        if (rv != EXR_ERR_SUCCESS)
            break;
        for (int c = 0; c < enc.channel_count; c++) {
            int k = 0;
            while (k < nch && strcmp(names[k], enc.channels[c].channel_name) != 0)
                k++;
            exr_coding_channel_info_t *ch = &enc.channels[c];
            ch->encode_from_ptr = (const uint8_t *)(pixels + ((size_t)cinfo.start_y * width) * nch + k);
            ch->user_pixel_stride = nch * (int32_t)sizeof(float);
            ch->user_line_stride = width * nch * (int32_t)sizeof(float);
            ch->user_bytes_per_element = sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
        }
        if (!initialized) {
            rv = exr_encoding_choose_default_routines(ctx, part, &enc);
            initialized = 1;
            if (rv != EXR_ERR_SUCCESS)
                break;
        }
        rv = exr_encoding_run(ctx, part, &enc);
    }
    if (initialized) {
        exr_result_t d = exr_encoding_destroy(ctx, &enc);
        if (rv == EXR_ERR_SUCCESS)
            rv = d;
    }
    return rv;
}

/* The header attributes of meta (film.h). worldToCamera is the standard
 * attribute, an Imath matrix (row vectors, so the transpose of ours) into
 * OpenEXR's camera frame (x right, y up, looking down -z), which is
 * Mitsuba's camera frame (x left, y up, looking down +z) turned half a
 * turn about y. */
static exr_result_t write_metadata(exr_context_t ctx, int part, const film_metadata *meta)
{
    char seed[32];
    snprintf(seed, sizeof seed, "%llu", (unsigned long long)meta->seed);
    exr_attr_m44f_t w2c;
    static const double flip[3] = {-1.0, 1.0, -1.0};
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            w2c.m[4 * c + r] = (float)(meta->world_to_camera[r][c] * (r < 3 ? flip[r] : 1.0));
    exr_result_t rv = exr_attr_set_int(ctx, part, "spp", meta->spp);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_attr_set_string(ctx, part, "seed", seed);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_attr_set_string(ctx, part, "renderer", "celadon");
    if (rv == EXR_ERR_SUCCESS && meta->integrator[0])
        rv = exr_attr_set_string(ctx, part, "integrator", meta->integrator);
    if (rv == EXR_ERR_SUCCESS && meta->camera[0])
        rv = exr_attr_set_string(ctx, part, "camera", meta->camera);
    if (rv == EXR_ERR_SUCCESS && meta->camera[0])
        rv = exr_attr_set_m44f(ctx, part, "worldToCamera", &w2c);
    return rv;
}

int exr_write_float(const char *path, int width, int height, int nch, const char *const *names,
                    const float *pixels, const film_metadata *meta, char *err, size_t errlen)
{
    char tmp[4200];
    atomic_temp_name(path, tmp, sizeof tmp);
    exr_message[0] = '\0';
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = remember_error;
    exr_context_t ctx = NULL;
    int part = 0;
    exr_result_t rv = exr_start_write(&ctx, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_part(ctx, "rgb", EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctx, part, width, height, EXR_COMPRESSION_ZIP);
    for (int c = 0; c < nch && rv == EXR_ERR_SUCCESS; c++)
        rv = exr_add_channel(ctx, part, names[c], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (rv == EXR_ERR_SUCCESS && meta && meta->spp > 0)
        rv = write_metadata(ctx, part, meta);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctx);
    if (rv == EXR_ERR_SUCCESS)
        rv = write_chunks(ctx, part, width, height, nch, names, pixels);
    if (ctx) {
        exr_result_t f = exr_finish(&ctx);
        if (rv == EXR_ERR_SUCCESS)
            rv = f;
    }
    if (rv == EXR_ERR_SUCCESS && rename(tmp, path) == 0)
        return 0;
    int rename_errno = errno;
    remove(tmp);
    if (rv == EXR_ERR_SUCCESS)
        snprintf(err, errlen, "%s: cannot rename into place: %s", path, strerror(rename_errno));
    else
        snprintf(err, errlen, "%s: cannot write EXR: %s", path,
                 exr_message[0] ? exr_message : exr_get_default_error_message(rv));
    return -1;
}
