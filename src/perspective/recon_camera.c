/* recon_camera_meridian: the outline's arcs -> camera -> meridian
 * (recon_camera.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "perspective/perspective_internal.h"

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
