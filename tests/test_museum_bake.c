/* The museum's light bake (src/museum/museum_bake.h, room_surfaces.h,
 * rgbe.h) against closed forms: a diffuse floor under a point light
 * sends L = rho / pi * I h / r^3 from every texel (the bake traces the
 * render's own integrator, so this is its direct light, exact with next
 * event estimation); a probe sees a small emitter only in the direction
 * three.js's equirectangular lookup gives it; a lightmap texel's UV on the
 * glb's quad is the texel's centre; RGBE keeps 8 bits of mantissa. */
#include <math.h>

#include "museum/museum_bake.h"
#include "museum/rgbe.h"
#include "museum/room_surfaces.h"
#include "test_render_util.h"


Test(museum_bake, floor_under_point_light_is_closed_form)
{
    const double rho = 0.5, I = 3.0, h = 0.8;
    render_fixture f;
    render_fixture_open(&f);
    /* A 2 m x 2 m floor at y = 0 facing up (the default rectangle faces +z: turned by -90 deg about x). */
    scene_t *s = render_scene_of(&f, "<shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/>"
                                "</transform><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.5\"/></bsdf>"
                                "</shape><emitter type=\"point\"><point name=\"position\" x=\"0.3\" y=\"0.8\" z=\"0\"/>"
                                "<rgb name=\"intensity\" value=\"3\"/></emitter>");
    quad_spec q = {{-1, 0, 1}, {2, 0, 0}, {0, 0, -2}};
    lightmap_layout m = lightmap_layout_for(&q, 1, 8.0, 1, 64);
    cr_assert_eq(m.tile_w, 16);
    float *rgb = malloc(sizeof(float) * 3 * (size_t)m.width * m.height);
    for (int denoise = 0; denoise <= 1; denoise++) {
    bake_lightmap(s, &q, &m, 0, denoise, rgb);
    double worst = 0;
    for (int y = 0; y < m.tile_h; y++)
        for (int x = 0; x < m.tile_w; x++) {
            double sp, tp;
            lightmap_texel_st(&m, x, y, &sp, &tp);
            vec3 p = v3_add(q.corner, v3_add(v3_scale(q.du, sp), v3_scale(q.dv, tp)));
            double dx = p.x - 0.3, dz = p.z, r = sqrt(dx * dx + dz * dz + h * h);
            double truth = rho / M_PI * I * h / (r * r * r);
            const float *got = rgb + 3 * ((size_t)(y + 1) * m.width + x + 1);
            for (int c = 0; c < 3; c++)
                worst = fmax(worst, fabs(got[c] - truth) / truth);
        }
    /* Noise-free light through the denoiser: its regression keeps a smooth field. */
    cr_expect_lt(worst, denoise ? 0.01 : 1e-3, "denoise %d: worst relative error %g", denoise, worst);
    }
    /* The gutters repeat the borders. */
    for (int c = 0; c < 3; c++) {
        cr_expect_eq(rgb[3 * (5 * m.width) + c], rgb[3 * (5 * m.width + 1) + c]);
        cr_expect_eq(rgb[3 * (m.width - 1) + c], rgb[3 * (m.width + m.width - 2) + c]);
    }
    free(rgb);
    scene_destroy(s);
    render_fixture_close(&f);
}

Test(museum_bake, probe_sees_emitter_where_threejs_looks)
{
    render_fixture f;
    render_fixture_open(&f);
    /* A 0.4 m square emitter 1 m along +z, facing the probe at the origin. */
    scene_t *s = render_scene_of(&f, "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"0.2\"/>"
                                "<rotate y=\"1\" angle=\"180\"/><translate z=\"1\"/></transform>"
                                "<emitter type=\"area\"><rgb name=\"radiance\" value=\"2\"/></emitter></shape>");
    float *rgb = malloc(sizeof(float) * 3 * PROBE_WIDTH * PROBE_HEIGHT);
    bake_probe(s, v3(0, 0, 0), 0, rgb);
    /* three.js: u = atan2(z, x) / 2 pi + 1/2, so +z is u = 3/4; the middle row is the horizon. */
    int lit = 0;
    for (int y = 0; y < PROBE_HEIGHT; y++)
        for (int x = 0; x < PROBE_WIDTH; x++) {
            double phi = 2 * M_PI * ((x + 0.5) / PROBE_WIDTH - 0.5), th = M_PI * (0.5 - (y + 0.5) / PROBE_HEIGHT);
            vec3 d = v3(cos(th) * cos(phi), sin(th), cos(th) * sin(phi));
            double t = 1.0 / d.z; /* where the ray meets z = 1 */
            int inside = d.z > 0 && fabs(t * d.x) < 0.19 && fabs(t * d.y) < 0.19;
            int outside = d.z <= 0 || fabs(t * d.x) > 0.21 || fabs(t * d.y) > 0.21;
            float v = rgb[3 * (y * PROBE_WIDTH + x)];
            if (inside) {
                cr_expect_float_eq(v, 2.0f, 1e-5f, "texel %d,%d", x, y);
                lit++;
            }
            if (outside)
                cr_expect_eq(v, 0.0f, "texel %d,%d", x, y);
        }
    cr_expect_gt(lit, 4);
    cr_expect_gt(rgb[3 * (PROBE_HEIGHT / 2 * PROBE_WIDTH + 3 * PROBE_WIDTH / 4)], 1.0f);
    free(rgb);
    scene_destroy(s);
    render_fixture_close(&f);
}

Test(museum_bake, lightmap_uv_is_texel_centre)
{
    quad_spec q[PEDESTAL_FACES];
    layout_exhibit e = {.centre = {1, 0, -2}, .width = 0.5, .pedestal_height = 0.8};
    pedestal_faces(&e, q);
    lightmap_layout m = lightmap_layout_for(q, PEDESTAL_FACES, PEDESTAL_TEXELS_PER_M, PEDESTAL_TEXELS_MIN, 256);
    cr_assert_eq(m.width, PEDESTAL_FACES * (m.tile_w + 2));
    for (int k = 0; k < PEDESTAL_FACES; k++) {
        vec3 n = v3_norm(v3_cross(q[k].du, q[k].dv));
        vec3 mid = v3_add(q[k].corner, v3_scale(v3_add(q[k].du, q[k].dv), 0.5));
        cr_expect_gt(v3_dot(n, v3_sub(mid, v3(1, 0.4, -2))), 0, "face %d faces out", k);
        for (int y = 0; y < m.tile_h; y += 3)
            for (int x = 0; x < m.tile_w; x += 3) {
                double sp, tp, u, v;
                lightmap_texel_st(&m, x, y, &sp, &tp);
                lightmap_uv(&m, k, sp, tp, &u, &v);
                cr_expect_float_eq(u * m.width, k * (m.tile_w + 2) + 1 + x + 0.5, 1e-9);
                cr_expect_float_eq(v * m.height, 1 + y + 0.5, 1e-9);
            }
    }
}

Test(museum_bake, rgbe_keeps_eight_bits)
{
    const float c[4][3] = {{1, 0.5f, 0.25f}, {1e-3f, 2e-3f, 3e-3f}, {700, 1, 0}, {0.1f, 0.1f, 0.1f}};
    for (int i = 0; i < 4; i++) {
        uint8_t e[4];
        float back[3];
        rgbe_from_float(c[i], e);
        rgbe_to_float(e, back);
        float m = fmaxf(fmaxf(c[i][0], c[i][1]), c[i][2]);
        for (int k = 0; k < 3; k++)
            cr_expect_leq(fabsf(back[k] - c[i][k]), m / 128, "%g -> %g", c[i][k], back[k]);
    }
    float black[3] = {0, 0, 0}, back[3];
    uint8_t e[4];
    rgbe_from_float(black, e);
    rgbe_to_float(e, back);
    cr_expect_eq(back[0] + back[1] + back[2], 0.0f);
}
