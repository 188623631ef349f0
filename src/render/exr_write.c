/* Float32 OpenEXR output through the OpenEXR 3 core C API (openexr.h). */
#include <errno.h>
#include <openexr.h>
#include <stdio.h>
#include <string.h>

#include "celadon/film.h"
#include "core/core.h"
#include "render/exr_error.h"
#include "render/exr_metadata.h"
#include "render/exr_read.h"

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

int exr_write_float(const char *path, int width, int height, int nch, const char *const *names,
                    const float *pixels, const film_metadata *meta, char *err, size_t errlen)
{
    return exr_write_float_attrs(path, width, height, nch, names, pixels, meta, NULL, 0, err, errlen);
}

/* The file with meta's attributes (NULL: none), attrs, and then like's
 * (NULL: none) where the file sets none of the name. */
static int write_file(const char *path, int width, int height, int nch, const char *const *names,
                      const float *pixels, const film_metadata *meta, const film_attr *attrs, int nattrs,
                      exr_const_context_t like, char *err, size_t errlen)
{
    char tmp[4200];
    atomic_temp_name(path, tmp, sizeof tmp);
    exr_error_clear();
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_error_remember;
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
        rv = exr_metadata_write(ctx, part, meta);
    for (int a = 0; a < nattrs && rv == EXR_ERR_SUCCESS; a++)
        rv = exr_attr_set_string(ctx, part, attrs[a].name, attrs[a].value);
    if (rv == EXR_ERR_SUCCESS && like)
        rv = exr_copy_unset_attributes(ctx, part, like, 0);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctx);
    if (rv == EXR_ERR_SUCCESS)
        rv = write_chunks(ctx, part, width, height, nch, names, pixels);
    if (ctx) {
        exr_result_t f = exr_finish(&ctx);
        if (rv == EXR_ERR_SUCCESS)
            rv = f;
    }
    if (rv == EXR_ERR_SUCCESS && rename(tmp, path) == 0) {
        atomic_temp_done(tmp);
        return 0;
    }
    int rename_errno = errno;
    remove(tmp);
    atomic_temp_done(tmp);
    if (rv == EXR_ERR_SUCCESS)
        snprintf(err, errlen, "%s: cannot rename into place: %s", path, strerror(rename_errno));
    else
        snprintf(err, errlen, "%s: cannot write EXR: %s", path, exr_error_text(rv));
    return -1;
}

int exr_write_float_attrs(const char *path, int width, int height, int nch, const char *const *names,
                          const float *pixels, const film_metadata *meta, const film_attr *attrs, int nattrs,
                          char *err, size_t errlen)
{
    return write_file(path, width, height, nch, names, pixels, meta, attrs, nattrs, NULL, err, errlen);
}

int exr_write_float_like(const char *path, int width, int height, int nch, const char *const *names,
                         const float *pixels, const exr_in *like, const film_attr *attrs, int nattrs, char *err,
                         size_t errlen)
{
    return write_file(path, width, height, nch, names, pixels, NULL, attrs, nattrs, exr_in_context(like), err,
                      errlen);
}
