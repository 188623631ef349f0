/* The hand-checked truth masks of the real-dev photographs
 * (tests/data/real-dev-truth/, docs/gallery-real.md "Truth"), made with the
 * tool's help and corrected by hand:
 *
 *   real_truth seed PHOTO OUT.png NET.png
 *       the learned segmentation's mask (--segmenter learned --force) and
 *       the network's own mask (probability > 0.5), as 0/255 PNGs: the start
 *   real_truth edit SEED.png NET.png EDITS NAME OUT.png
 *       the truth: SEED, or NET after a line "NAME base net" (or their
 *       union after "NAME base union"), then the polygons of EDITS's lines
 *       for NAME in order (photo pixels; a pixel is inside when its centre
 *       is): "NAME add x,y x,y ..." fills the polygon with vessel, "NAME
 *       cut ..." with not-vessel, "NAME net ..." with NET's labels and
 *       "NAME seed ..." with SEED's
 *   real_truth check PHOTO MASK.png OUT.png [OTHER.png] [X Y W H ZOOM]
 *       the photo tinted blue outside MASK, red where only OTHER holds the
 *       vessel, green where only MASK does; optionally cropped to X Y W H
 *       and magnified ZOOM times (nearest, MASK's border pixels then red):
 *       what the eye checks against the photo's edge.
 *
 * The committed masks are the edited ones; the seeds depend on the code of
 * the day, so they are the start, not the truth. */
#include <cairo.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/image.h"
#include "celadon/reconstruct.h"
#include "prior/prior.h"
#include "sheet/recon_sheet.h"

static int write_mask(const char *path, const uint8_t *m, int w, int h)
{
    uint8_t *px = malloc((size_t)w * h);
    char err[256];
    if (!px)
        return -1;
    for (size_t i = 0; i < (size_t)w * h; i++)
        px[i] = m[i] ? 255 : 0;
    int rc = image_write_u8(path, w, h, 1, px, err, sizeof err);
    if (rc)
        fprintf(stderr, "real_truth: %s: %s\n", path, err);
    free(px);
    return rc;
}

/* A 0/1 mask from a PNG's first channel; NULL when unreadable. */
static uint8_t *read_mask(const char *path, int *w, int *h)
{
    image_t img;
    char err[256];
    if (image_read(path, &img, err, sizeof err) != 0) {
        fprintf(stderr, "real_truth: %s: %s\n", path, err);
        return NULL;
    }
    uint8_t *m = malloc((size_t)img.width * img.height);
    for (size_t i = 0; m && i < (size_t)img.width * img.height; i++)
        m[i] = img.data[i * img.channels] > 0.5f;
    *w = img.width;
    *h = img.height;
    image_free(&img);
    return m;
}

static int seed(const char *photo, const char *out, const char *net_out)
{
    reconstruction r;
    char err[512];
    int st = sheet_reconstruct_forced(photo, RECONSTRUCT_SEGMENTER_LEARNED, &r, err, sizeof err);
    if (st != 0 || !r.extract.mask) {
        fprintf(stderr, "real_truth: %s: %s\n", photo, st ? err : "no mask");
        reconstruction_free(&r);
        return 1;
    }
    int w = r.extract.width, h = r.extract.height;
    int rc = write_mask(out, r.extract.mask, w, h);
    float *prob = malloc((size_t)w * h * sizeof *prob);
    uint8_t *net = malloc((size_t)w * h);
    if (!rc && prob && net && object_prior_compute(&r.photo, prob, err, sizeof err) == 0) {
        for (size_t i = 0; i < (size_t)w * h; i++)
            net[i] = prob[i] > 0.5f;
        rc = write_mask(net_out, net, w, h);
    }
    free(prob);
    free(net);
    reconstruction_free(&r);
    return rc ? 1 : 0;
}

/* Sets m to src (or to v when src is NULL) inside one polygon given as "x,y x,y ..." (pixel centres
 * inside, even-odd). */
static int fill_polygon(uint8_t *m, int w, int h, const char *pts, const uint8_t *src, int v)
{
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_A8, w, h);
    cairo_t *cr = cairo_create(s);
    cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
    int n = 0;
    double x, y;
    int used;
    while (sscanf(pts, " %lf,%lf%n", &x, &y, &used) == 2) {
        if (n++ == 0)
            cairo_move_to(cr, x, y);
        else
            cairo_line_to(cr, x, y);
        pts += used;
    }
    cairo_close_path(cr);
    cairo_fill(cr);
    cairo_surface_flush(s);
    const unsigned char *d = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            if (d[(size_t)j * stride + i] > 127)
                m[(size_t)j * w + i] = src ? src[(size_t)j * w + i] : (uint8_t)v;
    cairo_destroy(cr);
    cairo_surface_destroy(s);
    return n >= 3 ? 0 : -1;
}

static int edit(const char *seed_png, const char *net_png, const char *edits, const char *name, const char *out)
{
    int w, h, w2 = 0, h2 = 0;
    uint8_t *seed = read_mask(seed_png, &w, &h), *net = read_mask(net_png, &w2, &h2);
    uint8_t *m = malloc((size_t)w * h);
    FILE *f = fopen(edits, "r");
    if (!seed || !net || !m || !f || w != w2 || h != h2) {
        fprintf(stderr, "real_truth: cannot read %s, %s or %s\n", seed_png, net_png, edits);
        return 1;
    }
    memcpy(m, seed, (size_t)w * h);
    char line[8192], who[256], op[16], arg[16];
    int used, lineno = 0, rc = 0;
    while (!rc && fgets(line, sizeof line, f)) {
        lineno++;
        if (line[0] == '#' || sscanf(line, "%255s %15s%n", who, op, &used) != 2 || strcmp(who, name))
            continue;
        if (!strcmp(op, "base") && sscanf(line + used, "%15s", arg) == 1 && (!strcmp(arg, "net") || !strcmp(arg, "union")))
            for (size_t i = 0; i < (size_t)w * h; i++)
                m[i] = net[i] || (arg[0] == 'u' && seed[i]);
        else if (!strcmp(op, "add") || !strcmp(op, "cut") || !strcmp(op, "net") || !strcmp(op, "seed"))
            rc = fill_polygon(m, w, h, line + used, op[0] == 'n' ? net : op[0] == 's' ? seed : NULL, op[0] == 'a');
        else
            rc = -1;
        if (rc)
            fprintf(stderr, "real_truth: %s:%d: not an edit\n", edits, lineno);
    }
    fclose(f);
    rc = rc || write_mask(out, m, w, h);
    free(m);
    free(seed);
    free(net);
    return rc ? 1 : 0;
}

static int border(const uint8_t *m, int w, int h, int i, int j)
{
    if (!m[(size_t)j * w + i])
        return 0;
    return i == 0 || j == 0 || i == w - 1 || j == h - 1 || !m[(size_t)j * w + i - 1] || !m[(size_t)j * w + i + 1] ||
           !m[(size_t)(j - 1) * w + i] || !m[(size_t)(j + 1) * w + i];
}

static int check(int argc, char **argv)
{
    image_t ph;
    char err[256];
    int w, h, w2 = 0, h2 = 0;
    if (image_read(argv[2], &ph, err, sizeof err) != 0) {
        fprintf(stderr, "real_truth: %s: %s\n", argv[2], err);
        return 1;
    }
    uint8_t *m = read_mask(argv[3], &w, &h);
    int at = 5;
    uint8_t *o = NULL;
    if (argc == 6 || argc == 11)
        o = read_mask(argv[at++], &w2, &h2);
    if (!m || w != ph.width || h != ph.height || (o && (w2 != w || h2 != h))) {
        fprintf(stderr, "real_truth: the masks are not the photo's size\n");
        return 1;
    }
    int x0 = 0, y0 = 0, cw = w, ch = h, z = 1;
    if (argc - at == 5) {
        x0 = atoi(argv[at]);
        y0 = atoi(argv[at + 1]);
        cw = atoi(argv[at + 2]);
        ch = atoi(argv[at + 3]);
        z = atoi(argv[at + 4]);
        if (x0 < 0 || y0 < 0 || cw < 1 || ch < 1 || z < 1 || x0 + cw > w || y0 + ch > h) {
            fprintf(stderr, "real_truth: the crop is not inside the photo\n");
            return 1;
        }
    }
    uint8_t *rgb = malloc((size_t)cw * z * ch * z * 3);
    for (int j = 0; j < ch * z; j++)
        for (int i = 0; i < cw * z; i++) {
            int pi = x0 + i / z, pj = y0 + j / z;
            float c[3];
            for (int k = 0; k < 3; k++)
                c[k] = ph.data[((size_t)pj * w + pi) * ph.channels + (ph.channels >= 3 ? k : 0)];
            int in = m[(size_t)pj * w + pi], other = o ? o[(size_t)pj * w + pi] : in;
            /* outside the mask tinted blue; where OTHER differs, red (OTHER only) or green (MASK only) */
            const float tint[3][3] = {{0.2f, 0.3f, 1}, {1, 0.1f, 0.1f}, {0.1f, 1, 0.1f}};
            int k0 = in != other ? (other ? 1 : 2) : (!in ? 0 : -1);
            for (int k = 0; k0 >= 0 && k < 3; k++)
                c[k] = 0.85f * c[k] + 0.15f * tint[k0][k];
            if (border(m, w, h, pi, pj) && z > 1)
                c[0] = 1, c[1] = c[2] = 0;
            for (int k = 0; k < 3; k++)
                rgb[((size_t)j * cw * z + i) * 3 + k] = (uint8_t)(255 * c[k] + 0.5f);
        }
    int rc = image_write_u8(argv[4], cw * z, ch * z, 3, rgb, err, sizeof err);
    if (rc)
        fprintf(stderr, "real_truth: %s: %s\n", argv[4], err);
    free(rgb);
    free(m);
    free(o);
    image_free(&ph);
    return rc ? 1 : 0;
}

int main(int argc, char **argv)
{
    if (argc == 5 && !strcmp(argv[1], "seed"))
        return seed(argv[2], argv[3], argv[4]);
    if (argc == 7 && !strcmp(argv[1], "edit"))
        return edit(argv[2], argv[3], argv[4], argv[5], argv[6]);
    if (argc >= 5 && !strcmp(argv[1], "check") && (argc == 5 || argc == 6 || argc == 10 || argc == 11))
        return check(argc, argv);
    fprintf(stderr, "usage: real_truth seed PHOTO OUT.png NET.png | edit SEED.png NET.png EDITS NAME OUT.png |\n"
                    "       check PHOTO MASK.png OUT.png [OTHER.png] [X Y W H ZOOM]\n");
    return 2;
}
