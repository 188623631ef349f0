/* The photo -> profile -> outputs pipeline: one library call that the CLI
 * (`celadon reconstruct`), the museum, the benchmarks and the tests share.
 *
 *   reconstruct_photo    decode, image stages (recon_extract), B-spline fit,
 *                        curvature domains, Hausdorff errors, the camera and
 *                        the meridian (recon_camera_meridian), texture
 *   reconstruct_write    profile.json, texture.png, model.obj/.mtl/.ply and
 *                        the --lod meshes, overlay.png: all or nothing
 *
 * Exit-code semantics of the returned status: 0 ok, 2 bad input (the photo
 * cannot be reconstructed, or the result fails the quality gate: err says why
 * in one line, without the file name), 1 internal failure (out of memory,
 * cannot write).
 *
 * The quality gate: every run measures the figures below; a figure over its
 * limit refuses the photo (status 2, err names the figure and its value),
 * unless opt->force is set: then the run goes on and quality.passed is 0.
 * docs/algorithms-recon.md ("Quality gate") explains the limits. */
#ifndef CELADON_RECONSTRUCT_H
#define CELADON_RECONSTRUCT_H

#include <stddef.h>

#include "celadon/bspline.h"
#include "celadon/image.h"
#include "celadon/mesh.h"
#include "celadon/profile.h"
#include "celadon/recon.h"
#include "celadon/recon_camera.h"
#include "celadon/recon_texture.h"

enum { RECONSTRUCT_MAX_LODS = 8 };

/* The limits of the quality gate. */
#define RECONSTRUCT_MAX_HAUSDORFF_PX 2.33   /* the paper's worst B-spline fit (Table 1) */
#define RECONSTRUCT_MAX_LR_DISAGREEMENT 0.02 /* mean |r_left - r_right| / r_max on rows both sides keep */
#define RECONSTRUCT_MAX_EXCLUDED_FRACTION 0.5 /* profile rows taken from one side only or bridged */

typedef struct {
    double hausdorff_px;      /* the larger one-sided Hausdorff distance between curve and polyline */
    double lr_disagreement;   /* see RECONSTRUCT_MAX_LR_DISAGREEMENT */
    double excluded_fraction;
    unsigned border_contact;  /* the vessel touches the image border: bits 1 top, 2 bottom, 4 left, 8 right */
    int passed;
    char failed[400];         /* the figures over their limits, one line ("" when passed) */
} reconstruct_quality;

/* Which segmentation decides the vessel's mask (docs/algorithms-recon.md,
 * "Learned object prior"): the classical energy alone; that energy with the
 * learned object prior as one more term; or the classical one first and the
 * prior only for a photo whose classical result fails the quality gate (or
 * is refused by the image stages), the prior's result kept when it passes.
 * Without the network file (`make deps-model`) every mode is classic. */
typedef enum { RECONSTRUCT_SEGMENTER_AUTO = 0, RECONSTRUCT_SEGMENTER_CLASSIC, RECONSTRUCT_SEGMENTER_LEARNED } reconstruct_segmenter;

typedef struct {
    recon_options recon;   /* image stages: threshold, side */
    reconstruct_segmenter segmenter;
    double smoothing_px;   /* largest distance of a profile point from the B-spline */
    int segments;          /* angular segments of model.obj/.ply */
    int lods[RECONSTRUCT_MAX_LODS], n_lods; /* extra meshes model_N.* */
    int mouth_cap;         /* close the mouth with a disc (the base is always closed) */
    int force;             /* write the outputs even when the quality gate fails */
    recon_camera_options camera; /* fov_deg (--fov); focal_35mm 0: read from the photo's EXIF */
} reconstruct_options;

/* The defaults of `celadon reconstruct`: automatic threshold and side, 1 px
 * smoothing, 360 segments, no LODs, open mouth, the focal length from the
 * ellipses or the EXIF. */
reconstruct_options reconstruct_options_default(void);

typedef struct {
    int segments, vertices, faces;
} reconstruct_mesh_stats;

/* Wall-clock milliseconds per stage (the paper's Table 1 and more). */
typedef struct {
    double decode, prior, image, bspline, domains, hausdorff, camera, texture, mesh, overlay, write, total;
} reconstruct_timings;

typedef struct {
    image_t photo;          /* the decoded photo */
    recon_result extract;   /* the image stages (mask, contour, axis, outline, polyline) */
    bspline_t curve;        /* the profile fitted to extract.polyline, (r, h) px */
    double *domains;        /* curvature domains: increasing u from 0 to 1 */
    int n_domains;
    double err_curve_to_polyline, err_polyline_to_curve; /* one-sided Hausdorff, px */
    /* The camera model: has_camera 1 when recon_camera_meridian succeeded
     * (perspective, or orthographic when the ellipses are too flat: see
     * camera.method and camera.note), then meridian is the vessel's profile
     * (profile.json "camera" and "meridian"); 0 when it failed (camera_note
     * says why): the image outline (curve) is the profile. */
    int has_camera;
    recon_camera camera;
    recon_meridian meridian;
    char camera_note[256];
    recon_texture_t texture; /* by the camera when it is perspective, else by scanlines */
    reconstruct_quality quality;
    int used_prior;          /* the mask was made with the learned object prior */
    reconstruct_mesh_stats mesh, lods[RECONSTRUCT_MAX_LODS]; /* filled by reconstruct_write */
    reconstruct_timings ms;
} reconstruction;

/* Runs every stage up to the texture on the photo at path. On failure the
 * result holds no arrays; either way reconstruction_free releases it. */
int reconstruct_photo(const char *path, const reconstruct_options *opt, reconstruction *r, char *err,
                      size_t errlen);

/* reconstruct_photo on a photo in memory (pixels as image_read gives them:
 * floats in [0, 1], 1 to 4 channels, has_alpha for a last alpha channel),
 * copied; held to the same size limits, with the same words. No EXIF: the
 * focal length comes from opt->camera or the ellipses. */
int reconstruct_image(const image_t *photo, const reconstruct_options *opt, reconstruction *r, char *err,
                      size_t errlen);

/* One option of `celadon reconstruct` by its name without the dashes:
 * "threshold", "side", "segmenter", "segments", "lod", "smoothing", "fov"
 * (values as on the command line), "force" or "mouth-cap" ("1" or "0").
 * The command line sets its options through it, so both check alike.
 * Returns 0, or -1 with one line in err ("NAME wants ..., not 'VALUE'"). */
int reconstruct_option_set(reconstruct_options *opt, const char *name, const char *value, char *err,
                           size_t errlen);

/* For callers that hold a reconstruction by pointer (the Python package):
 * the n options names[i] = values[i] (reconstruct_option_set) over the
 * defaults, then reconstruct_photo(path), or when path is NULL
 * reconstruct_image(photo). NULL on failure, with *status (2 bad input, 1
 * other) and err; reconstruction_destroy releases it. */
reconstruction *reconstruction_create(const char *path, const image_t *photo, const char *const *names,
                                      const char *const *values, int n, int *status, char *err, size_t errlen);
void reconstruction_destroy(reconstruction *r);

/* Through the profile view (reconstruction_profile with source): its
 * profile.json text (profile_json_text), its radius at height h
 * (profile_radius), and its mesh as reconstruct_write revolves model.obj
 * (height 1, caps MESH_CAP_*). */
char *reconstruction_profile_text(const reconstruction *r, const char *source, char *err, size_t errlen);
int reconstruction_radius(const reconstruction *r, double h, double *radius);
int reconstruction_mesh(const reconstruction *r, int segments, unsigned caps, mesh_t *m);

/* 1 when the camera is perspective (not the orthographic fallback). */
int reconstruction_is_perspective(const reconstruction *r);

/* The profile.json view of a reconstruction (borrows r's arrays: valid while
 * r is; do not profile_free it). source is the photo's path as recorded in
 * the file. Its profile_shape() is the meridian when r has a camera. */
void reconstruction_profile(const reconstruction *r, const char *source, profile_t *p);

/* Writes every output into the folder dir (created if missing; its parent
 * must exist). The files are written into a temporary folder and moved into
 * place only when all are complete, so a failure leaves nothing behind.
 * Fills r->mesh, r->lods and the overlay/mesh/write timings. Returns 0 or 1
 * (err: one line). */
int reconstruct_write(reconstruction *r, const char *source, const char *dir, const reconstruct_options *opt,
                      char *err, size_t errlen);

void reconstruction_free(reconstruction *r);

#endif
