/* Whether a mask can be the silhouette of a surface of revolution standing
 * on its base (docs/algorithms-recon.md, "Not a vessel").
 *
 * Every cross-section of a solid of revolution is a disc centred on the
 * axis; its image, through any pinhole or parallel camera, is a filled
 * ellipse around the image of its centre, which lies on the imaged axis, and
 * (the configuration being symmetric about the plane through the camera and
 * the axis) symmetric about that axis. The silhouette is their union. So,
 * whatever the elevation, the focal length or the roll:
 *  - every line across the silhouette perpendicular to the imaged axis meets
 *    it in an interval that contains the axis: the backdrop never lies on
 *    the axis between object on both sides;
 *  - its lowest part, the near half of the base's ellipse, is symmetric
 *    about the axis.
 * A star, a person or a chair seen from the front have backdrop on the
 * axis between their legs; two vessels side by side have it between them
 * above and below where they touch; an L shape, or a vessel with a second
 * one beside it, stand on a base that reaches much farther on one side. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "recon/recon_internal.h"

/* The lowest band of the silhouette whose symmetry is measured, as a
 * fraction of its height along the axis: deep enough to hold more than the
 * tip of a thin base ellipse, shallow enough to stay below a low spout. */
#define BASE_BAND 0.03

/* The object's box (inclusive) and its extent along the axis; 0 when the
 * mask is empty. */
static int object_extent(const uint8_t *mask, int w, int h, vec2 origin, vec2 dir, int box[4], double *h_lo,
                         double *h_hi)
{
    if (!recon_mask_box(mask, w, h, box))
        return 0;
    *h_lo = INFINITY;
    *h_hi = -INFINITY;
    for (int y = box[1]; y <= box[3]; y++)
        for (int x = box[0]; x <= box[2]; x++)
            if (mask[(size_t)y * w + x]) {
                double hh = v2_dot(v2_sub(v2(x + 0.5, y + 0.5), origin), dir);
                *h_lo = fmin(*h_lo, hh);
                *h_hi = fmax(*h_hi, hh);
            }
    return 1;
}

double recon_base_asymmetry(const uint8_t *mask, int w, int h, vec2 origin, vec2 dir)
{
    int box[4];
    double h_lo, h_hi;
    if (!object_extent(mask, w, h, origin, dir, box, &h_lo, &h_hi))
        return 0;
    vec2 nrm = v2(-dir.y, dir.x);
    double height = h_hi - h_lo + 1, band = h_lo + fmax(BASE_BAND * height, 2.0);
    double s_lo = 0, s_hi = 0;
    for (int y = box[1]; y <= box[3]; y++)
        for (int x = box[0]; x <= box[2]; x++)
            if (mask[(size_t)y * w + x]) {
                vec2 d = v2_sub(v2(x + 0.5, y + 0.5), origin);
                if (v2_dot(d, dir) < band) {
                    double s = v2_dot(d, nrm);
                    s_lo = fmin(s_lo, s - 0.5);
                    s_hi = fmax(s_hi, s + 0.5);
                }
            }
    return fabs(s_hi + s_lo) / height;
}

int recon_axis_gap(const uint8_t *mask, int w, int h, vec2 origin, vec2 dir, double *axis_gap)
{
    *axis_gap = 0;
    int box[4];
    double h_lo, h_hi;
    if (!object_extent(mask, w, h, origin, dir, box, &h_lo, &h_hi))
        return 0;
    /* The backdrop outside the object (its component reaches the border of
     * the object's box grown by a pixel; holes enclosed by the object, a
     * handle's window, are not outside). */
    int x0 = box[0] > 0 ? box[0] - 1 : 0, y0 = box[1] > 0 ? box[1] - 1 : 0;
    int x1 = box[2] + 1 < w ? box[2] + 1 : w - 1, y1 = box[3] + 1 < h ? box[3] + 1 : h - 1;
    const int bw = x1 - x0 + 1, bh = y1 - y0 + 1;
    uint8_t *inv = malloc((size_t)bw * bh);
    int *lab = malloc((size_t)bw * bh * sizeof *lab);
    long *area = NULL;
    uint8_t *outside = NULL;
    int n = -1;
    if (inv && lab) {
        for (int y = 0; y < bh; y++)
            for (int x = 0; x < bw; x++)
                inv[(size_t)y * bw + x] = !mask[(size_t)(y0 + y) * w + x0 + x];
        n = recon_mask_label(inv, bw, bh, lab, &area);
    }
    if (n >= 0)
        outside = calloc((size_t)n + 1, 1);
    if (!outside) {
        free(inv);
        free(lab);
        free(area);
        return -1;
    }
    for (int x = 0; x < bw; x++)
        outside[lab[x]] = outside[lab[(size_t)(bh - 1) * bw + x]] = 1;
    for (int y = 0; y < bh; y++)
        outside[lab[(size_t)y * bw]] = outside[lab[(size_t)y * bw + bw - 1]] = 1;
    outside[0] = 0; /* label 0: the object */

    /* Rows from the first one whose axis pixel is object down to the
     * object's last: above it, object on both sides of the axis may be two
     * handles rising over the rim. A row counts when its axis pixel is
     * outside backdrop with object on both sides of it. */
    int first = -1, gap_rows = 0;
    for (int y = 0; y < bh; y++) {
        int c = (int)floor(origin.x + (y0 + y + 0.5 - origin.y) * dir.x / dir.y) - x0;
        if (c < 0 || c >= bw)
            continue;
        const uint8_t *m = mask + (size_t)(y0 + y) * w + x0;
        if (first < 0) {
            if (m[c])
                first = y;
            continue;
        }
        if (m[c] || !outside[lab[(size_t)y * bw + c]])
            continue;
        gap_rows += memchr(m, 1, (size_t)c) && memchr(m + c, 1, (size_t)(bw - c));
    }
    *axis_gap = gap_rows / (h_hi - h_lo + 1);
    free(outside);
    free(inv);
    free(lab);
    free(area);
    return 0;
}
