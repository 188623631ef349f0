/* The meridian r(h) from the outline and the camera (perspective_internal.h).
 *
 * The outline is the envelope of the imaged cross-section circles: at each
 * outline point one circle's image touches it. Back-projected, the outline
 * tangent and the viewing ray span the plane that touches the surface along
 * that ray, and on a surface of revolution the normal lies in the meridian
 * plane of its point. So the point is where the ray meets the plane through
 * the axis that contains the tangent plane's normal: with the ray
 * P(s) = O + s d and the normal n, the azimuthal component n . (Y x P(s))
 * is linear in s and vanishes at
 *     s = (n_z O_x - n_x O_z) / (n_x d_z - n_z d_x),
 * and the circle is (r, y) = (|P_xz|, P_y). For a level orthographic camera
 * s = 0 and the meridian is the outline itself. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/curve_domains.h"
#include "celadon/curve_fit.h"
#include "perspective/perspective_internal.h"

/* Outline points on each side of a point that its tangent is fitted over. */
enum { TANGENT_HALF_WINDOW = 4 };
/* How far the meridian's curve may reach beyond its widest point: the
 * outline curve's tolerance (the quality gate's 2.33 px). */
#define MAX_OVERSHOOT_PX 2.33

int recon_envelope_point(const recon_camera *cam, vec2 p, vec2 t, double *r, double *y)
{
    ray3 ray = recon_camera_ray(cam, p);
    double c = cos(cam->pitch), s = sin(cam->pitch);
    vec3 t3 = v3(t.x, t.y * c, t.y * s); /* t.x along X, t.y along the camera's up */
    vec3 n = v3_cross(ray.d, t3);
    double den = n.x * ray.d.z - n.z * ray.d.x;
    if (!(fabs(den) > 1e-12 * v3_len(n) * v3_len(ray.d)))
        return -1;
    vec3 P = ray3_at(ray, (n.z * ray.o.x - n.x * ray.o.z) / den);
    *r = hypot(P.x, P.z);
    *y = P.y;
    return isfinite(*r) && isfinite(*y) ? 0 : -1;
}

/* Tangent of the outline at q[k]: least-squares slope du/dw over the
 * neighbouring points q[lo..hi-1] (the outline is a function of w). */
static vec2 tangent_at(const vec2 *q, int lo, int hi, int k)
{
    int a = k - TANGENT_HALF_WINDOW < lo ? lo : k - TANGENT_HALF_WINDOW;
    int b = k + TANGENT_HALF_WINDOW >= hi ? hi - 1 : k + TANGENT_HALF_WINDOW;
    double mw = 0, mu = 0;
    for (int i = a; i <= b; i++)
        mw += q[i].y, mu += q[i].x;
    mw /= b - a + 1, mu /= b - a + 1;
    double sww = 0, suw = 0;
    for (int i = a; i <= b; i++)
        sww += (q[i].y - mw) * (q[i].y - mw), suw += (q[i].x - mu) * (q[i].y - mw);
    return v2(sww > 0 ? suw / sww : 0, 1);
}

static int by_height(const void *a, const void *b)
{
    double x = ((const vec2 *)a)->y, y = ((const vec2 *)b)->y;
    return (x > y) - (x < y);
}

void recon_meridian_free(recon_meridian *m)
{
    bspline_free(&m->curve);
    free(m->domains);
    free(m->points);
    memset(m, 0, sizeof *m);
}

/* Whether a point beyond the polyline's end lies on that end's ellipse
 * (within 3 times the fit's residual, and half a pixel, as the arcs grow in
 * recon_camera.c): it is the rim's (base's) own image, whose circle the
 * meridian already ends at. Solved as an envelope point it would need the
 * outline's tangent, and near the ends of a thin ellipse (b of a few px at
 * a few degrees) that turns from vertical to level within a pixel, far
 * less than the tangent's window: the drawn bowl at 5 degrees got points
 * 2-4% of the height too wide there. */
static int on_end_ellipse(const recon_ellipse *e, vec2 f)
{
    double tol = fmax(3 * e->rms_px, 0.5);
    double dist = e->b > 0 ? recon_ellipse_distance(e->w0, e->a, e->b, f, NULL) : f.y - e->w0;
    return fabs(dist) <= tol;
}

/* The profile's outline in the camera frame, top to bottom: between the
 * rim's and the base's heights along the imaged axis, the polyline's points
 * (what recon_extract kept of either side, or their mean, with the excluded
 * parts left out) put back into the image on side_used, without its closing
 * end points and the points it adds along a ledge (the tangent is fitted to
 * one point per row); above and below, where the polyline stops but the
 * outline goes on (the rim's far edge and the foot's near edge seen from
 * above), the silhouette of side_used. Returns the count; q[mid[0]] to
 * q[mid[1] - 1] are the polyline's. */
static int profile_outline(const recon_camera *cam, const recon_result *res, vec2 *q, int mid[2])
{
    int s = res->side_used == RECON_SIDE_LEFT ? 0 : 1, n_sil = res->n_silhouette[s], n = 0;
    const vec2 *sil = res->silhouette[s];
    vec2 d = res->axis_direction, nrm = v2(-d.y, d.x);
    double side = s ? 1 : -1, H = res->n_polyline > 0 ? res->polyline[res->n_polyline - 1].y : 0;
    /* Beyond the ends the outline is the rim's (base's) ellipse: no further
     * out than its far (near) edge, half a pixel of noise allowed. */
    double w_top = cam->rim.w0 + cam->rim.b + 0.5, w_bottom = cam->base.w0 - cam->base.b - 0.5;
    int k = 0;
    /* (half a pixel past the corners' rows, not the corners themselves) */
    for (double h; k < n_sil && (h = v2_dot(v2_sub(sil[k], res->axis_origin), d)) >= H; k++) {
        vec2 f = recon_camera_to_frame(cam, sil[k]);
        if (h >= H + 0.5 && f.y <= w_top && !on_end_ellipse(&cam->rim, f))
            q[n++] = f;
    }
    double last_h = H;
    mid[0] = n;
    for (int i = res->n_polyline - 2; i > 0; i--) {
        vec2 p = res->polyline[i];
        if (last_h - p.y < 0.5)
            continue;
        last_h = p.y;
        vec2 img = v2_add(res->axis_origin, v2_add(v2_scale(d, p.y), v2_scale(nrm, side * p.x)));
        q[n++] = recon_camera_to_frame(cam, img);
    }
    mid[1] = n;
    for (; k < n_sil; k++) {
        vec2 f = recon_camera_to_frame(cam, sil[k]);
        if (v2_dot(v2_sub(sil[k], res->axis_origin), d) <= -0.5 && f.y >= w_bottom && !on_end_ellipse(&cam->base, f))
            q[n++] = f;
    }
    return n;
}

int recon_meridian_from_outline(const recon_camera *cam, const recon_result *res, double smoothing_px,
                                recon_meridian *mer, char *err, size_t errlen)
{
    memset(mer, 0, sizeof *mer);
    double Hm = cam->rim_y - cam->base_y;
    int s = res->side_used == RECON_SIDE_LEFT ? 0 : 1, cap = res->n_polyline + res->n_silhouette[s] + 1;
    vec2 *q = malloc((size_t)cap * sizeof *q), *pts = malloc((size_t)(cap + 2) * sizeof *pts);
    if (!q || !pts) {
        free(q);
        free(pts);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    int mid[2];
    int n = profile_outline(cam, res, q, mid);
    /* Envelope samples (r, h) in world units, h above the base. Beyond the
     * polyline's ends the outline turns into the rim's (base's) ellipse: a
     * point there is solved only while the outline is steeper than 45
     * degrees (flatter, the tangent plane grazes the cross-sections and the
     * radius is ill-conditioned: a level brush pot's rim gave 38% too wide). */
    int m = 1;
    for (int k = 0; k < n; k++) {
        double r, y;
        /* A polyline point's tangent from polyline points only: the corners
         * are where the outline leaves the end ellipses, a turn that a
         * window across them would average in (the wide-mouthed vase
         * rendered level at 50 mm: the last rows above its base corners
         * came out 12% of the radius too wide, 3% of the height). */
        int inner = k >= mid[0] && k < mid[1];
        vec2 t = tangent_at(q, inner ? mid[0] : 0, inner ? mid[1] : n, k);
        if ((k < mid[0] || k >= mid[1]) && fabs(t.x) > 1)
            continue;
        if (recon_envelope_point(cam, q[k], t, &r, &y) == 0 && y > cam->base_y && y < cam->rim_y)
            pts[m++] = v2(r, y - cam->base_y);
    }
    free(q);
    qsort(pts + 1, (size_t)(m - 1), sizeof *pts, by_height);
    int k = 1;
    for (int i = 2; i < m; i++) /* strictly increasing heights */
        if (pts[i].y > pts[k].y)
            pts[++k] = pts[i];
    m = k + 1;
    if (m < 4) {
        free(pts);
        snprintf(err, errlen, "the outline gives too few meridian points (%d)", m - 1);
        return -1;
    }
    /* Closed by the base and the rim circles the camera found. */
    pts[0] = v2(cam->base_r, 0);
    pts[m] = v2(cam->rim_r, Hm);
    m++;
    int fitted = bspline_fit_profile(pts, m, smoothing_px, &mer->curve, NULL) == 0;
    /* As for the outline's curve (reconstruct.c): control points that
     * undershoot the axis (a mouth closing on it) are put on it, so the
     * profile.json reader, which refuses a negative radius, reads it back. */
    for (int i = 0; fitted && i < mer->curve.n_ctrl; i++)
        mer->curve.ctrl[i].x = fmax(0, mer->curve.ctrl[i].x);
    if (!fitted || curve_domains_by_curvature_variation(&mer->curve, PROFILE_DOMAIN_TOL_PX, PROFILE_DOMAIN_TOL_DEG,
                                                        &mer->domains, &mer->n_domains) != 0) {
        free(pts);
        recon_meridian_free(mer);
        snprintf(err, errlen, "cannot fit a curve to the meridian");
        return -1;
    }
    /* A fit that overshoots its points is unstable (a sparse run of points
     * near an end): the curve reaches out to many times the vessel's width
     * (the real-dev high-view pyxis: 3098 px beyond its widest point, the
     * two-handled jar 848; sound fits stay within 0.7 px). Beyond the
     * outline's own curve tolerance it is no meridian. */
    double r_points = 0;
    for (int i = 0; i < m; i++)
        r_points = fmax(r_points, pts[i].x);
    double over = bspline_largest(&mer->curve, 0) - r_points;
    if (!(over <= MAX_OVERSHOOT_PX)) {
        free(pts);
        recon_meridian_free(mer);
        snprintf(err, errlen, "the meridian's curve overshoots its points by %.0f px (an unstable fit; at most %.2f)",
                 over, MAX_OVERSHOOT_PX);
        return -1;
    }
    /* Fitted in world units (about px at the axis, so the pixel tolerances
     * keep their meaning), stored in units of the height. */
    for (int i = 0; i < mer->curve.n_ctrl; i++) /* division: the rim lands on exactly 1 */
        mer->curve.ctrl[i] = v2(mer->curve.ctrl[i].x / Hm, mer->curve.ctrl[i].y / Hm);
    for (int i = 0; i < m; i++)
        pts[i] = v2(pts[i].x / Hm, pts[i].y / Hm);
    mer->points = pts;
    mer->n_points = m;
    mer->height_px = Hm;
    return 0;
}
