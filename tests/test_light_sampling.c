/* Sampling lights by solid angle, and picking them: the spherical
 * rectangle and the sphere's cone are uniform in the solid angle the shape
 * subtends (their density is one over its closed form, and the samples fall
 * into sub-regions as often as those subtend, by chi-square), the density a
 * ray hit reports is the sampler's (what MIS weighs with), and where the
 * solid-angle sampler does not apply the area sampler's density is
 * converted consistently; the light tree picks each emitter as often as its
 * pmf says, the pmfs sum to at most one, and a light is never starved
 * where it shines. The integration with the path tracer is checked against closed
 * forms in test_render_lights.c. */
#include "emitters/emitter_impl.h"
#include "render/scene_impl.h"
#include "test_bsdf_support.h"
#include "test_render_util.h"

/* The fixture opened, body loaded, and its first shape in *sh. */
static scene_t *open_first_shape(render_fixture *f, const char *body, const shape_t **sh)
{
    render_fixture_open(f);
    scene_t *s = render_scene_of(f, body);
    *sh = &s->shapes.items[0];
    return s;
}

/* The solid angle of the rectangle [x0,x1] x [y0,y1] in the plane z = h
 * seen from the origin, from the corner-anchored closed form
 * atan(x y / (h sqrt(x^2 + y^2 + h^2))) by inclusion-exclusion. */
static double rect_solid_angle(double x0, double x1, double y0, double y1, double h)
{
#define F(x, y) atan((x) * (y) / (h * sqrt((x) * (x) + (y) * (y) + h * h)))
    return F(x1, y1) - F(x0, y1) - F(x1, y0) + F(x0, y0);
#undef F
}

/* The hit shape_sample_from gives is where a ray from ref toward it first
 * meets the shape, and the density there is the sample's. */
static void check_hit_consistent(const scene_t *s, const shape_t *sh, vec3 ref, const surface_hit *h, double pdf)
{
    vec3 d = v3_sub(h->p, ref);
    double dist = v3_len(d);
    ray3 r = {ref, v3_scale(d, 1.0 / dist)};
    surface_hit g;
    cr_assert(shape_list_intersect(&s->shapes, &r, 0.0, dist * (1.0 + 1e-6) + 1e-6, &g));
    cr_assert_lt(v3_len(v3_sub(g.p, h->p)), 1e-5 * (1.0 + dist), "the ray meets the shape elsewhere");
    double q = shape_pdf_from(sh, ref, &g);
    cr_assert_float_eq(q, pdf, 1e-6 * pdf, "hit density %g, sampled %g", q, pdf);
}

/* A 3 x 2 rectangle in the plane z = 0 (corner (-1.5,-1) + a (3,0,0) + b
 * (0,2,0)), turned by to_world's rotation; refs at height h above points
 * over and beside it. */
Test(light_sampling, spherical_rectangle_is_uniform_in_solid_angle)
{
    render_fixture f;
    render_fixture_open(&f);
    scene_t *s = render_scene_of(&f, "<shape type=\"rectangle\"><transform name=\"to_world\"><scale x=\"1.5\" y=\"1\"/>"
                                "<rotate x=\"1\" angle=\"30\"/><translate y=\"2\"/></transform>"
                                "<emitter type=\"area\"/></shape>");
    const shape_t *sh = &s->shapes.items[0];
    cr_assert_not_null(sh->solid_angle, "an unsheared rectangle has the spherical sampler");
    vec3 ex = v3_norm(v3_sub(transform_point(&sh->to_world, v3(1, -1, 0)), transform_point(&sh->to_world, v3(-1, -1, 0))));
    vec3 ey = v3_norm(v3_sub(transform_point(&sh->to_world, v3(-1, 1, 0)), transform_point(&sh->to_world, v3(-1, -1, 0))));
    vec3 ez = v3_cross(ex, ey), centre = transform_point(&sh->to_world, v3(0, 0, 0));
    const double above[][3] = {{0.2, 0.3, 1.0}, {2.5, -1.7, 0.4}, {0.0, 0.0, 0.05}, {-1.4, 0.9, 3.0}};
    enum { NA = 8, NB = 8, N = 64000 };
    for (int c = 0; c < 4; c++) {
        /* ref, in the rectangle's frame (x, y along the edges, z up). */
        double rx = above[c][0], ry = above[c][1], h = above[c][2];
        vec3 ref = v3_add(centre, v3_add(v3_add(v3_scale(ex, rx), v3_scale(ey, ry)), v3_scale(ez, h)));
        double omega = rect_solid_angle(-1.5 - rx, 1.5 - rx, -1.0 - ry, 1.0 - ry, h);
        double obs[NA * NB] = {0}, expect[NA * NB];
        for (int i = 0; i < NA; i++)
            for (int j = 0; j < NB; j++)
                expect[j * NA + i] = N * rect_solid_angle(-1.5 + 3.0 * i / NA - rx, -1.5 + 3.0 * (i + 1) / NA - rx,
                                                          -1.0 + 2.0 * j / NB - ry, -1.0 + 2.0 * (j + 1) / NB - ry, h) /
                                     omega;
        for (int k = 0; k < N; k++) {
            /* Stratified in u.x only: the test must see the sampler's own map. */
            vec3 u = v3((k + 0.5) / N, fmod(k * 0.6180339887498949, 1.0), 0.5);
            surface_hit hit;
            double pdf;
            shape_sample_from(sh, ref, u, &hit, &pdf);
            cr_assert_float_eq(pdf, 1.0 / omega, 1e-8 / omega, "ref %d: density %g, 1/solid angle %g", c, pdf,
                               1.0 / omega);
            if (k % 64 == 0)
                check_hit_consistent(s, sh, ref, &hit, pdf);
            int i = (int)(hit.uv.x * NA), j = (int)(hit.uv.y * NB);
            obs[(j < NB ? j : NB - 1) * NA + (i < NA ? i : NA - 1)] += 1.0;
        }
        double p = chi2_pvalue_counts(obs, expect, NA * NB, NULL);
        cr_expect_gt(p, chi2_threshold(), "ref %d: chi-square p = %g", c, p);
    }
    scene_destroy(s);
    render_fixture_close(&f);
}

/* Directions to a sphere from outside: uniform in the cone it subtends
 * (cells equal in cos theta and phi about the axis to the centre), on the
 * near side, with density 1 / (2 pi (1 - cos theta_max)). */
Test(light_sampling, sphere_cone_is_uniform_in_solid_angle)
{
    render_fixture f;
    render_fixture_open(&f);
    scene_t *s = render_scene_of(&f, "<shape type=\"sphere\"><point name=\"center\" value=\"1, 2, 3\"/>"
                                "<float name=\"radius\" value=\"0.5\"/><emitter type=\"area\"/></shape>");
    const shape_t *sh = &s->shapes.items[0];
    cr_assert_not_null(sh->solid_angle);
    const vec3 c = v3(1, 2, 3);
    const double dists[] = {0.52, 0.8, 3.0, 40.0};
    enum { NC = 8, NP = 8, N = 64000 };
    for (int t = 0; t < 4; t++) {
        vec3 ref = v3_add(c, v3_scale(v3_norm(v3(0.3, -1.0, 0.5)), dists[t]));
        double sin2 = 0.25 / (dists[t] * dists[t]), cos_max = sqrt(1.0 - sin2);
        double omega = 2.0 * M_PI * (1.0 - cos_max);
        frame3 fr = frame3_from_normal(v3_norm(v3_sub(c, ref)));
        double obs[NC * NP] = {0}, expect[NC * NP];
        for (int i = 0; i < NC * NP; i++)
            expect[i] = (double)N / (NC * NP);
        for (int k = 0; k < N; k++) {
            vec3 u = v3((k + 0.5) / N, fmod(k * 0.6180339887498949, 1.0), 0.5);
            surface_hit hit;
            double pdf;
            shape_sample_from(sh, ref, u, &hit, &pdf);
            cr_assert_float_eq(pdf, 1.0 / omega, 1e-7 / omega);
            cr_assert_float_eq(v3_len(v3_sub(hit.p, c)), 0.5, 1e-9, "off the sphere");
            cr_assert_gt(v3_dot(hit.ng, v3_sub(ref, hit.p)), 0.0, "on the far side");
            if (k % 64 == 0)
                check_hit_consistent(s, sh, ref, &hit, pdf);
            vec3 w = frame3_to_local(fr, v3_norm(v3_sub(hit.p, ref)));
            double phi = atan2(w.y, w.x) + M_PI;
            int i = (int)((w.z - cos_max) / (1.0 - cos_max) * NC), j = (int)(phi / (2.0 * M_PI) * NP);
            i = i < 0 ? 0 : i >= NC ? NC - 1 : i, j = j < 0 ? 0 : j >= NP ? NP - 1 : j;
            obs[i * NP + j] += 1.0;
        }
        double p = chi2_pvalue_counts(obs, expect, NC * NP, NULL);
        cr_expect_gt(p, chi2_threshold(), "distance %g: chi-square p = %g", dists[t], p);
    }
    scene_destroy(s);
    render_fixture_close(&f);
}

/* Seen from far enough that area sampling's density in solid angle varies
 * over the rectangle by at most 2x ((d_max / d_min)^3 <= 2), the rectangle
 * is sampled uniformly in area through its own coordinates: the hit's uv is
 * u itself (u's 2D stratification kept), the density is area sampling's
 * (the hit reports it too), and E[1 / pdf] is the closed-form solid angle. */
Test(light_sampling, distant_rectangle_is_sampled_by_area)
{
    render_fixture f;
    const shape_t *sh;
    scene_t *s = open_first_shape(&f, "<shape type=\"rectangle\"><transform name=\"to_world\">"
                                      "<scale x=\"1.5\" y=\"1\"/></transform><emitter type=\"area\"/></shape>", &sh);
    /* (x, y, h): over the centre and beside the rectangle, far; then near
     * enough that the spherical rectangle stays (pdf 1 / solid angle). */
    const double refs[][3] = {{0.0, 0.0, 10.0}, {4.0, -3.0, 12.0}, {-20.0, 5.0, 6.0}, {0.3, 0.2, 2.0}};
    enum { N = 20000 };
    for (int c = 0; c < 4; c++) {
        double rx = refs[c][0], ry = refs[c][1], h = refs[c][2];
        vec3 ref = v3(rx, ry, h);
        double omega = rect_solid_angle(-1.5 - rx, 1.5 - rx, -1.0 - ry, 1.0 - ry, h);
        double near_x = rx - fmin(1.5, fmax(-1.5, rx)), near_y = ry - fmin(1.0, fmax(-1.0, ry));
        double far_x = fabs(rx) + 1.5, far_y = fabs(ry) + 1.0;
        double q = (h * h + far_x * far_x + far_y * far_y) / (h * h + near_x * near_x + near_y * near_y);
        bool by_area = q * q * q <= 4.0;
        cr_assert_eq(by_area, c < 3, "ref %d: the test's geometry (q^3 = %g)", c, q * q * q);
        double inv = 0.0;
        for (int k = 0; k < N; k++) {
            vec2 u = v2((k + 0.5) / N, fmod(k * 0.6180339887498949, 1.0));
            surface_hit hit;
            double pdf;
            shape_sample_from(sh, ref, v3(u.x, u.y, 0.5), &hit, &pdf);
            inv += 1.0 / pdf / N;
            if (k % 64 == 0)
                check_hit_consistent(s, sh, ref, &hit, pdf);
            if (by_area) {
                cr_assert_float_eq(hit.uv.x, u.x, 1e-6, "ref %d: uv %g, u %g", c, hit.uv.x, u.x);
                cr_assert_float_eq(hit.uv.y, u.y, 1e-6, "ref %d: uv %g, u %g", c, hit.uv.y, u.y);
            } else {
                cr_assert_float_eq(pdf, 1.0 / omega, 1e-8 / omega, "ref %d: density %g", c, pdf);
            }
        }
        cr_expect_float_eq(inv, omega, 1e-3 * omega, "ref %d: E[1/pdf] %g, solid angle %g", c, inv, omega);
    }
    scene_destroy(s);
    render_fixture_close(&f);
}

/* Where no solid-angle sampler applies (a sheared rectangle, a sphere seen
 * from inside, a rectangle too small to bother), points are drawn by area
 * and the density converted: the hit of a ray toward the sample reports
 * that same density, and E[1 / pdf] over directions is the solid angle. */
Test(light_sampling, area_fallback_is_consistent)
{
    render_fixture f;
    render_fixture_open(&f);
    scene_t *s = render_scene_of(
        &f, "<shape type=\"rectangle\"><transform name=\"to_world\"><matrix value=\"1 0.5 0 0  0 1 0 0  0 0 1 0  0 0 0 1\"/>"
            "</transform><emitter type=\"area\"/></shape>"
            "<shape type=\"sphere\"><point name=\"center\" value=\"5, 0, 0\"/><float name=\"radius\" value=\"1\"/>"
            "<emitter type=\"area\"/></shape>"
            "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"0.001\"/>"
            "<translate x=\"-5\"/></transform><emitter type=\"area\"/></shape>");
    cr_expect_null(s->shapes.items[0].solid_angle, "a sheared rectangle is not sampled as a rectangle");
    const struct {
        int shape;
        vec3 ref;
        double solid_angle; /* 0: unknown */
    } cases[] = {{0, v3(0.1, 0.2, 1.0), 0.0}, {1, v3(5.2, 0.1, -0.3), 4.0 * M_PI}, {2, v3(-5, 0, 1), 0.0}};
    for (int t = 0; t < 3; t++) {
        const shape_t *sh = &s->shapes.items[cases[t].shape];
        rng_t rng;
        rng_seed(&rng, 3, (uint64_t)t);
        double inv = 0.0;
        const int n = 20000;
        for (int k = 0; k < n; k++) {
            vec3 u = v3(rng_next_double(&rng), rng_next_double(&rng), rng_next_double(&rng));
            surface_hit hit;
            double pdf;
            shape_sample_from(sh, cases[t].ref, u, &hit, &pdf);
            cr_assert_gt(pdf, 0.0);
            inv += 1.0 / pdf / n;
            if (k % 50 == 0)
                check_hit_consistent(s, sh, cases[t].ref, &hit, pdf);
        }
        if (cases[t].solid_angle > 0.0)
            cr_expect_float_eq(inv, cases[t].solid_angle, 0.05 * cases[t].solid_angle, "case %d: %g", t, inv);
    }
    scene_destroy(s);
    render_fixture_close(&f);
}

/* Twenty emitters of every kind: one-sided rectangles facing various ways,
 * spheres, a disk, point lights, a directional light and an environment. */
static const char *many_lights =
    "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"0.2\"/></emitter>"
    "<emitter type=\"directional\"><vector name=\"direction\" value=\"0, -1, 0.3\"/>"
    "<rgb name=\"irradiance\" value=\"0.5\"/></emitter>"
    "<emitter type=\"point\"><point name=\"position\" value=\"2, 3, -1\"/><rgb name=\"intensity\" value=\"4\"/></emitter>"
    "<emitter type=\"point\"><point name=\"position\" value=\"-3, 1, 2\"/><rgb name=\"intensity\" value=\"1\"/></emitter>"
    "<shape type=\"disk\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"90\"/><translate y=\"4\"/></transform>"
    "<emitter type=\"area\"><rgb name=\"radiance\" value=\"3\"/></emitter></shape>";

static scene_t *load_many_lights(render_fixture *f)
{
    char body[12000];
    int n = snprintf(body, sizeof body, "%s", many_lights);
    for (int i = 0; i < 8; i++)
        n += snprintf(body + n, sizeof body - (size_t)n,
                      "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"%g\"/>"
                      "<rotate x=\"%d\" y=\"%d\" angle=\"%d\"/><translate x=\"%g\" y=\"%g\" z=\"%g\"/></transform>"
                      "<emitter type=\"area\"><rgb name=\"radiance\" value=\"%g\"/></emitter></shape>",
                      0.2 + 0.1 * i, i % 2, 1 - i % 2, 45 * i, -4.0 + i, 1.0 + (i % 3), 0.5 * i - 2.0, 1.0 + i);
    for (int i = 0; i < 7; i++)
        n += snprintf(body + n, sizeof body - (size_t)n,
                      "<shape type=\"sphere\"><point name=\"center\" value=\"%g, %g, %g\"/>"
                      "<float name=\"radius\" value=\"%g\"/><emitter type=\"area\">"
                      "<rgb name=\"radiance\" value=\"%g\"/></emitter></shape>",
                      3.0 - i, 2.0 + 0.3 * i, -3.0 + i, 0.1 + 0.05 * i, 5.0 - 0.5 * i);
    return render_scene_of(f, body);
}

/* A flat light that radiates from its front only: wherever
 * emitter_faces_away says a point is behind it (so next-event estimation
 * draws nothing for it there), sampling it from that point gives nothing
 * for any numbers; it says so everywhere clearly behind, and never in
 * front or around a shape that is not flat. */
Test(light_sampling, a_flat_light_faces_away_only_where_it_refuses_every_sample)
{
    const char *bodies[] = {
        "<shape type=\"rectangle\"><transform name=\"to_world\"><scale x=\"1.5\" y=\"0.7\"/>"
        "<rotate x=\"1\" angle=\"30\"/><rotate y=\"1\" angle=\"-50\"/><translate x=\"3\" y=\"2\"/></transform>"
        "<emitter type=\"area\"/></shape>",
        "<shape type=\"rectangle\"><boolean name=\"flip_normals\" value=\"true\"/><transform name=\"to_world\">"
        "<rotate x=\"1\" angle=\"90\"/><translate y=\"0.99\"/></transform><emitter type=\"area\"/></shape>",
        "<shape type=\"sphere\"><float name=\"radius\" value=\"0.5\"/><emitter type=\"area\"/></shape>",
    };
    const double heights[] = {-2.0, -1e-3, -1e-9, 0.0, 1e-9, 1e-3, 2.0};
    for (int b = 0; b < 3; b++) {
        render_fixture f;
        const shape_t *sh;
        scene_t *s = open_first_shape(&f, bodies[b], &sh);
        const emitter_t *e = sh->emitter;
        cr_assert_not_null(e);
        /* The plane's frame from the shape's own corners (rectangles). */
        vec3 o = transform_point(&sh->to_world, v3(0, 0, 0));
        vec3 n = v3_norm(transform_normal(&sh->to_world, v3(0, 0, 1)));
        if (sh->flip_normals)
            n = v3_neg(n);
        vec3 ex = v3_norm(v3_sub(transform_point(&sh->to_world, v3(1, 0, 0)), o)), ey = v3_cross(n, ex);
        int away = 0;
        for (int hi = 0; hi < 7; hi++)
            for (int k = 0; k < 40; k++) {
                double a = 6.0 * fmod(k * 0.7548776662466927, 1.0) - 3.0, c = 6.0 * fmod(k * 0.5698402909980532, 1.0) - 3.0;
                vec3 ref = v3_add(o, v3_add(v3_add(v3_scale(ex, a), v3_scale(ey, c)), v3_scale(n, heights[hi])));
                if (b == 2) /* the sphere: around it */
                    ref = v3_scale(v3_norm(v3(a, c, heights[hi])), 0.5 + fabs(heights[hi]));
                bool faces_away = emitter_faces_away(e, ref);
                /* Within 1e-9 of the plane (the float vertices' plane is off
                 * the exact one by ~1e-7) only the samples decide. */
                if (b == 2 || heights[hi] >= 1e-3)
                    cr_assert(!faces_away, "shape %d: ref at height %g is not behind", b, heights[hi]);
                else if (heights[hi] <= -1e-3)
                    cr_assert(faces_away, "shape %d: ref at height %g is behind", b, heights[hi]);
                if (!faces_away)
                    continue;
                away++;
                for (int j = 0; j < 200; j++) {
                    vec3 u = v3((j + 0.5) / 200, fmod(j * 0.6180339887498949, 1.0), fmod(j * 0.4142135623730951, 1.0));
                    emitter_sample_rec es;
                    cr_assert(!emitter_sample(e, ref, u, &es), "shape %d: a point behind got light", b);
                }
            }
        cr_expect(b == 2 || away >= 80, "shape %d: %d points behind", b, away);
        scene_destroy(s);
        render_fixture_close(&f);
    }
}

Test(light_tree, picks_as_often_as_its_pmf_says)
{
    render_fixture f;
    render_fixture_open(&f);
    scene_t *s = load_many_lights(&f);
    const emitter_list *l = &s->emitters;
    cr_assert_eq(l->count, 20);
    rng_t rng;
    rng_seed(&rng, 5, 5);
    bool picked_somewhere[20] = {false};
    double reuse_sum = 0.0;
    int reuse_n = 0;
    for (int t = 0; t < 20; t++) {
        emitter_ref ref = {v3(8.0 * rng_next_double(&rng) - 4.0, 5.0 * rng_next_double(&rng) - 0.5,
                              8.0 * rng_next_double(&rng) - 4.0),
                           t % 5 == 4 ? v3(0, 0, 0)
                                      : warp_square_to_uniform_sphere(v2(rng_next_double(&rng), rng_next_double(&rng)))};
        double pmf[20], sum = 0.0;
        for (int e = 0; e < 20; e++)
            sum += pmf[e] = emitter_list_pmf(l, &ref, l->items[e]);
        /* A node's bounds may promise light its children's do not: then no
         * emitter is picked (the sample is lost, the estimate unbiased). */
        cr_assert(sum <= 1.0 + 1e-9 && sum > 0.0, "ref %d: the pmfs sum to %g", t, sum);
        cr_assert_eq(pmf[l->env->index], 0.0, "a constant environment is left to BSDF sampling");
        for (int e = 0; e < 20; e++)
            picked_somewhere[e] |= pmf[e] > 0.0;
        enum { N = 20000 };
        double obs[21] = {0}, expect[21];
        for (int k = 0; k < N; k++) {
            double p, reuse;
            const emitter_t *e = emitter_list_pick(l, &ref, (k + rng_next_double(&rng)) / N, &p, &reuse);
            if (!e) {
                obs[20] += 1.0;
                continue;
            }
            cr_assert_float_eq(p, pmf[e->index], 1e-12, "pick and pmf disagree");
            cr_assert(reuse >= 0.0 && reuse < 1.0, "remainder %g", reuse);
            reuse_sum += reuse, reuse_n++;
            obs[e->index] += 1.0;
        }
        for (int e = 0; e < 20; e++)
            expect[e] = N * pmf[e];
        expect[20] = N * fmax(0.0, 1.0 - sum);
        double pv = chi2_pvalue_counts(obs, expect, 21, NULL);
        cr_expect_gt(pv, chi2_threshold(), "ref %d: chi-square p = %g", t, pv);
    }
    for (int e = 0; e < 20; e++)
        cr_expect(picked_somewhere[e] || l->items[e] == l->env, "emitter %d is never picked", e);
    /* The remainders are uniform: their mean is 1/2 within 5 sd. */
    cr_expect_lt(fabs(reuse_sum / reuse_n - 0.5), 5.0 * sqrt(1.0 / 12.0 / reuse_n), "remainders average %g",
                 reuse_sum / reuse_n);
    scene_destroy(s);
    render_fixture_close(&f);
}

/* A one-sided rectangle light shines on its front half-space only: picked
 * there (however small its share), never well behind it (near its edge
 * the bounds cannot tell). */
Test(light_tree, lights_are_picked_where_they_shine_only)
{
    render_fixture f;
    render_fixture_open(&f);
    scene_t *s = load_many_lights(&f);
    const emitter_list *l = &s->emitters;
    const emitter_t *rect = NULL;
    for (int e = 0; e < l->count && !rect; e++)
        if (l->items[e]->shape && !strcmp(l->items[e]->shape->type, "rectangle"))
            rect = l->items[e];
    cr_assert_not_null(rect);
    const shape_t *sh = rect->shape;
    vec3 c = transform_point(&sh->to_world, v3(0, 0, 0)), n = sh->normal_axis;
    for (int k = 1; k <= 20; k++) {
        vec3 side = v3_norm(v3_cross(n, v3(0.3, 0.4, 0.5)));
        vec3 front = v3_add(c, v3_add(v3_scale(n, 0.1 * k), v3_scale(side, 0.2 * k)));
        vec3 back = v3_add(c, v3_add(v3_scale(n, -0.5 - 0.2 * k), v3_scale(side, 0.05 * k)));
        emitter_ref rf = {front, v3_neg(n)}, rb = {back, n};
        cr_expect_gt(emitter_list_pmf(l, &rf, rect), 0.0, "in front, %d", k);
        cr_expect_eq(emitter_list_pmf(l, &rb, rect), 0.0, "behind, %d", k);
    }
    scene_destroy(s);
    render_fixture_close(&f);
}
