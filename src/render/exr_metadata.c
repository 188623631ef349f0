/* The film's metadata in an OpenEXR header (exr_metadata.h).
 *
 * worldToCamera is the standard attribute, an Imath matrix (row vectors, so
 * the transpose of ours) into OpenEXR's camera frame (x right, y up, looking
 * down -z), which is Mitsuba's camera frame (x left, y up, looking down +z)
 * turned half a turn about y: its first and third rows negated, both ways. */
#include "render/exr_metadata.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const double flip[4] = {-1.0, 1.0, -1.0, 1.0};

exr_result_t exr_metadata_write(exr_context_t ctx, int part, const film_metadata *meta)
{
    char seed[32];
    snprintf(seed, sizeof seed, "%" PRIu64, meta->seed);
    exr_attr_m44f_t w2c;
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            w2c.m[4 * c + r] = (float)(meta->world_to_camera[r][c] * flip[r]);
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
    /* OpenEXR's standard capDate ("YYYY:MM:DD hh:mm:ss", local time) and
     * utcOffset (UTC minus local time, seconds): when the file was made. */
    time_t now = time(NULL);
    struct tm tm;
    localtime_r(&now, &tm);
    char date[32];
    strftime(date, sizeof date, "%Y:%m:%d %H:%M:%S", &tm);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_attr_set_string(ctx, part, "capDate", date);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_attr_set_float(ctx, part, "utcOffset", (float)-tm.tm_gmtoff);
    return rv;
}

/* The string attribute into out (empty when missing). */
static void read_string(exr_const_context_t ctx, int part, const char *name, char *out, size_t outlen)
{
    const char *s = NULL;
    int32_t len = 0;
    out[0] = '\0';
    if (exr_attr_get_string(ctx, part, name, &len, &s) == EXR_ERR_SUCCESS && s)
        snprintf(out, outlen, "%.*s", (int)len, s);
}

void exr_metadata_read(exr_const_context_t ctx, int part, film_metadata *meta)
{
    memset(meta, 0, sizeof *meta);
    int32_t spp = 0;
    char seed[32];
    exr_attr_m44f_t w2c;
    if (exr_attr_get_int(ctx, part, "spp", &spp) == EXR_ERR_SUCCESS && spp > 0)
        meta->spp = spp;
    read_string(ctx, part, "seed", seed, sizeof seed);
    meta->seed = strtoull(seed, NULL, 10);
    read_string(ctx, part, "integrator", meta->integrator, sizeof meta->integrator);
    read_string(ctx, part, "camera", meta->camera, sizeof meta->camera);
    read_string(ctx, part, "celadon/sampler", meta->sampler, sizeof meta->sampler);
    read_string(ctx, part, "celadon/sceneDigest", meta->scene_digest, sizeof meta->scene_digest);
    read_string(ctx, part, "celadon/scene", meta->scene_path, sizeof meta->scene_path);
    read_string(ctx, part, "celadon/commandLine", meta->command_line, sizeof meta->command_line);
    if (exr_attr_get_m44f(ctx, part, "worldToCamera", &w2c) == EXR_ERR_SUCCESS)
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++)
                meta->world_to_camera[r][c] = w2c.m[4 * c + r] * flip[r];
}
