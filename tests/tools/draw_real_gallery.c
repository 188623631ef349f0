/* The gallery of real museum photographs, as `make gallery-real` writes it:
 *
 *   draw_real_gallery DOCSDIR PHOTO...
 *
 * reconstructs each photo as `celadon reconstruct --force` does and writes
 * DOCSDIR/img/real-dev/NAME.jpg (its overlay drawn over the segmentation,
 * not over the photo: the photos stay outside the project; each row links
 * to its source) and DOCSDIR/gallery-real.md (every photo with the gate's
 * verdict, its figures and what was left out of the profile, and the count
 * and median left/right disagreement of those that pass). Where the photo
 * has a truth (tests/support/realdev_truth.h), its outline is drawn green on
 * the overlay and each segmenter (classic, learned, auto) is measured
 * against it: the mask's IoU and the profile's distance from the true
 * outline. */
#include <cairo.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <gsl/gsl_statistics_double.h>

#include "celadon/image.h"
#include "sheet/recon_sheet.h"
#include "../support/realdev_truth.h"

enum { THUMB_W = 320 };

/* The overlay as a THUMB_W wide JPEG. */
static int write_thumbnail(const char *path, const image_t *ov)
{
    double s = (double)THUMB_W / ov->width;
    int th = (int)(ov->height * s);
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, THUMB_W, th);
    sheet_paint_thumbnail(sf, ov, 0, 0, s);
    cairo_surface_flush(sf);
    const unsigned char *data = cairo_image_surface_get_data(sf);
    int stride = cairo_image_surface_get_stride(sf);
    uint8_t *rgb = malloc((size_t)THUMB_W * th * 3);
    int rc = -1;
    char err[256];
    if (rgb) {
        for (int j = 0; j < th; j++)
            for (int i = 0; i < THUMB_W; i++) {
                uint32_t px = *(const uint32_t *)(data + (size_t)j * stride + 4 * i);
                for (int q = 0; q < 3; q++)
                    rgb[((size_t)j * THUMB_W + i) * 3 + q] = (uint8_t)(px >> (16 - 8 * q));
            }
        rc = image_write_u8(path, THUMB_W, th, 3, rgb, err, sizeof err);
        if (rc)
            fprintf(stderr, "draw_real_gallery: %s: %s\n", path, err);
    }
    free(rgb);
    cairo_surface_destroy(sf);
    return rc;
}

/* The photo's file name without folder and extension. */
static void stem(const char *path, char *out, size_t len)
{
    const char *b = strrchr(path, '/');
    snprintf(out, len, "%s", b ? b + 1 : path);
    char *dot = strrchr(out, '.');
    if (dot)
        *dot = '\0';
}

/* What the profile left out, one phrase per part. */
static void parts_text(const recon_result *x, char *out, size_t len)
{
    size_t at = 0;
    out[0] = '\0';
    for (int i = 0; i < x->n_excluded && at < len; i++) {
        const recon_excluded *e = &x->excluded[i];
        at += (size_t)snprintf(out + at, len - at, "%s%s (%s, rows %d–%d, profile %s)", i ? "; " : "",
                               recon_part_name(e->what), e->side < 0 ? "left" : (e->side > 0 ? "right" : "both"),
                               e->row0, e->row1, recon_profile_source_name(e->profile));
    }
}

/* The truth mask's border pixels in green over the overlay. */
static void draw_truth(image_t *ov, const realdev_truth *t)
{
    if (ov->width != t->width || ov->height != t->height)
        return;
    for (int j = 1; j + 1 < t->height; j++)
        for (int i = 1; i + 1 < t->width; i++) {
            const uint8_t *m = t->mask + (size_t)j * t->width + i;
            if (*m && (!m[-1] || !m[1] || !m[-t->width] || !m[t->width])) {
                float *px = ov->data + ((size_t)j * t->width + i) * 3;
                px[0] = 0.1f, px[1] = 0.7f, px[2] = 0.1f;
            }
        }
}

typedef struct {
    int passed, on;        /* ran and passed the gate; on the true outline */
    double iou, off, over; /* against the truth: mask IoU, outline distance and overreach (of the body's height) */
} truth_run;

static void measure(const reconstruction *r, int status, const realdev_truth *t, truth_run *out)
{
    out->passed = status == 0 && r->quality.passed;
    out->iou = status == 0 && r->extract.mask ? realdev_truth_iou(t, r->extract.mask) : NAN;
    out->off = status == 0 ? realdev_truth_outline(t, &r->extract) : INFINITY;
    out->over = status == 0 ? realdev_truth_overreach(t, &r->extract) : INFINITY;
    out->on = status == 0 && realdev_truth_on_outline(t, &r->extract);
}

static void run_segmenter(const char *path, reconstruct_segmenter s, const realdev_truth *t, truth_run *out)
{
    reconstruction r;
    char err[400];
    int st = sheet_reconstruct_forced(path, s, &r, err, sizeof err);
    measure(&r, st, t, out);
    reconstruction_free(&r);
}

/* "0.991, 0.21% / 0.00%, pass" for one run: IoU, outline / overreach, gate; bold when off the outline. */
static void truth_text(const truth_run *u, char *out, size_t len)
{
    char off[64] = "off";
    const char *b = u->on ? "" : "**";
    if (isfinite(u->off))
        snprintf(off, sizeof off, "%s%.2f%% / %.2f%%%s", b, 100 * u->off, 100 * u->over, b);
    if (isnan(u->iou))
        snprintf(out, len, "refused");
    else
        snprintf(out, len, "%.3f, %s, %s", u->iou, off, u->passed ? "pass" : "gate");
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: draw_real_gallery DOCSDIR PHOTO...\n");
        return 2;
    }
    char dir[4096], md[4096], tmp[4200];
    snprintf(dir, sizeof dir, "%s/img/real-dev", argv[1]);
    snprintf(md, sizeof md, "%s/gallery-real.md", argv[1]);
    snprintf(tmp, sizeof tmp, "%s.tmp", md);
    char parent[4096];
    snprintf(parent, sizeof parent, "%s/img", argv[1]);
    mkdir(parent, 0777);
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "draw_real_gallery: %s: cannot create\n", dir);
        return 2;
    }
    int n = argc - 2, passed = 0, truths = 0, on_outline = 0, wrong = 0;
    double *lr = calloc((size_t)n, sizeof *lr);
    char **rows = calloc((size_t)n, sizeof *rows);
    if (!lr || !rows)
        return 1;
    for (int i = 0; i < n; i++) {
        const char *path = argv[2 + i];
        char name[256], thumb[4600], verdict[600], parts[2048];
        stem(path, name, sizeof name);
        snprintf(thumb, sizeof thumb, "%s/%s.jpg", dir, name);
        reconstruction r = {0};
        image_t ov;
        if (sheet_reconstruct_overlay(path, 1, &r, &ov, verdict, sizeof verdict) != 0) {
            fprintf(stderr, "draw_real_gallery: %s: cannot draw\n", path);
            return 1;
        }
        int refused = strncmp(verdict, "refused", 7) == 0;
        realdev_truth t;
        char truth_cols[400] = "– | – | –";
        if (realdev_truth_load(path, &t) == 0) {
            truth_run c, l, a;
            run_segmenter(path, RECONSTRUCT_SEGMENTER_CLASSIC, &t, &c);
            run_segmenter(path, RECONSTRUCT_SEGMENTER_LEARNED, &t, &l);
            measure(&r, refused ? 2 : 0, &t, &a);
            char tc[3][120];
            truth_text(&c, tc[0], sizeof tc[0]);
            truth_text(&l, tc[1], sizeof tc[1]);
            truth_text(&a, tc[2], sizeof tc[2]);
            snprintf(truth_cols, sizeof truth_cols, "%s | %s | %s", tc[0], tc[1], tc[2]);
            truths++;
            on_outline += a.passed && a.on;
            wrong += a.passed && !a.on;
            draw_truth(&ov, &t);
            printf("%-50s truth: classic %s; learned %s; auto %s\n", name, tc[0], tc[1], tc[2]);
            realdev_truth_free(&t);
        }
        if (write_thumbnail(thumb, &ov)) {
            fprintf(stderr, "draw_real_gallery: %s: cannot draw\n", path);
            return 1;
        }
        image_free(&ov);
        parts_text(&r.extract, parts, sizeof parts);
        const reconstruct_quality *q = &r.quality;
        if (!refused && q->passed)
            lr[passed++] = q->lr_disagreement;
        /* Met file names end in the object's number: its page */
        const char *num = strrchr(name, '_');
        rows[i] = malloc(8192);
        if (!rows[i])
            return 1;
        char figures[160] = "–";
        if (!refused)
            snprintf(figures, sizeof figures, "Hausdorff %.2f px, L/R %.2f%%, one-sided %.0f%%", q->hausdorff_px,
                     100 * q->lr_disagreement, 100 * q->excluded_fraction);
        char gate[700];
        snprintf(gate, sizeof gate, "%s%s", refused ? "" : "refused by the quality gate: ", verdict);
        snprintf(rows[i], 8192, "| ![%s](img/real-dev/%s.jpg) | **%s**<br>[source](https://www.metmuseum.org/art/collection/search/%s) | %s | %s | %s | %s |\n",
                 name, name, name, num ? num + 1 : "",
                 !refused && q->passed ? (r.used_prior ? "**passed** (with the object prior)" : "**passed**") : gate,
                 figures, truth_cols,
                 parts[0] ? parts : "nothing");
        printf("%-50s %s\n", name, !refused && q->passed ? "passed" : gate);
        reconstruction_free(&r);
    }
    double median = passed ? gsl_stats_median(lr, 1, (size_t)passed) : 0;
    FILE *f = fopen(tmp, "w");
    if (!f) {
        fprintf(stderr, "draw_real_gallery: %s: cannot write\n", tmp);
        return 2;
    }
    fprintf(f, "# Gallery: the real museum photographs\n\n"
               "Every photo of the real-dev set (%d museum photographs from The Met, CC0; the\n"
               "set is not part of the project: each row links to its source) reconstructed\n"
               "as `celadon reconstruct --force` does. Each picture is the reconstruction's\n"
               "overlay drawn over its segmentation (the vessel's mask in grey) instead of\n"
               "the photo: the contour (blue), the axis (black), the fitted profile\n"
               "(magenta, on the side it was taken from), the corners, and the parts left\n"
               "out of the profile (handles yellow, asymmetry orange, shadows and stands\n"
               "blue). `make real-dev` writes the same overlays over the photos themselves\n"
               "into out/real-dev/; `make gallery-real` rewrites this page. The segmenter is\n"
               "the default, auto: the learned object prior (algorithms-recon.md, section 14)\n"
               "runs only on a photo the classical segmentation leaves refused, and its\n"
               "result is kept when it passes (marked \"with the object prior\").\n\n"
               "**%d of %d pass the quality gate**; the median left/right disagreement of\n"
               "those is %.2f%% of the largest radius. How the gate decides and the known\n"
               "failures: [algorithms-recon.md](algorithms-recon.md) (sections 9 and 12).\n\n"
               "**Truth.** %d photos have a hand-checked truth (tests/data/real-dev-truth/,\n"
               "its outline green on the overlays): the vessel's mask, handles and lid in,\n"
               "stand, plinth and shadows out; its rows are the body's.\n"
               "Each segmenter is measured against it: the mask's IoU; the profile's mean\n"
               "distance from the true outline in %% of the body's height over the body's\n"
               "rows but the worst fifth; and how far the profile reaches beyond the\n"
               "body's rows, in %% of its height (tests/support/realdev_truth.h). At most\n"
               "0.5%% and 1%% is *on the true outline*; off it is in bold, \"off\" when the\n"
               "profile misses more than a fifth of the body. With auto, **passing the gate\n"
               "on the true outline: %d; passing off it (accepted wrong): %d; refused: %d**.\n"
               "How the masks were made: [algorithms-recon.md](algorithms-recon.md), section 11.\n\n"
               "| overlay | photo | gate (auto) | figures | truth: classic (IoU, outline / beyond, gate) | learned | auto | left out of the profile |\n"
               "|---|---|---|---|---|---|---|---|\n",
            n, passed, n, 100 * median, truths, on_outline, wrong, truths - on_outline - wrong);
    for (int i = 0; i < n; i++) {
        fputs(rows[i], f);
        free(rows[i]);
    }
    free(rows);
    free(lr);
    if (fclose(f) != 0 || rename(tmp, md) != 0) {
        fprintf(stderr, "draw_real_gallery: %s: cannot write\n", md);
        remove(tmp);
        return 2;
    }
    return 0;
}
