/* Scanline texture extraction (the layout and the column mapping are in recon_texture.h). */
#include "celadon/recon_texture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "recon/recon.h"

void recon_texture_free(recon_texture_t *t)
{
    free(t->rgb);
    free(t->seen);
    memset(t, 0, sizeof *t);
}

/* Row j (0 = top = rim) of a texture with `rows` rows lies at this height. */
static double row_height(int j, int rows, double H) { return H * (1.0 - (j + 0.5) / rows); }

/* Records, for every texture row that one silhouette crosses, its signed
 * distance s from the axis there (along the right-hand normal), keeping the
 * outermost crossing: the smallest s for the left side (sign -1), the largest
 * for the right one (sign +1). Walks the outline's segments once. */
static void silhouette_on_rows(const vec2 *pts, int n, vec2 origin, vec2 dir, double H, int rows, int sign,
                               double *s_row, unsigned char *hit)
{
    vec2 right = v2(-dir.y, dir.x);
    for (int i = 0; i + 1 < n; i++) {
        vec2 a = v2_sub(pts[i], origin), b = v2_sub(pts[i + 1], origin);
        double ha = v2_dot(a, dir), hb = v2_dot(b, dir), sa = v2_dot(a, right), sb = v2_dot(b, right);
        double lo = fmin(ha, hb), hi = fmax(ha, hb);
        double f0 = ceil(rows * (1.0 - hi / H) - 0.5), f1 = floor(rows * (1.0 - lo / H) - 0.5);
        if (!(f0 <= f1) || f1 < 0.0 || f0 > rows - 1.0)
            continue;
        int j0 = f0 < 0.0 ? 0 : (int)f0, j1 = f1 > rows - 1.0 ? rows - 1 : (int)f1;
        for (int j = j0; j <= j1; j++) {
            double h = row_height(j, rows, H);
            double t = hb != ha ? (h - ha) / (hb - ha) : 0.0;
            double s = sa + t * (sb - sa);
            if (!hit[j] || sign * s > sign * s_row[j])
                s_row[j] = s;
            hit[j] = 1;
        }
    }
}

/* Rows the outline missed (slivers at the base and the rim) take the nearest
 * row that it crossed. Returns 0, or -1 when it crossed none. */
static int fill_missing_rows(double *s_row, const unsigned char *hit, int rows)
{
    int first = -1;
    for (int j = 0; j < rows && first < 0; j++)
        if (hit[j])
            first = j;
    if (first < 0)
        return -1;
    for (int j = 0; j < first; j++)
        s_row[j] = s_row[first];
    int last = first;
    for (int j = first + 1; j < rows; j++) {
        if (hit[j])
            last = j;
        else
            s_row[j] = s_row[last];
    }
    return 0;
}


/* The profile polyline's radius at height h (px), linear between its points. */
static double polyline_radius(const recon_result *res, double h)
{
    const vec2 *p = res->polyline;
    int i = 0;
    while (i + 2 < res->n_polyline && p[i + 1].y < h)
        i++;
    double t = p[i + 1].y > p[i].y ? fmin(fmax((h - p[i].y) / (p[i + 1].y - p[i].y), 0.0), 1.0) : 0.0;
    return p[i].x + t * (p[i + 1].x - p[i].x);
}

int recon_texture_from_photo(const image_t *photo, const recon_result *res, recon_texture_t *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    double H = res->n_polyline > 0 ? res->polyline[res->n_polyline - 1].y : 0.0;
    if (!(H >= 1.0) || !isfinite(H) || H > 1e6) {
        snprintf(err, errlen, "texture: the profile has no height");
        return -1;
    }
    int rows = (int)lround(H);
    double *s_row[2] = {calloc((size_t)rows, sizeof(double)), calloc((size_t)rows, sizeof(double))};
    unsigned char *hit[2] = {calloc((size_t)rows, 1), calloc((size_t)rows, 1)};
    unsigned char *sides = calloc((size_t)rows, 1); /* recon_texture_fill_parts's */
    double *row_y = calloc(3 * (size_t)rows, sizeof *row_y), *body_x = row_y ? row_y + rows : NULL;
    int status = -1;
    if (!s_row[0] || !s_row[1] || !hit[0] || !hit[1] || !sides || !row_y) {
        snprintf(err, errlen, "texture: out of memory");
        goto done;
    }
    int missing[2];
    for (int k = 0; k < 2; k++) {
        silhouette_on_rows(res->silhouette[k], res->n_silhouette[k], res->axis_origin, res->axis_direction, H, rows,
                           k ? 1 : -1, s_row[k], hit[k]);
        missing[k] = fill_missing_rows(s_row[k], hit[k], rows) != 0;
    }
    if (missing[0] && missing[1]) {
        snprintf(err, errlen, "texture: neither silhouette reaches the profile's heights");
        goto done;
    }
    /* Over the rows where a part covers a side (recon_texture_covered_rows:
     * a part left out of the profile, or an outline standing out of the
     * profile) the outline on that side is not the body's: the profile's
     * radius is (taken from the other side, or bridged). */
    vec2 dir = res->axis_direction, right = v2(-dir.y, dir.x);
    for (int j = 0; j < rows && res->n_polyline >= 2; j++) {
        double h = row_height(j, rows, H), r = polyline_radius(res, h);
        vec2 on_axis = v2_add(res->axis_origin, v2_scale(dir, h));
        row_y[j] = on_axis.y;
        body_x[2 * j] = v2_add(on_axis, v2_scale(right, -r)).x;
        body_x[2 * j + 1] = v2_add(on_axis, v2_scale(right, r)).x;
    }
    if (res->n_polyline >= 2)
        recon_texture_covered_rows(res, rows, row_y, body_x, sides);
    for (int j = 0; j < rows; j++)
        for (int k = 0; k < 2; k++)
            if (sides[j] & (1 << k))
                s_row[k][j] = (k ? 1 : -1) * polyline_radius(res, row_height(j, rows, H));
    /* A side washed out over its whole height: the other side's mirror image
     * (the vessel is symmetric about its axis). */
    for (int k = 0; k < 2; k++)
        if (missing[k])
            for (int j = 0; j < rows; j++)
                s_row[k][j] = -s_row[1 - k][j];
    double widest = 0.0;
    for (int j = 0; j < rows; j++)
        widest = fmax(widest, s_row[1][j] - s_row[0][j]);
    if (!(widest >= 1.0) || widest > 1e6) {
        snprintf(err, errlen, "texture: the silhouettes enclose no width");
        goto done;
    }
    out->width = (int)ceil(widest);
    out->height = rows;
    out->rgb = malloc((size_t)out->width * rows * 3);
    double *cos_u = malloc((size_t)out->width * sizeof(double));
    if (!out->rgb || !cos_u) {
        free(cos_u);
        recon_texture_free(out);
        snprintf(err, errlen, "texture: out of memory");
        goto done;
    }
    for (int i = 0; i < out->width; i++)
        cos_u[i] = cos(M_PI * (i + 0.5) / out->width);
    for (int j = 0; j < rows; j++) {
        double c = 0.5 * (s_row[0][j] + s_row[1][j]), a = 0.5 * (s_row[1][j] - s_row[0][j]);
        /* The outermost half pixel is a mix of vessel and background: sample
         * just inside the silhouette instead. */
        a = fmax(0.0, a - fmin(0.5, 0.25 * a));
        vec2 on_axis = v2_add(res->axis_origin, v2_scale(dir, row_height(j, rows, H)));
        uint8_t *px = out->rgb + (size_t)j * out->width * 3;
        for (int i = 0; i < out->width; i++) {
            float rgb[3];
            recon_sample_rgb(photo, v2_add(on_axis, v2_scale(right, c - a * cos_u[i])), rgb);
            for (int k = 0; k < 3; k++)
                px[3 * i + k] = recon_to_u8(rgb[k]);
        }
    }
    free(cos_u);
    if (recon_texture_fill_parts(out, sides) != 0) {
        recon_texture_free(out);
        snprintf(err, errlen, "texture: out of memory");
        goto done;
    }
    status = 0;
done:
    free(sides);
    free(row_y);
    for (int k = 0; k < 2; k++) {
        free(s_row[k]);
        free(hit[k]);
    }
    return status;
}
