/* Baking the museum's lightmaps and probes. See museum_light.h. */
#include "museum/museum_light.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/scene.h"
#include "museum/jpeg_memory.h"
#include "museum/museum_bake.h"
#include "museum/rgbe.h"

vec3 museum_probe_point(const layout_exhibit *le, const museum_exhibit *e)
{
    return v3_add(le->vessel_base, v3(0, e->height_m / 2, 0));
}

/* Bakes the lightmap of q into a JPEG; stream_row keeps each map's sampler streams apart. */
static int bake_jpeg(const scene_t *s, const quad_spec *q, const lightmap_layout *m, uint32_t stream_row,
                     museum_file_bytes *out)
{
    long n = (long)m->width * m->height;
    float *lin = malloc((size_t)n * 3 * sizeof *lin);
    uint8_t *code = malloc((size_t)n * 3);
    int rc = -1;
    if (lin && code) {
        /* One sample a texel tells no variance: nothing for the denoiser to weigh. */
        bake_lightmap(s, q, m, stream_row, scene_spp(s) > 1, lin);
        bake_encode(lin, n, code);
        rc = jpeg_encode_rgb(code, m->width, m->height, MUSEUM_LIGHTMAP_JPEG_QUALITY, &out->bytes, &out->len);
    }
    free(lin), free(code);
    return rc;
}

static int bake_hdr(const scene_t *s, vec3 at, uint32_t stream_row, museum_file_bytes *out)
{
    float *lin = malloc((size_t)PROBE_WIDTH * PROBE_HEIGHT * 3 * sizeof *lin);
    if (!lin)
        return -1;
    bake_probe(s, at, stream_row, lin);
    int rc = rgbe_encode(lin, PROBE_WIDTH, PROBE_HEIGHT, &out->bytes, &out->len);
    free(lin);
    return rc;
}

/* Every map's streams start on a row of their own ("pixel" rows of the sampler). */
enum { STREAM_ROWS_PER_MAP = 512 };

static int bake_maps(const scene_t *s, const layout_t *l, museum_light *m)
{
    quad_spec room[ROOM_SURFACES];
    room_surfaces(l, room);
    uint32_t row = 0;
    for (int k = 0; k < ROOM_SURFACES; k++, row += STREAM_ROWS_PER_MAP) {
        m->room_layout[k] = lightmap_layout_for(&room[k], 1, ROOM_TEXELS_PER_M, 1, ROOM_TEXELS_MAX);
        if (bake_jpeg(s, &room[k], &m->room_layout[k], row, &m->room[k]) != 0)
            return -1;
    }
    for (int i = 0; i < m->n; i++, row += STREAM_ROWS_PER_MAP) {
        quad_spec q[PEDESTAL_FACES];
        pedestal_faces(&l->exhibits[i], q);
        m->pedestal_layout[i] = lightmap_layout_for(q, PEDESTAL_FACES, PEDESTAL_TEXELS_PER_M, PEDESTAL_TEXELS_MIN,
                                                    ROOM_TEXELS_MAX);
        if (bake_jpeg(s, q, &m->pedestal_layout[i], row % 65536, &m->pedestal[i]) != 0)
            return -1;
    }
    return 0;
}

static int bake_probes(const scene_t *s, const layout_t *l, const museum_exhibit *ex, museum_light *m)
{
    if (bake_hdr(s, l->camera_position, 0, &m->room_probe) != 0)
        return -1;
    for (int i = 0; i < m->n; i++)
        if (bake_hdr(s, museum_probe_point(&l->exhibits[i], &ex[i]), (uint32_t)((i + 1) * PROBE_HEIGHT) % 65536,
                     &m->probe[i]) != 0)
            return -1;
    return 0;
}

static scene_t *load(const char *path, int spp, char *err, size_t errlen)
{
    scene_options o = scene_options_default();
    o.spp = spp;
    return scene_create_from_file(path, NULL, 0, &o, err, errlen);
}

int museum_light_bake(const char *scene, const char *room_scene, const layout_t *l, const museum_exhibit *ex,
                      int spp, museum_light *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (errlen > 0)
        err[0] = '\0';
    out->n = l->n_exhibits;
    size_t n = (size_t)(out->n > 0 ? out->n : 1);
    out->pedestal_layout = calloc(n, sizeof *out->pedestal_layout);
    out->pedestal = calloc(n, sizeof *out->pedestal);
    out->probe = calloc(n, sizeof *out->probe);
    if (!out->pedestal_layout || !out->pedestal || !out->probe) {
        museum_light_free(out);
        snprintf(err, errlen, "cannot bake the light: out of memory");
        return -1;
    }
    scene_t *s = load(scene, spp, err, errlen);
    int rc = s ? bake_maps(s, l, out) : -1;
    scene_destroy(s);
    s = rc == 0 ? load(room_scene, spp, err, errlen) : NULL;
    rc = s ? bake_probes(s, l, ex, out) : -1;
    scene_destroy(s);
    if (rc != 0) {
        if (!err[0])
            snprintf(err, errlen, "cannot bake the light: out of memory");
        museum_light_free(out);
    }
    return rc;
}

void museum_light_free(museum_light *m)
{
    for (int k = 0; k < ROOM_SURFACES; k++)
        free(m->room[k].bytes);
    for (int i = 0; m->pedestal && i < m->n; i++)
        free(m->pedestal[i].bytes);
    for (int i = 0; m->probe && i < m->n; i++)
        free(m->probe[i].bytes);
    free(m->room_probe.bytes);
    free(m->pedestal_layout), free(m->pedestal), free(m->probe);
    memset(m, 0, sizeof *m);
}
