/* What the parts left out of the profile cover in the texture, filled from
 * the body (recon_texture_fill_parts in recon_texture.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/recon_texture.h"

int recon_texture_parts_at(const recon_result *res, double y)
{
    int sides = 0;
    for (int i = 0; i < res->n_excluded; i++) {
        const recon_excluded *p = &res->excluded[i];
        if ((p->what != RECON_PART_HANDLE && p->what != RECON_PART_ASYMMETRY) ||
            y < p->row0 - RECON_TEXTURE_PART_MARGIN_ROWS || y > p->row1 + RECON_TEXTURE_PART_MARGIN_ROWS)
            continue;
        sides |= p->side < 0 ? 1 : p->side > 0 ? 2 : 3;
    }
    return sides;
}

/* The outermost x (the least on the left, k = 0; the greatest on the
 * right) of side k's outline over image row y (y +/- 0.5), its points
 * joined by segments (a jump between two rows is a segment across the rows
 * between), or NAN where it does not reach the row. The outline's points
 * run top to bottom. */
static double outline_x(const recon_result *res, int k, double y)
{
    const vec2 *p = res->silhouette[k];
    int n = res->n_silhouette[k], lo = 0, hi = n - 1;
    if (n < 1)
        return NAN;
    while (lo < hi) { /* the first point at or below y - 0.5 */
        int mid = (lo + hi) / 2;
        if (p[mid].y < y - 0.5)
            lo = mid + 1;
        else
            hi = mid;
    }
    double best = NAN;
    for (int i = lo > 0 ? lo - 1 : 0; i < n && (i == 0 || p[i - 1].y <= y + 0.5); i++) {
        vec2 a = p[i], b = i + 1 < n ? p[i + 1] : p[i];
        double y0 = fmax(fmin(a.y, b.y), y - 0.5), y1 = fmin(fmax(a.y, b.y), y + 0.5);
        if (y0 > y1)
            continue;
        for (int e = 0; e < 2; e++) {
            double yy = e ? y1 : y0, t = b.y != a.y ? (yy - a.y) / (b.y - a.y) : 0.0;
            double x = a.x + t * (b.x - a.x);
            if (isnan(best) || (k ? x > best : x < best))
                best = x;
        }
    }
    return best;
}

void recon_texture_covered_rows(const recon_result *res, int rows, const double *row_y, const double *body_x,
                                unsigned char *sides)
{
    memset(sides, 0, (size_t)rows);
    for (int j = 0; j < rows; j++) {
        sides[j] |= (unsigned char)recon_texture_parts_at(res, row_y[j]);
        double half = 0.5 * fabs(body_x[2 * j + 1] - body_x[2 * j]);
        double tol = fmax(RECON_TEXTURE_PART_DEPARTURE_PX, RECON_TEXTURE_PART_DEPARTURE * half);
        for (int k = 0; k < 2; k++) {
            double x = outline_x(res, k, row_y[j]), out = k ? x - body_x[2 * j + 1] : body_x[2 * j] - x;
            if (!(out > tol))
                continue;
            for (int d = -RECON_TEXTURE_PART_MARGIN_ROWS; d <= RECON_TEXTURE_PART_MARGIN_ROWS; d++)
                if (j + d >= 0 && j + d < rows)
                    sides[j + d] |= (unsigned char)(1 << k);
        }
    }
}

/* Texel i of a row lies at angle pi (1 - u) from the right outline, u =
 * (i + 0.5) / w: in side k's band when it is turned more than the band's
 * angle from the front (u = 1/2) toward that side. */
static int in_band(int i, int w, int side_bit)
{
    double u = (i + 0.5) / w, edge = 0.5 - RECON_TEXTURE_PART_BAND_DEG / 180.0;
    return side_bit == 1 ? u < edge : u > 1.0 - edge;
}

int recon_texture_fill_parts(recon_texture_t *t, const unsigned char *sides)
{
    int w = t->width, rows = t->height;
    uint8_t *orig = malloc((size_t)w * rows * 3);
    if (!orig)
        return -1;
    memcpy(orig, t->rgb, (size_t)w * rows * 3);
    for (int bit = 1; bit <= 2; bit <<= 1) {
        for (int j = 0; j < rows; j++) {
            if (!(sides[j] & bit))
                continue;
            int other = 3 - bit, above = j, below = j;
            while (above >= 0 && (sides[above] & bit))
                above--;
            while (below < rows && (sides[below] & bit))
                below++;
            if (above < 0 && below >= rows && (sides[j] & other))
                continue; /* parts on both sides over every row: nothing to fill from */
            /* Weight of the row below: 0 at the row above, 1 at the row below. */
            double f = above < 0 ? 1.0 : below >= rows ? 0.0 : (double)(j - above) / (below - above);
            for (int i = 0; i < w; i++) {
                if (!in_band(i, w, bit))
                    continue;
                uint8_t *px = t->rgb + ((size_t)j * w + i) * 3;
                if (!(sides[j] & other)) { /* the body's mirror texel, as the photo shows it */
                    memcpy(px, orig + ((size_t)j * w + (w - 1 - i)) * 3, 3);
                    continue;
                }
                const uint8_t *a = orig + ((size_t)(above < 0 ? below : above) * w + i) * 3;
                const uint8_t *b = orig + ((size_t)(below >= rows ? above : below) * w + i) * 3;
                for (int k = 0; k < 3; k++)
                    px[k] = (uint8_t)lround((1.0 - f) * a[k] + f * b[k]);
            }
        }
    }
    free(orig);
    return 0;
}
