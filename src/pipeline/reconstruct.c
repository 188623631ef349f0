/* reconstruct_photo: decode -> image stages -> B-spline -> domains ->
 * Hausdorff errors -> texture. See include/celadon/reconstruct.h. */
#include "celadon/reconstruct.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/curve_distance.h"
#include "celadon/curve_domains.h"
#include "celadon/curve_fit.h"
#include "core/core.h"

enum { MIN_SIDE_PX = 32 };
#define MAX_MEGAPIXELS 100.0
/* The curvature-adaptive domains (rings of the mesh): each within 0.25 px of
 * its chord, and its tangent angle within 0.25 deg of linear in arc length
 * (more domains where the curvature changes; bounds the interpolated shading
 * normal's error between rings). */
#define DOMAIN_TOL_PX 0.25
#define DOMAIN_TOL_NORMAL_DEG 0.25

reconstruct_options reconstruct_options_default(void)
{
    return (reconstruct_options){
        .recon = {.threshold = -1, .side = RECON_SIDE_AUTO}, .smoothing_px = 1.0, .segments = 360};
}

static double ms_since(double t0) { return 1e3 * (now_seconds() - t0); }

static int fail(int code, char *err, size_t errlen, const char *what)
{
    snprintf(err, errlen, "%s", what);
    return code;
}

int reconstruct_photo(const char *path, const reconstruct_options *opt, reconstruction *r, char *err,
                      size_t errlen)
{
    memset(r, 0, sizeof *r);
    double t_start = now_seconds(), t0 = t_start;
    if (image_read_checked(path, MIN_SIDE_PX, MAX_MEGAPIXELS, &r->photo, err, errlen) != 0)
        return 2;
    r->ms.decode = ms_since(t0);

    recon_status rs = recon_extract(&r->photo, &opt->recon, &r->extract, err, errlen);
    if (rs != RECON_OK)
        return rs == RECON_ERR_INTERNAL ? 1 : 2;
    r->ms.image = r->extract.ms_image_processing;

    t0 = now_seconds();
    if (bspline_fit_profile(r->extract.polyline, r->extract.n_polyline, opt->smoothing_px, &r->curve, NULL) != 0)
        return fail(2, err, errlen, "the profile is too short or degenerate to fit a curve");
    r->ms.bspline = ms_since(t0);
    t0 = now_seconds();
    if (curve_domains_by_curvature_variation(&r->curve, DOMAIN_TOL_PX, DOMAIN_TOL_NORMAL_DEG, &r->domains,
                                             &r->n_domains) != 0)
        return fail(1, err, errlen, "cannot split the curve into domains");
    r->ms.domains = ms_since(t0);
    t0 = now_seconds();
    curve_polyline_hausdorff(&r->curve, r->extract.polyline, r->extract.n_polyline, &r->err_curve_to_polyline,
                             &r->err_polyline_to_curve);
    r->ms.hausdorff = ms_since(t0);

    t0 = now_seconds();
    if (recon_texture_from_photo(&r->photo, &r->extract, &r->texture, err, errlen) != 0)
        return 2;
    r->ms.texture = ms_since(t0);
    r->ms.total = ms_since(t_start);
    return 0;
}

void reconstruction_profile(const reconstruction *r, const char *source, profile_t *p)
{
    const recon_result *x = &r->extract;
    memset(p, 0, sizeof *p);
    snprintf(p->source_path, sizeof p->source_path, "%s", source);
    p->source_width = r->photo.width;
    p->source_height = r->photo.height;
    p->axis_origin = x->axis_origin;
    p->axis_direction = x->axis_direction;
    p->tilt_deg = x->tilt_deg;
    memcpy(p->corners, x->corners, sizeof p->corners);
    snprintf(p->side, sizeof p->side, "%s", x->side_used == RECON_SIDE_LEFT ? "left" : "right");
    p->n_polyline = x->n_polyline;
    p->polyline = x->polyline;
    p->curve = r->curve;
    p->n_domains = r->n_domains;
    p->domains = r->domains;
    p->err_curve_to_polyline = r->err_curve_to_polyline;
    p->err_polyline_to_curve = r->err_polyline_to_curve;
    p->contour_points = x->n_contour;
    p->ms_image_processing = r->ms.image;
    p->ms_bspline = r->ms.bspline + r->ms.domains;
    p->ms_texture = r->ms.texture;
    p->ms_mesh = r->ms.mesh;
}

void reconstruction_free(reconstruction *r)
{
    recon_texture_free(&r->texture);
    free(r->domains);
    bspline_free(&r->curve);
    recon_result_free(&r->extract);
    image_free(&r->photo);
    memset(r, 0, sizeof *r);
}
