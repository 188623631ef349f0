/* Lightmaps and probes from scene_radiance. See museum_bake.h. */
#include "museum/museum_bake.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/denoise.h"
#include "celadon/film.h"

static void put(float *out, long i, rgb L)
{
    out[3 * i] = (float)L.r, out[3 * i + 1] = (float)L.g, out[3 * i + 2] = (float)L.b;
}

/* Copies texel (sx, sy) of the image to (dx, dy). */
static void copy_texel(float *rgb, int width, int sx, int sy, int dx, int dy)
{
    memcpy(rgb + 3 * ((long)dy * width + dx), rgb + 3 * ((long)sy * width + sx), 3 * sizeof(float));
}

static void fill_gutter(const lightmap_layout *m, int k, float *rgb)
{
    int x0 = k * (m->tile_w + 2), w = m->tile_w, h = m->tile_h;
    for (int y = 1; y <= h; y++) {
        copy_texel(rgb, m->width, x0 + 1, y, x0, y);
        copy_texel(rgb, m->width, x0 + w, y, x0 + w + 1, y);
    }
    for (int x = x0; x < x0 + w + 2; x++) {
        copy_texel(rgb, m->width, x, 1, x, 0);
        copy_texel(rgb, m->width, x, h, x, h + 1);
    }
}

/* The denoiser's channels of a lightmap texel (denoise.h): its radiance,
 * a grey albedo and unit depth (a flat diffuse face: nothing to tell apart
 * but the face), the face's normal, its estimate's variance. */
static void put_features(float *px, rgb L, vec3 n, double variance)
{
    const float f[DENOISE_CHANNELS] = {(float)L.r, (float)L.g, (float)L.b, 0.5f, 0.5f, 0.5f,
                                       (float)n.x, (float)n.y, (float)n.z, 1.0f, (float)variance};
    memcpy(px, f, sizeof f);
}

void bake_lightmap(const scene_t *s, const quad_spec *q, const lightmap_layout *m, uint32_t stream_row, int denoise,
                   float *out)
{
    long per_tile = (long)m->tile_w * m->tile_h, total = per_tile * m->n, npix = (long)m->width * m->height;
    float *in = calloc((size_t)npix * DENOISE_CHANNELS, sizeof *in);
    if (!in)
        abort();
#pragma omp parallel for schedule(dynamic, 64)
    for (long i = 0; i < total; i++) {
        int k = (int)(i / per_tile), x = (int)(i % per_tile % m->tile_w), y = (int)(i % per_tile / m->tile_w);
        double sp, tp, variance;
        lightmap_texel_st(m, x, y, &sp, &tp);
        vec3 n = v3_norm(v3_cross(q[k].du, q[k].dv));
        vec3 p = v3_add(q[k].corner, v3_add(v3_scale(q[k].du, sp), v3_scale(q[k].dv, tp)));
        ray3 r = {v3_add(p, v3_scale(n, BAKE_OFFSET)), v3_scale(n, -1)};
        int ix = k * (m->tile_w + 2) + 1 + x, iy = 1 + y;
        rgb L = scene_radiance(s, &r, 0, 2 * BAKE_OFFSET, (uint32_t)ix, (uint32_t)iy + stream_row, &variance);
        put_features(in + ((long)iy * m->width + ix) * DENOISE_CHANNELS, L, n, variance);
    }
    if (!denoise)
        for (long i = 0; i < npix; i++)
            memcpy(out + 3 * i, in + i * DENOISE_CHANNELS, 3 * sizeof *out);
    else if (denoise_image(m->width, m->height, in, out) != 0)
        abort(); /* out of memory in the denoiser: as for in above (the bake has no error path) */
    free(in);
    for (int k = 0; k < m->n; k++)
        fill_gutter(m, k, out);
}

void bake_probe(const scene_t *s, vec3 at, uint32_t stream_row, float *rgb)
{
#pragma omp parallel for schedule(dynamic, 64)
    for (long i = 0; i < (long)PROBE_WIDTH * PROBE_HEIGHT; i++) {
        int x = (int)(i % PROBE_WIDTH), y = (int)(i / PROBE_WIDTH);
        double phi = 2 * M_PI * ((x + 0.5) / PROBE_WIDTH - 0.5), theta = M_PI * (0.5 - (y + 0.5) / PROBE_HEIGHT);
        ray3 r = {at, v3(cos(theta) * cos(phi), sin(theta), cos(theta) * sin(phi))};
        put(rgb, i, scene_radiance(s, &r, 0, INFINITY, (uint32_t)x, (uint32_t)y + stream_row, NULL));
    }
}

void bake_encode(const float *rgb, long n, uint8_t *out)
{
    for (long i = 0; i < 3 * n; i++)
        out[i] = (uint8_t)lrint(film_view_encode(FILM_VIEW_STANDARD, rgb[i]) * 255.0);
}
