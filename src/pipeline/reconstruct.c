/* reconstruct_photo: decode -> image stages -> B-spline -> domains ->
 * Hausdorff errors -> camera and meridian -> texture. See
 * include/celadon/reconstruct.h. */
#include "celadon/reconstruct.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/curve_distance.h"
#include "celadon/curve_domains.h"
#include "celadon/curve_fit.h"
#include "core/core.h"
#include "prior/prior.h"

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

/* The Hausdorff distances between the curve and the polyline's pieces: the
 * rows left out (a handle, bridged) are not part of the outline, so neither
 * the chord across them nor the curve over them is measured. The curve's
 * parameter is the polyline's normalised chord length (curve_fit.h). */
static void bridged_hausdorff(reconstruction *r)
{
    const vec2 *p = r->extract.polyline;
    const uint8_t *bridge = r->extract.polyline_bridge;
    int n = r->extract.n_polyline;
    double total = 0, at = 0;
    for (int i = 0; i + 1 < n; i++)
        total += v2_len(v2_sub(p[i + 1], p[i]));
    r->err_curve_to_polyline = r->err_polyline_to_curve = 0;
    for (int a = 0; a < n;) {
        int b = a;
        double u0 = total > 0 ? at / total : 0;
        while (b + 1 < n && !(bridge && bridge[b])) {
            at += v2_len(v2_sub(p[b + 1], p[b]));
            b++;
        }
        /* The curve leaves a piece's end toward the bridge: its parameter
         * (chord length) locates the end to within a pixel or two, so the
         * curve side stops 2 px short of an end next to a bridge. */
        double u1 = total > 0 ? at / total : 1, margin = total > 0 ? 2.0 / total : 0;
        if (a > 0)
            u0 += margin;
        if (b + 1 < n && bridge && bridge[b])
            u1 -= margin;
        double c2p, p2c;
        curve_range_polyline_hausdorff(&r->curve, u0, u1 > u0 ? u1 : u0, p + a, b - a + 1, &c2p, &p2c);
        r->err_curve_to_polyline = fmax(r->err_curve_to_polyline, c2p);
        r->err_polyline_to_curve = fmax(r->err_polyline_to_curve, p2c);
        if (b + 1 < n)
            at += v2_len(v2_sub(p[b + 1], p[b]));
        a = b + 1;
    }
}

/* The quality figures and their verdict. */
static void assess(reconstruction *r)
{
    reconstruct_quality *q = &r->quality;
    q->hausdorff_px = fmax(r->err_curve_to_polyline, r->err_polyline_to_curve);
    q->lr_disagreement = r->extract.lr_disagreement;
    q->excluded_fraction = r->extract.excluded_fraction;
    q->border_contact = r->extract.border_contact;
    size_t len = 0;
    q->failed[0] = '\0';
#define FAILED(...) len += (size_t)snprintf(q->failed + len, len < sizeof q->failed ? sizeof q->failed - len : 0, __VA_ARGS__)
    if (q->border_contact) {
        static const char *edge[4] = {"top", "bottom", "left", "right"};
        for (int k = 0; k < 4; k++)
            if (q->border_contact & (1u << k))
                FAILED("%sthe vessel touches the %s image border", len ? "; " : "", edge[k]);
        FAILED(" (leave a margin around the vessel)");
    }
    if (!(q->lr_disagreement <= RECONSTRUCT_MAX_LR_DISAGREEMENT))
        FAILED("%sleft and right outlines disagree by %.1f%% of the largest radius (limit %.0f%%)", len ? "; " : "",
               100 * q->lr_disagreement, 100 * RECONSTRUCT_MAX_LR_DISAGREEMENT);
    if (!(q->excluded_fraction <= RECONSTRUCT_MAX_EXCLUDED_FRACTION))
        FAILED("%s%.0f%% of the profile's rows are one-sided or bridged (limit %.0f%%)", len ? "; " : "",
               100 * q->excluded_fraction, 100 * RECONSTRUCT_MAX_EXCLUDED_FRACTION);
    if (!(q->hausdorff_px <= RECONSTRUCT_MAX_HAUSDORFF_PX))
        FAILED("%sthe B-spline is %.2f px from the outline (Hausdorff; limit %.2f px)", len ? "; " : "",
               q->hausdorff_px, RECONSTRUCT_MAX_HAUSDORFF_PX);
#undef FAILED
    q->passed = len == 0;
}

/* The camera and the meridian (recon_camera.h): the focal length from --fov,
 * else from the photo's EXIF, else from the ellipses. A failure is not the
 * photo's: the image outline stays the profile and camera_note says why. */
static void fit_camera(const char *path, const reconstruct_options *opt, reconstruction *r)
{
    recon_camera_options copt = opt->camera;
    if (path && !(copt.fov_deg > 0) && !(copt.focal_35mm > 0))
        copt.focal_35mm = image_exif_focal_35mm(path);
    if (!(copt.smoothing_px > 0))
        copt.smoothing_px = opt->smoothing_px;
    char why[200];
    r->has_camera = recon_camera_meridian(&r->photo, &r->extract, &copt, &r->camera, &r->meridian, why,
                                          sizeof why) == 0;
    if (!r->has_camera)
        snprintf(r->camera_note, sizeof r->camera_note, "no camera model: %s", why);
}

int reconstruction_is_perspective(const reconstruction *r)
{
    return r->has_camera && r->camera.method != RECON_CAMERA_ORTHOGRAPHIC;
}

static int fail(int code, char *err, size_t errlen, const char *what)
{
    snprintf(err, errlen, "%s", what);
    return code;
}

/* The image stages, the B-spline, its domains and errors, and the quality
 * figures, on r->photo with the object prior (or NULL). Returns 0, or the
 * exit code with err set. */
static int profile_stages(reconstruction *r, const reconstruct_options *opt, const float *prior, char *err,
                          size_t errlen)
{
    recon_options ro = opt->recon;
    ro.object_prior = prior;
    recon_status rs = recon_extract(&r->photo, &ro, &r->extract, err, errlen);
    if (rs != RECON_OK)
        return rs == RECON_ERR_INTERNAL ? 1 : 2;
    r->ms.image = r->extract.ms_image_processing;

    double t0 = now_seconds();
    if (bspline_fit_profile(r->extract.polyline, r->extract.n_polyline, opt->smoothing_px, &r->curve, NULL) != 0)
        return fail(2, err, errlen, "the profile is too short or degenerate to fit a curve");
    /* A surface of revolution needs r >= 0 at every control point (the
     * curve's convex hull then keeps r >= 0; sor_build refuses otherwise).
     * A fit through a mouth or a knob that closes on the axis can undershoot
     * it: such points are put on the axis, and the Hausdorff distance below
     * measures what that moved. */
    for (int i = 0; i < r->curve.n_ctrl; i++)
        r->curve.ctrl[i].x = fmax(0, r->curve.ctrl[i].x);
    r->ms.bspline = ms_since(t0);
    t0 = now_seconds();
    if (curve_domains_by_curvature_variation(&r->curve, DOMAIN_TOL_PX, DOMAIN_TOL_NORMAL_DEG, &r->domains,
                                             &r->n_domains) != 0)
        return fail(1, err, errlen, "cannot split the curve into domains");
    r->ms.domains = ms_since(t0);
    t0 = now_seconds();
    bridged_hausdorff(r);
    r->ms.hausdorff = ms_since(t0);
    assess(r);
    return 0;
}

/* Releases what profile_stages made, keeping the photo. */
static void drop_profile(reconstruction *r)
{
    free(r->domains);
    r->domains = NULL;
    r->n_domains = 0;
    bspline_free(&r->curve);
    recon_result_free(&r->extract);
    memset(&r->extract, 0, sizeof r->extract);
    memset(&r->quality, 0, sizeof r->quality);
}

/* The object prior of r->photo (malloc'd), or NULL when the network file is
 * missing or the network failed (err then says why; *failed is set). */
static float *photo_prior(reconstruction *r, int *failed, char *err, size_t errlen)
{
    double t0 = now_seconds();
    float *prior = malloc((size_t)r->photo.width * r->photo.height * sizeof *prior);
    int rc = prior ? object_prior_compute(&r->photo, prior, err, errlen) : -1;
    r->ms.prior = ms_since(t0);
    *failed = rc < 0;
    if (rc != 0) {
        if (!prior)
            snprintf(err, errlen, "out of memory");
        free(prior);
        return NULL;
    }
    return prior;
}

/* The profile by the chosen segmenter. auto: the classical segmentation, and
 * where its result is refused (by the image stages or the quality gate) and
 * it came from the segmentation, again with the prior: the prior's result is
 * kept when it passes, else the classical one stands. */
static int segmented_profile(reconstruction *r, const reconstruct_options *opt, char *err, size_t errlen)
{
    int failed = 0;
    if (opt->segmenter == RECONSTRUCT_SEGMENTER_LEARNED) {
        float *prior = photo_prior(r, &failed, err, errlen);
        if (failed)
            return 1;
        int code = profile_stages(r, opt, prior, err, errlen);
        r->used_prior = prior != NULL;
        free(prior);
        return code;
    }
    int code = profile_stages(r, opt, NULL, err, errlen);
    if (opt->segmenter == RECONSTRUCT_SEGMENTER_CLASSIC || code == 1 || (code == 0 && r->quality.passed) ||
        r->extract.mask_mode != RECON_MASK_GRAPH_CUT)
        return code;
    char err2[1024];
    float *prior = photo_prior(r, &failed, err2, sizeof err2);
    if (!prior)
        return code;
    reconstruction classic = *r;
    memset(&r->extract, 0, sizeof r->extract);
    memset(&r->curve, 0, sizeof r->curve);
    r->domains = NULL;
    r->n_domains = 0;
    int code2 = profile_stages(r, opt, prior, err2, sizeof err2);
    free(prior);
    if (code2 == 0 && r->quality.passed) {
        r->used_prior = 1;
        drop_profile(&classic); /* its own arrays: r's were reset before the second run */
        return 0;
    }
    double ms_prior = r->ms.prior;
    drop_profile(r);
    *r = classic;
    r->ms.prior = ms_prior;
    return code;
}

/* Every stage after the decoding, on r->photo; path (NULL for a photo from
 * memory) for its EXIF. t_start: when the run began. */
static int reconstruct_decoded(const char *path, const reconstruct_options *opt, reconstruction *r, double t_start,
                               char *err, size_t errlen)
{
    int code = segmented_profile(r, opt, err, errlen);
    if (code != 0)
        return code;
    if (!r->quality.passed && !opt->force) {
        snprintf(err, errlen, "quality gate: %s; --force writes the result anyway", r->quality.failed);
        return 2;
    }

    double t0 = now_seconds();
    fit_camera(path, opt, r);
    r->ms.camera = ms_since(t0);
    t0 = now_seconds();
    int tex = reconstruction_is_perspective(r)
                  ? recon_texture_from_camera(&r->photo, &r->camera, &r->meridian, &r->extract, &r->texture, err, errlen)
                  : recon_texture_from_photo(&r->photo, &r->extract, &r->texture, err, errlen);
    if (tex != 0)
        return 2;
    r->ms.texture = ms_since(t0);
    r->ms.total = ms_since(t_start);
    return 0;
}

int reconstruct_photo(const char *path, const reconstruct_options *opt, reconstruction *r, char *err,
                      size_t errlen)
{
    memset(r, 0, sizeof *r);
    double t_start = now_seconds();
    if (image_read_checked(path, MIN_SIDE_PX, MAX_MEGAPIXELS, &r->photo, err, errlen) != 0)
        return 2;
    r->ms.decode = ms_since(t_start);
    return reconstruct_decoded(path, opt, r, t_start, err, errlen);
}

int reconstruct_image(const image_t *photo, const reconstruct_options *opt, reconstruction *r, char *err,
                      size_t errlen)
{
    memset(r, 0, sizeof *r);
    double t_start = now_seconds();
    int w = photo->width, h = photo->height;
    /* The checks and words of image_read_checked. */
    if (w < MIN_SIDE_PX || h < MIN_SIDE_PX) {
        snprintf(err, errlen, "image too small (%dx%d; at least %dx%d needed)", w, h, MIN_SIDE_PX, MIN_SIDE_PX);
        return 2;
    }
    if ((double)w * h > MAX_MEGAPIXELS * 1e6) {
        snprintf(err, errlen, "image too large (%dx%d; at most %.0f megapixels)", w, h, MAX_MEGAPIXELS);
        return 2;
    }
    if (photo->channels < 1 || photo->channels > 4 || !photo->data)
        return fail(2, err, errlen, "an image has 1 to 4 channels");
    size_t n = (size_t)w * h * photo->channels;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(photo->data[i]))
            return fail(2, err, errlen, "the image has a value that is not finite");
    r->photo = image_alloc(w, h, photo->channels);
    if (!r->photo.data)
        return fail(1, err, errlen, "out of memory");
    memcpy(r->photo.data, photo->data, sizeof *photo->data * n);
    r->photo.bits = photo->bits, r->photo.has_alpha = photo->has_alpha;
    r->ms.decode = ms_since(t_start);
    return reconstruct_decoded(NULL, opt, r, t_start, err, errlen);
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
    p->n_excluded = x->n_excluded;
    for (int i = 0; i < x->n_excluded && i < (int)(sizeof p->excluded / sizeof p->excluded[0]); i++) {
        const recon_excluded *e = &x->excluded[i];
        snprintf(p->excluded[i].what, sizeof p->excluded[i].what, "%s", recon_part_name(e->what));
        p->excluded[i].rows[0] = e->row0;
        p->excluded[i].rows[1] = e->row1;
        p->excluded[i].side = e->side;
        snprintf(p->excluded[i].profile, sizeof p->excluded[i].profile, "%s", recon_profile_source_name(e->profile));
    }
    const reconstruct_quality *q = &r->quality;
    p->quality.present = 1;
    p->quality.passed = q->passed;
    p->quality.hausdorff_px = q->hausdorff_px;
    p->quality.lr_disagreement = q->lr_disagreement;
    p->quality.excluded_fraction = q->excluded_fraction;
    p->quality.border_contact = q->border_contact;
    if (r->has_camera)
        recon_camera_fill_profile(&r->camera, &r->meridian, p);
}

void reconstruction_free(reconstruction *r)
{
    recon_texture_free(&r->texture);
    recon_meridian_free(&r->meridian);
    free(r->domains);
    bspline_free(&r->curve);
    recon_result_free(&r->extract);
    image_free(&r->photo);
    memset(r, 0, sizeof *r);
}
