/* Ring placement for meshed SORs: the tolerance is the angular sagitta of the
 * widest ring, and the rings are the kept boundaries plus the curvature
 * domains at that tolerance. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "celadon/curve_domains.h"
#include "celadon/mesh_rings.h"
#include "support/sor_profiles.h"

/* The largest radius of the control polygon (it bounds r). */
static double control_rmax(const bspline_t *c)
{
    double rmax = 0;
    for (int i = 0; i < c->n_ctrl; i++)
        rmax = fmax(rmax, c->ctrl[i].x);
    return rmax;
}

/* A chord subtending 2 pi / N on a circle of radius R misses the circle by
 * R (1 - cos(pi / N)) at its middle; measured here on the chord itself. */
Test(mesh_rings, tolerance_is_the_angular_sagitta)
{
    bspline_t c;
    sor_test_profile(6, &c);
    double rmax = control_rmax(&c);
    for (int n = 3; n <= 4096; n *= 2) {
        double mid = rmax * hypot(1 + cos(2 * M_PI / n), sin(2 * M_PI / n)) / 2; /* |midpoint of the chord| */
        cr_assert_float_eq(mesh_ring_tolerance(&c, n), rmax - mid, 1e-9 * (rmax - mid), "N=%d", n);
    }
    /* ~ 4.93 r / N^2 at large N: four times smaller per doubling. */
    cr_assert_float_eq(mesh_ring_tolerance(&c, 512) / mesh_ring_tolerance(&c, 1024), 4.0, 1e-4);
    cr_assert_eq(mesh_ring_tolerance(&c, 2), 0.0);
    /* Floored where float vertices stop resolving the chords. */
    cr_assert_float_eq(mesh_ring_tolerance(&c, 100000), MESH_RING_TOL_FLOOR * rmax, 1e-9 * rmax);
    cr_assert_gt(mesh_ring_tolerance(&c, 4096), MESH_RING_TOL_FLOOR * rmax);
    bspline_free(&c);
}

/* Every kept boundary and every curvature domain (chord tolerance tol,
 * normal tolerance 2 tol / r_max radians) is a ring, nothing else is. */
Test(mesh_rings, union_of_kept_boundaries_and_curvature_domains)
{
    bspline_t c;
    sor_test_profile(6, &c);
    double rmax = control_rmax(&c);
    const double keep[] = {0.0, 0.123456, 0.5, 0.77, 1.0};
    for (int n = 16; n <= 1024; n *= 4) {
        double tol = mesh_ring_tolerance(&c, n), *u = NULL, *dom = NULL;
        int nu = 0, nd = 0;
        cr_assert_eq(mesh_rings(&c, keep, 5, tol, &u, &nu), 0);
        cr_assert_eq(curve_domains_by_curvature_variation(&c, tol, 2 * tol / rmax * 180 / M_PI, &dom, &nd), 0);
        for (int i = 1; i < nu; i++)
            cr_assert_gt(u[i], u[i - 1]);
        int found = 0;
        for (int k = 0; k < 5; k++)
            for (int i = 0; i < nu; i++)
                found += u[i] == keep[k];
        cr_assert_eq(found, 5, "N=%d: every kept boundary is a ring", n);
        int shared = 0;
        for (int k = 0; k < nd; k++)
            for (int i = 0; i < nu; i++)
                shared += u[i] == dom[k];
        cr_assert_eq(shared, nd, "N=%d: every curvature domain is a ring", n);
        int common = 0; /* kept boundaries that are also domains (the ends, maybe more) */
        for (int k = 0; k < 5; k++)
            for (int i = 0; i < nd; i++)
                common += dom[i] == keep[k];
        cr_assert_eq(nu, nd + 5 - common, "N=%d: nothing but the two sets", n);
        free(u);
        free(dom);
    }
    /* Finer segments, more rings. */
    double *a = NULL, *b = NULL;
    int na = 0, nb = 0;
    cr_assert_eq(mesh_rings(&c, NULL, 0, mesh_ring_tolerance(&c, 16), &a, &na), 0);
    cr_assert_eq(mesh_rings(&c, NULL, 0, mesh_ring_tolerance(&c, 1024), &b, &nb), 0);
    cr_assert_gt(nb, 4 * na, "%d rings at N=1024, %d at N=16", nb, na);
    free(a);
    free(b);
    bspline_free(&c);
}

Test(mesh_rings, rejects_bad_input)
{
    bspline_t c;
    sor_test_profile(0, &c);
    double *u = NULL;
    int n = 0;
    const double decreasing[] = {0.0, 0.6, 0.4, 1.0}, outside[] = {0.0, 0.5, 1.5};
    cr_assert_eq(mesh_rings(&c, decreasing, 4, 0.1, &u, &n), -1);
    cr_assert_eq(mesh_rings(&c, outside, 3, 0.1, &u, &n), -1);
    cr_assert_eq(mesh_rings(&c, NULL, 0, 0.0, &u, &n), -1);
    cr_assert_eq(mesh_rings(&c, NULL, 0, NAN, &u, &n), -1);
    cr_assert_eq(mesh_rings(&c, NULL, 2, 0.1, &u, &n), -1);
    cr_assert_null(u);
    bspline_free(&c);
}
