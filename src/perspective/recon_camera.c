/* recon_camera_meridian: the outline's arcs -> camera -> meridian
 * (recon_camera.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "perspective/perspective_internal.h"

/* Whether the points pts[0..n) (image) all lie within tol of the ellipse e
 * (camera frame), or of one fitted to them and the arc's points together
 * (half: as recon_fit_axis_ellipse) whose residual stays within twice e's
 * and 0.05 px. work has room for n_arc + n points. */
static int on_one_ellipse(const recon_camera *cam, const recon_ellipse *e, int half, const vec2 *arc, int n_arc,
                          const vec2 *pts, int n, double tol, vec2 *work)
{
    int near = 1;
    for (int k = 0; k < n && near; k++) {
        vec2 q = recon_camera_to_frame(cam, pts[k]);
        near = fabs(recon_ellipse_distance(e->w0, e->a, e->b, q, NULL)) <= tol;
    }
    if (near)
        return 1;
    int m = 0;
    for (int k = 0; k < n_arc; k++)
        work[m++] = recon_camera_to_frame(cam, arc[k]);
    for (int k = 0; k < n; k++)
        work[m++] = recon_camera_to_frame(cam, pts[k]);
    recon_ellipse f;
    if (recon_fit_axis_ellipse(work, m, half, &f) != 0 || !(f.b > 0) || !(f.rms_px <= 2 * e->rms_px + 0.05))
        return 0;
    for (int k = 0; k < n; k++)
        if (!(fabs(recon_ellipse_distance(f.w0, f.a, f.b, work[n_arc + k], NULL)) <= tol))
            return 0;
    return 1;
}

/* Appends to the arc (x increasing) the columns beyond its end on side
 * `dir` (-1 left, +1 right) whose outline lies on one ellipse with the
 * arc (within 3 times its residual, and half a pixel), up to where it
 * leaves it (to within 2% of the arc's width), a gap, or half the arc's
 * width. Returns the number added, or -1 when out of memory. */
static int grow_end(const image_t *img, const recon_result *res, const recon_camera *cam, const recon_ellipse *e,
                    int side, int half, int dir, vec2 **arc, int *n)
{
    if (*n < 6 || !(e->b > 0))
        return 0;
    int x_end = (int)floor((dir < 0 ? (*arc)[0] : (*arc)[*n - 1]).x);
    double width = (*arc)[*n - 1].x - (*arc)[0].x;
    int reach = (int)ceil(0.5 * width), batch = (int)fmax(3, ceil(0.02 * width));
    int i0 = dir < 0 ? x_end - reach : x_end + 1, i1 = dir < 0 ? x_end - 1 : x_end + reach;
    vec2 *col = malloc((size_t)(reach > 0 ? reach : 1) * sizeof *col);
    vec2 *grown = realloc(*arc, (size_t)(*n + reach + 1) * sizeof *grown);
    vec2 *work = malloc((size_t)(*n + reach + 1) * sizeof *work);
    if (grown)
        *arc = grown;
    int m = col && grown && work && reach > 0 ? recon_outline_columns(img, res, i0, i1, side, col) : -1;
    if (m < 0) {
        free(col);
        free(work);
        return reach > 0 ? -1 : 0;
    }
    if (dir < 0) /* outward order */
        for (int k = 0; k < m / 2; k++) {
            vec2 t = col[k];
            col[k] = col[m - 1 - k];
            col[m - 1 - k] = t;
        }
    int run = 0; /* the columns up to the first gap */
    for (double last_x = x_end + 0.5; run < m && fabs(col[run].x - last_x) <= 2.5; run++)
        last_x = col[run].x;
    /* Batches double while they are taken and halve down to the first size
     * when not: a few ellipse fits per end. */
    int kept = 0;
    double tol = fmax(3 * e->rms_px, 0.5);
    for (int size = batch; kept < run;) {
        int b = size < run - kept ? size : run - kept;
        if (on_one_ellipse(cam, e, half, grown, *n, col, kept + b, tol, work)) {
            kept += b;
            size *= 2;
        } else if (size > batch) {
            size /= 2;
        } else {
            break;
        }
    }
    /* the arc plus the kept columns, x increasing */
    if (dir < 0) {
        memmove(grown + kept, grown, (size_t)*n * sizeof *grown);
        for (int k = 0; k < kept; k++)
            grown[k] = col[kept - 1 - k];
    } else {
        memcpy(grown + *n, col, (size_t)kept * sizeof *grown);
    }
    *n += kept;
    free(col);
    free(work);
    return kept;
}

/* The corners bound the arcs, and a corner found inside its arc (the melon
 * vase's, 20-113 px in from the true ends) leaves a short arc whose ellipse
 * is ill-determined. The outline beyond a corner that lies on one ellipse
 * with the arc is the same circle's image: the arcs grow by it, and the
 * camera is fitted again. Returns the columns added, or -1 (out of memory). */
static int grow_arcs(const image_t *img, const recon_result *res, const recon_camera *cam, vec2 **top, int *n_top,
                     vec2 **bottom, int *n_bottom)
{
    int added = 0;
    for (int dir = -1; dir <= 1; dir += 2) {
        int a = grow_end(img, res, cam, &cam->rim, -1, 1, dir, top, n_top);
        int b = grow_end(img, res, cam, &cam->base, 1, -1, dir, bottom, n_bottom);
        if (a < 0 || b < 0)
            return -1;
        added += a + b;
    }
    return added;
}

int recon_camera_meridian(const image_t *img, const recon_result *res, const recon_camera_options *opt,
                          recon_camera *cam, recon_meridian *mer, char *err, size_t errlen)
{
    memset(cam, 0, sizeof *cam);
    memset(mer, 0, sizeof *mer);
    if (!img || !img->data || !res || !res->mask || res->width != img->width || res->height != img->height ||
        res->n_silhouette[res->side_used == RECON_SIDE_LEFT ? 0 : 1] < 4) {
        snprintf(err, errlen, "no extraction result for this photo");
        return -1;
    }
    vec2 *top = NULL, *bottom = NULL;
    int n_top = 0, n_bottom = 0;
    if (recon_outline_arcs(img, res, &top, &n_top, &bottom, &n_bottom) != 0) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    double smoothing = opt && opt->smoothing_px > 0 ? opt->smoothing_px : 1.0;
    int rc = recon_camera_solve(img, res, opt, top, n_top, bottom, n_bottom, cam, err, errlen);
    /* Once: a second round moved no synth-dev camera by more than 0.5
     * degrees and cost as much again. */
    int added = rc == 0 ? grow_arcs(img, res, cam, &top, &n_top, &bottom, &n_bottom) : 0;
    if (added < 0) {
        snprintf(err, errlen, "out of memory");
        rc = -1;
    } else if (added > 0) {
        rc = recon_camera_solve(img, res, opt, top, n_top, bottom, n_bottom, cam, err, errlen);
    }
    if (rc == 0)
        rc = recon_meridian_from_outline(cam, res, smoothing, mer, err, errlen);
    free(top);
    free(bottom);
    if (rc != 0) {
        memset(cam, 0, sizeof *cam);
        recon_meridian_free(mer);
    }
    return rc;
}

/* The world point of the meridian point (r, h) at angle phi: phi = pi/2
 * faces the camera, which is on the -Z side. */
static vec3 world_point(const recon_camera *cam, const recon_meridian *mer, double r, double h, double phi)
{
    double H = mer->height_px;
    return v3(r * H * cos(phi), cam->base_y + h * H, -r * H * sin(phi));
}

vec2 recon_camera_project(const recon_camera *cam, const recon_meridian *mer, double r, double h, double phi)
{
    return recon_camera_to_image(cam, recon_camera_frame_of(cam, world_point(cam, mer, r, h, phi)));
}

int recon_camera_sees(const recon_camera *cam, const recon_meridian *mer, double r, double h, double phi,
                      double dr_dh, double min_cos)
{
    vec3 p = world_point(cam, mer, r, h, phi);
    vec3 n = v3_norm(v3(cos(phi), -dr_dh, -sin(phi)));
    ray3 eye = recon_camera_ray(cam, recon_camera_frame_of(cam, p));
    /* Toward the camera: against the viewing direction. */
    vec3 v = v3_norm(v3_neg(eye.d));
    return v3_dot(n, v) > min_cos;
}

void recon_camera_fill_profile(const recon_camera *cam, const recon_meridian *mer, profile_t *p)
{
    static const char *const methods[] = {"ellipses", "exif", "flag", "orthographic"};
    profile_camera *c = &p->camera;
    memset(c, 0, sizeof *c);
    snprintf(c->method, sizeof c->method, "%s", methods[cam->method]);
    snprintf(c->note, sizeof c->note, "%s", cam->note);
    c->elevation_deg = cam->elevation_deg;
    c->focal_px = cam->focal_px;
    c->roll_deg = cam->roll_deg;
    c->principal_point = cam->principal_point;
    const recon_ellipse *e[2] = {&cam->base, &cam->rim};
    for (int k = 0; k < 2; k++)
        c->conics[k] = (profile_conic){recon_camera_to_image(cam, v2(0, e[k]->w0)), {e[k]->a, e[k]->b},
                                       e[k]->rms_px, e[k]->max_px, e[k]->n_points, e[k]->n_inliers};
    p->has_camera = 1;
    p->has_meridian = 1;
    p->meridian = mer->curve;
    p->meridian_domains = mer->domains;
    p->n_meridian_domains = mer->n_domains;
}
