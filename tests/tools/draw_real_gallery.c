/* The gallery of real museum photographs, as `make gallery-real` writes it:
 *
 *   draw_real_gallery DOCSDIR PHOTO...
 *
 * reconstructs each photo as `celadon reconstruct --force` does and writes
 * DOCSDIR/img/real-dev/NAME.jpg (its overlay drawn over the segmentation,
 * not over the photo: the photos stay outside the project; each row links
 * to its source) and DOCSDIR/gallery-real.md (every photo with the gate's
 * verdict, its figures and what was left out of the profile, and the count
 * and median left/right disagreement of those that pass). */
#include <cairo.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <gsl/gsl_statistics_double.h>

#include "celadon/image.h"
#include "sheet/recon_sheet.h"

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
    int n = argc - 2, passed = 0;
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
        if (sheet_reconstruct_overlay(path, 1, &r, &ov, verdict, sizeof verdict) != 0 || write_thumbnail(thumb, &ov)) {
            fprintf(stderr, "draw_real_gallery: %s: cannot draw\n", path);
            return 1;
        }
        image_free(&ov);
        int refused = strncmp(verdict, "refused", 7) == 0;
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
        snprintf(rows[i], 8192, "| ![%s](img/real-dev/%s.jpg) | **%s**<br>[source](https://www.metmuseum.org/art/collection/search/%s) | %s | %s | %s |\n",
                 name, name, name, num ? num + 1 : "",
                 !refused && q->passed ? (r.used_prior ? "**passed** (with the object prior)" : "**passed**") : gate,
                 figures,
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
               "| overlay | photo | gate | figures | left out of the profile |\n|---|---|---|---|---|\n",
            n, passed, n, 100 * median);
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
