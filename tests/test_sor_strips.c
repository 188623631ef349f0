/* The strips of the strip tree: every node's strip (and annulus) holds its
 * arc, the strip test's range holds the ray, and a strip culls a ray that
 * passes its node's annulus but truly misses the arc. The arcs are sampled
 * here from the leaves' own control points, the ray in long double. */
#include <criterion/criterion.h>
#include <stdio.h>

#include "sor/sor_internal.h"
#include "support/counted_check.h"
#include "support/sor_profiles.h"

#define ARC_SAMPLES 400 /* per leaf */

static double bezier3(const double p[4], double w)
{
    double m = 1.0 - w;
    return m * m * m * p[0] + 3.0 * m * m * w * p[1] + 3.0 * m * w * w * p[2] + w * w * w * p[3];
}

/* One past the last node of the subtree at k (depth-first layout). */
static int subtree_end(const sor_t *s, int k)
{
    return s->nodes[k].piece >= 0 ? k + 1 : subtree_end(s, s->nodes[k].skip);
}

Test(sor_strips, every_strip_and_annulus_holds_its_arc)
{
    failures = 0;
    for (int i = 0; i < sor_test_profile_count(); i++) {
        const char *name = sor_test_profile_name(i);
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        double S = s->size;
        for (int k = 0; k < s->n_nodes; k++) {
            const sor_node *nd = &s->nodes[k];
            const sor_strip *st = &s->strips[k];
            CHECK(st->nr >= 0.0 && fabs(hypot(st->nr, st->nh / S) - 1.0) < 1e-12, "%s node %d: normal (%g, %g)", name,
                  k, st->nr, st->nh);
            double gmin = INFINITY, gmax = -INFINITY;
            for (int j = k, end = subtree_end(s, k); j < end; j++) {
                if (s->nodes[j].piece < 0)
                    continue;
                const sor_piece *pc = &s->pieces[s->nodes[j].piece];
                for (int q = 0; q <= ARC_SAMPLES; q++) {
                    double w = (double)q / ARC_SAMPLES, r = bezier3(pc->r, w), h = bezier3(pc->h, w);
                    double g = st->nr * r * r + st->nh * h;
                    gmin = fmin(gmin, g), gmax = fmax(gmax, g);
                    CHECK(g >= st->d0 && g <= st->d1, "%s node %d: arc point (%g, %g) outside its strip", name, k, r,
                          h);
                    CHECK(r * r >= nd->q0 && r * r <= nd->q1 && h >= nd->h0 && h <= nd->h1,
                          "%s node %d: arc point (%g, %g) outside its annulus", name, k, r, h);
                }
            }
            /* Thin: the strip hugs the arc on both sides, within 5% of its
             * width (or the slack, for a straight arc). */
            double width = st->d1 - st->d0, tight = 0.05 * width + 2e-8 * S * S;
            CHECK(gmin - st->d0 <= tight && st->d1 - gmax <= tight, "%s node %d: strip [%g, %g] loose on arc [%g, %g]",
                  name, k, st->d0, st->d1, gmin, gmax);
        }
        sor_destroy(s);
    }
    cr_assert_eq(failures, 0, "%d failures", failures);
}

/* splitmix64 in [0, 1) */
static double uniform(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

/* A uniform point of the SOR's bounding box. */
static vec3 point_in_bounds(const sor_t *s, uint64_t *g)
{
    double x = (2 * uniform(g) - 1) * s->r_max, y = uniform(g) * s->height;
    return v3(x, y, (2 * uniform(g) - 1) * s->r_max);
}

/* The range sor_strip_range gives over [sa, sb] holds every value of
 * nr rho^2 + nh h the ray takes there, evaluated in long double from the ray
 * itself, for rays from far away, steep and shallow, of any length. */
Test(sor_strips, strip_range_holds_the_ray)
{
    failures = 0;
    uint64_t g = 7;
    for (int i = 0; i < sor_test_profile_count(); i++) {
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        for (int n = 0; n < 3000; n++) {
            double far = n % 3 == 0 ? 1e3 : 2.0, len = n % 5 == 0 ? 1e-3 : n % 5 == 1 ? 1e3 : 1.0;
            vec3 o = v3((2 * uniform(&g) - 1) * far, (2 * uniform(&g) - 1) * far, (2 * uniform(&g) - 1) * far);
            vec3 target = point_in_bounds(s, &g);
            vec3 d = v3_scale(v3_norm(v3_sub(target, o)), len);
            if (n % 7 == 0)
                d.y *= 1e-6; /* nearly horizontal */
            ray3 ray = {o, d};
            sor_ray ry;
            if (!sor_ray_setup(s, &ray, &ry) || ry.dy == 0.0 || ry.a == 0.0)
                continue;
            const sor_strip *st = &s->strips[(int)(uniform(&g) * s->n_nodes)];
            const sor_node *nd = &s->bound;
            double s0 = (nd->h0 - ry.hc) * ry.inv_dy, s1 = (nd->h1 - ry.hc) * ry.inv_dy;
            double lo_s = fmin(s0, s1), hi_s = fmax(s0, s1);
            double sa = lo_s + uniform(&g) * (hi_s - lo_s), sb = sa + uniform(&g) * (hi_s - sa);
            double lo, hi;
            sor_strip_range(s, st, &ry, sa, sb, &lo, &hi);
            for (int q = 0; q <= 64; q++) {
                long double sq = sa + (long double)(sb - sa) * q / 64, t = ry.tc + sq;
                long double x = o.x + t * d.x, y = o.y + t * d.y, z = o.z + t * d.z;
                long double val = st->nr * (x * x + z * z) + st->nh * y;
                CHECK(val >= lo && val <= hi, "%s: ray %d at s = %.17Lg: %.17Lg outside [%.17g, %.17g]",
                      sor_test_profile_name(i), n, sq, val, lo, hi);
            }
        }
        sor_destroy(s);
    }
    cr_assert_eq(failures, 0, "%d failures", failures);
}

/* The strip test never culls a leaf that holds a hit: for random rays at
 * every profile, whenever the exact leaf solver accepts a hit on a leaf, the
 * ray's range over that leaf's slab meets the leaf's strip. */
Test(sor_strips, strips_keep_every_leaf_hit)
{
    failures = 0;
    uint64_t g = 11;
    long hits = 0;
    for (int i = 0; i < sor_test_profile_count(); i++) {
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        vec3 c = v3(0.0, 0.5 * s->height, 0.0);
        for (int n = 0; n < 4000; n++) {
            double z = 2 * uniform(&g) - 1, phi = 2 * M_PI * uniform(&g), q = sqrt(1 - z * z);
            vec3 o = v3_add(c, v3_scale(v3(q * cos(phi), z, q * sin(phi)), 2.0 * s->size));
            vec3 target = point_in_bounds(s, &g);
            ray3 ray = {o, v3_sub(target, o)};
            sor_ray ry;
            if (!sor_ray_setup(s, &ray, &ry) || ry.dy == 0.0 || ry.a == 0.0)
                continue;
            for (int k = 0; k < s->n_nodes; k++) {
                const sor_node *nd = &s->nodes[k];
                if (nd->piece < 0)
                    continue;
                sor_best best = {INFINITY, -1, 0.0, SOR_PART_WALL};
                if (!sor_piece_intersect(s, &s->pieces[nd->piece], nd->piece, &ry, -ry.tc, &best))
                    continue;
                hits++;
                double s0 = (nd->h0 - ry.hc) * ry.inv_dy, s1 = (nd->h1 - ry.hc) * ry.inv_dy, lo, hi;
                sor_strip_range(s, &s->strips[k], &ry, fmax(fmin(s0, s1), -ry.tc), fmax(s0, s1), &lo, &hi);
                CHECK(hi >= s->strips[k].d0 && lo <= s->strips[k].d1,
                      "%s: ray %d hits leaf %d at s = %.17g outside its strip", sor_test_profile_name(i), n, k, best.s);
            }
        }
        sor_destroy(s);
    }
    cr_assert_gt(hits, 10000);
    cr_assert_eq(failures, 0, "%d failures", failures);
}

/* A leaf below a leaf pair (where the walk tests strips) whose arc rises in
 * both r and h and is nearly straight: the thinnest strip against its box. */
static int diagonal_leaf(const sor_t *s, int *parent, int *lane)
{
    double best = INFINITY;
    int found = -1;
    for (int k = 0; k < s->n_nodes; k++) {
        if (s->nodes[k].piece >= 0 || !s->pairs[k].strips)
            continue;
        for (int j = 0; j < 2; j++) {
            int c = j == 0 ? k + 1 : s->nodes[k].skip;
            const sor_piece *pc = &s->pieces[s->nodes[c].piece];
            const sor_node *nd = &s->nodes[c];
            const sor_strip *st = &s->strips[c];
            if (!(pc->r[3] > pc->r[0] && pc->h[3] > pc->h[0]))
                continue;
            double ratio = (st->d1 - st->d0) / (st->nr * (nd->q1 - nd->q0) + fabs(st->nh) * (nd->h1 - nd->h0));
            if (ratio < best)
                best = ratio, found = c, *parent = k, *lane = j;
        }
    }
    return found;
}

/* The ray's trace in the (R, h) plane is the parabola R = d^2 + k (h - h*)^2.
 * Put its vertex one box height below the leaf's box, through R0 - eps at the
 * box's bottom and halfway across at its top: it enters the box (so the
 * annulus cannot cull it), and, being convex, it stays left of its chord,
 * hence left of the nearly straight arc, which the test checks by sampling. */
Test(sor_strips, strip_culls_a_ray_the_annulus_keeps)
{
    int profile = -1, parent = -1, lane = -1, leaf = -1;
    sor_t *s = NULL;
    for (int i = 0; i < sor_test_profile_count() && leaf < 0; i++) {
        if (s)
            sor_destroy(s);
        s = sor_test_create(i, SOR_CAPS_ALL);
        leaf = diagonal_leaf(s, &parent, &lane);
        profile = i;
    }
    cr_assert_geq(leaf, 0, "no profile has a rising leaf below a leaf pair");
    const sor_piece *pc = &s->pieces[s->nodes[leaf].piece];
    double R0 = pc->r[0] * pc->r[0], R1 = pc->r[3] * pc->r[3], h0 = pc->h[0], h1 = pc->h[3], dh = h1 - h0;
    double eps = 0.01 * (R1 - R0), Rx = R0 + 0.5 * (R1 - R0), hstar = h0 - dh;
    double k = (Rx - R0 + eps) / (3.0 * dh * dh), d2 = R0 - eps - k * dh * dh;
    cr_assert_gt(d2, 0.0);
    /* cot^2(theta) = k; the ray passes (sqrt(d2), h*, 0) going along +z and up. */
    double theta = atan(1.0 / sqrt(k));
    vec3 dir = v3(0.0, sin(theta), cos(theta)), p = v3(sqrt(d2), hstar, 0.0);
    ray3 ray = {v3_sub(p, v3_scale(dir, 3.0 * s->size)), dir};
    /* Truth: every arc point lies right of the trace (larger R at its height). */
    for (int q = 0; q <= 1000; q++) {
        double w = q / 1000.0, r = bezier3(pc->r, w), h = bezier3(pc->h, w);
        cr_assert_gt(r * r, d2 + k * (h - hstar) * (h - hstar), "%s: the trace meets the arc at w = %g",
                     sor_test_profile_name(profile), w);
    }
    sor_ray ry;
    cr_assert(sor_ray_setup(s, &ray, &ry));
    double smin = -ry.tc, smax = INFINITY;
    int without = sor_children_test(s, parent, &ry, smin, smax, 0),
        with = sor_children_test(s, parent, &ry, smin, smax, 1);
    cr_assert(without & (1 << lane), "%s: the annulus of leaf %d should keep the ray", sor_test_profile_name(profile),
              leaf);
    cr_assert_not(with & (1 << lane), "%s: the walk should cull leaf %d by its strip", sor_test_profile_name(profile),
                  leaf);
    cr_assert_eq(with & ~without, 0, "strips only ever remove children");
    /* The same decision from the strip test itself, over the leaf's slab. */
    const sor_node *nd = &s->nodes[leaf];
    const sor_strip *st = &s->strips[leaf];
    double s0 = (nd->h0 - ry.hc) * ry.inv_dy, s1 = (nd->h1 - ry.hc) * ry.inv_dy, lo, hi;
    sor_strip_range(s, st, &ry, fmax(fmin(s0, s1), smin), fmin(fmax(s0, s1), smax), &lo, &hi);
    cr_assert(hi < st->d0 || lo > st->d1, "%s: the strip [%g, %g] of leaf %d should cull the ray's [%g, %g]",
              sor_test_profile_name(profile), st->d0, st->d1, leaf, lo, hi);
    sor_destroy(s);
}
