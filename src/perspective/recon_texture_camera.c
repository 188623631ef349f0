/* The texture by the camera (recon_texture_from_camera in recon_camera.h):
 * each texel (phi, v) is looked up where the camera images the wall point
 * of the meridian at height v and angle phi. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/recon_camera.h"
#include "recon/recon.h"

/* Meridian samples per texture row when inverting h(u). */
enum { SAMPLES_PER_ROW = 4 };

/* The meridian's radius and slope dr/dh at each row's height (rows from
 * the rim down), from a dense table of the curve, h(u) taken as increasing
 * (the first crossing otherwise). */
static int radius_by_row(const recon_meridian *mer, int rows, double *r, double *slope)
{
    const bspline_t *c = &mer->curve;
    int n = SAMPLES_PER_ROW * rows + 1;
    vec2 *d = malloc(2 * (size_t)n * sizeof *d);
    if (!d)
        return -1;
    double u0 = c->knots[0], u1 = c->knots[c->n_ctrl + c->degree];
    for (int i = 0; i < n; i++)
        bspline_eval_derivs(c, u0 + (u1 - u0) * i / (n - 1), 1, d + 2 * i);
    int i = 0;
    for (int j = rows - 1; j >= 0; j--) { /* increasing height */
        double h = 1.0 - (j + 0.5) / rows;
        while (i + 1 < n - 1 && d[2 * (i + 1)].y < h)
            i++;
        vec2 a = d[2 * i], b = d[2 * (i + 1)], da = d[2 * i + 1];
        double t = b.y > a.y ? fmin(fmax((h - a.y) / (b.y - a.y), 0), 1) : 0;
        r[j] = a.x + t * (b.x - a.x);
        slope[j] = fabs(da.y) > 1e-12 ? da.x / da.y : 0;
    }
    free(d);
    return 0;
}

/* Unseen texels of a row take the nearest seen texel's colour; returns the
 * number seen. */
static int fill_row(uint8_t *rgb, const uint8_t *seen, int w)
{
    int last = -1, count = 0;
    for (int i = 0; i < w; i++) {
        if (!seen[i])
            continue;
        for (int k = last + 1; k < i; k++) { /* the gap (last, i): nearer end */
            int from = last < 0 || i - k < k - last ? i : last;
            memcpy(rgb + 3 * k, rgb + 3 * from, 3);
        }
        last = i;
        count++;
    }
    for (int k = last + 1; last >= 0 && k < w; k++)
        memcpy(rgb + 3 * k, rgb + 3 * last, 3);
    return count;
}

int recon_texture_from_camera(const image_t *photo, const recon_camera *cam, const recon_meridian *mer,
                              const recon_result *parts,
                              recon_texture_t *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    double H = mer->height_px, rmax = 0;
    for (int i = 0; i < mer->n_points; i++)
        rmax = fmax(rmax, mer->points[i].x);
    if (!(H >= 1.0) || H > 1e6 || !(rmax * H >= 0.5) || rmax * H > 1e6) {
        snprintf(err, errlen, "texture: the meridian has no size");
        return -1;
    }
    int rows = (int)lround(H), cols = (int)ceil(2 * rmax * H);
    out->rgb = malloc((size_t)rows * cols * 3);
    out->seen = malloc((size_t)rows * cols);
    /* r, slope, row_y (each row's image row) and body_x (its outline's x on either side) */
    double *r = malloc(5 * (size_t)rows * sizeof *r);
    double *slope = r ? r + rows : NULL, *row_y = r ? r + 2 * rows : NULL, *body_x = r ? r + 3 * rows : NULL;
    int *seen_rows = malloc((size_t)rows * sizeof *seen_rows);
    if (!out->rgb || !out->seen || !r || !seen_rows || radius_by_row(mer, rows, r, slope) != 0) {
        free(r);
        free(seen_rows);
        recon_texture_free(out);
        snprintf(err, errlen, "texture: out of memory");
        return -1;
    }
    out->width = cols;
    out->height = rows;
    for (int j = 0; j < rows; j++) {
        double h = 1.0 - (j + 0.5) / rows;
        /* Within half a pixel of the outline a texel at angle d from the
         * outline's generator lies about r d^2 / 2 px inside it, and the
         * normal turns from the view by about d: cos >= 1/sqrt(r px). */
        double min_cos = 1 / sqrt(fmax(r[j] * H, 1.0));
        uint8_t *px = out->rgb + (size_t)j * cols * 3, *seen = out->seen + (size_t)j * cols;
        for (int i = 0; i < cols; i++) {
            double phi = M_PI * (1 - (i + 0.5) / cols);
            float rgb[3];
            recon_sample_rgb(photo, recon_camera_project(cam, mer, r[j], h, phi), rgb);
            for (int k = 0; k < 3; k++)
                px[3 * i + k] = recon_to_u8(rgb[k]);
            seen[i] = (uint8_t)recon_camera_sees(cam, mer, r[j], h, phi, slope[j], min_cos);
        }
        vec2 left = recon_camera_project(cam, mer, r[j], h, M_PI), right = recon_camera_project(cam, mer, r[j], h, 0);
        row_y[j] = 0.5 * (left.y + right.y);
        body_x[2 * j] = left.x, body_x[2 * j + 1] = right.x;
        seen_rows[j] = fill_row(px, seen, cols);
    }
    /* Rows the camera did not see at all (an underside): the nearest row
     * that it saw. */
    for (int j = 0; j < rows; j++) {
        if (seen_rows[j])
            continue;
        int best = -1;
        for (int k = 0; k < rows; k++)
            if (seen_rows[k] && (best < 0 || abs(k - j) < abs(best - j)))
                best = k;
        if (best >= 0)
            memcpy(out->rgb + (size_t)j * cols * 3, out->rgb + (size_t)best * cols * 3, (size_t)cols * 3);
    }
    unsigned char *sides = parts ? malloc((size_t)rows) : NULL;
    int rc = 0;
    if (parts) {
        if (sides)
            recon_texture_covered_rows(parts, rows, row_y, body_x, sides);
        if (!sides || recon_texture_fill_parts(out, sides) != 0) {
            recon_texture_free(out);
            snprintf(err, errlen, "texture: out of memory");
            rc = -1;
        }
    }
    free(sides);
    free(r);
    free(seen_rows);
    return rc;
}
