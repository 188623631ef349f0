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
            y < p->row0 - RECON_TEXTURE_PART_MARGIN_PX || y > p->row1 + RECON_TEXTURE_PART_MARGIN_PX)
            continue;
        sides |= p->side < 0 ? 1 : p->side > 0 ? 2 : 3;
    }
    return sides;
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
            int other = 3 - bit;
            /* The first texel inward of the band (the body's, nearer the front). */
            int inner = 0;
            while (inner < w && in_band(bit == 1 ? inner : w - 1 - inner, w, bit))
                inner++;
            inner = bit == 1 ? inner : w - 1 - inner;
            if (inner < 0 || inner >= w)
                continue;
            for (int i = 0; i < w; i++) {
                if (!in_band(i, w, bit))
                    continue;
                uint8_t *px = t->rgb + ((size_t)j * w + i) * 3;
                /* The body's mirror texel, as the photo shows it; with a part
                 * on both sides, the body's texel next to the band. */
                int from = !(sides[j] & other) ? w - 1 - i : inner;
                memcpy(px, orig + ((size_t)j * w + from) * 3, 3);
            }
        }
    }
    free(orig);
    return 0;
}
