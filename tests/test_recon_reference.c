/* The optimised image stages against straightforward references on random
 * inputs: the word-skipping Suzuki–Abe border following against a per-pixel
 * implementation of the paper's algorithm with an int label image (same
 * borders, points, order and hierarchy), the run-based mask cleaning against
 * flood fills, and the gray conversion against the per-pixel formula. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "recon/recon_internal.h"

static uint64_t rng_state;
static double rnd(void)
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (rng_state >> 11) * (1.0 / 9007199254740992.0);
}

static inline int clampi(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

/* Sizes around the vector and word widths and the 7-row ring. */
static const int SIZES[][2] = {{1, 1}, {2, 9}, {5, 3}, {7, 7}, {8, 8}, {9, 6}, {17, 17}, {33, 20}, {64, 41}, {101, 77}};
enum { N_SIZES = sizeof SIZES / sizeof SIZES[0] };

/* ---- Suzuki–Abe: the per-pixel algorithm with an int label image f (the
 * paper's), on the image with a one-pixel frame of zeros. */

static const int RDX[8] = {1, 1, 0, -1, -1, -1, 0, 1};
static const int RDY[8] = {0, -1, -1, -1, 0, 1, 1, 1};

static int ref_dir(int dx, int dy)
{
    for (int k = 0; k < 8; k++)
        if (RDX[k] == dx && RDY[k] == dy)
            return k;
    return -1;
}

typedef struct {
    int pts[2 * 100000], n;
    recon_border b[20000];
    int nb;
} ref_set;

static void ref_follow(int *f, int W, int x, int y, int x2, int y2, int nbd, ref_set *s)
{
    int d0 = ref_dir(x2 - x, y2 - y), d1 = -1;
    for (int k = 0; k < 8 && d1 < 0; k++) {
        int d = (d0 - k + 8) & 7;
        if (f[(y + RDY[d]) * W + x + RDX[d]])
            d1 = d;
    }
    cr_assert_lt(s->n, 100000);
    s->pts[2 * s->n] = x - 1;
    s->pts[2 * s->n++ + 1] = y - 1;
    if (d1 < 0) {
        f[y * W + x] = -nbd;
        return;
    }
    int x1 = x + RDX[d1], y1 = y + RDY[d1], x3 = x, y3 = y, dp = d1;
    for (;;) {
        int d4 = -1, east_zero = 0;
        for (int k = 1; k <= 8 && d4 < 0; k++) {
            int d = (dp + k) & 7;
            if (f[(y3 + RDY[d]) * W + x3 + RDX[d]])
                d4 = d;
            else if (d == 0)
                east_zero = 1;
        }
        if (east_zero)
            f[y3 * W + x3] = -nbd;
        else if (f[y3 * W + x3] == 1)
            f[y3 * W + x3] = nbd;
        int x4 = x3 + RDX[d4], y4 = y3 + RDY[d4];
        if (x4 == x && y4 == y && x3 == x1 && y3 == y1)
            return;
        cr_assert_lt(s->n, 100000);
        s->pts[2 * s->n] = x4 - 1;
        s->pts[2 * s->n++ + 1] = y4 - 1;
        dp = ref_dir(x3 - x4, y3 - y4);
        x3 = x4;
        y3 = y4;
    }
}

static void ref_border_follow(const uint8_t *m, int w, int h, ref_set *s)
{
    const int W = w + 2, H = h + 2;
    int *f = calloc((size_t)W * H, sizeof *f), nbd = 1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            f[(y + 1) * W + x + 1] = m[y * w + x] != 0;
    s->n = s->nb = 0;
    for (int y = 1; y < H - 1; y++) {
        int lnbd = 1;
        for (int x = 1; x < W - 1; x++) {
            int *p = f + y * W + x, hole = -1;
            if (*p == 0)
                continue;
            if (*p == 1 && p[-1] == 0)
                hole = 0;
            else if (*p >= 1 && p[1] == 0) {
                hole = 1;
                if (*p > 1)
                    lnbd = *p;
            }
            if (hole >= 0) {
                nbd++;
                int parent = -1;
                if (lnbd >= 2)
                    parent = s->b[lnbd - 2].is_hole == hole ? s->b[lnbd - 2].parent : lnbd - 2;
                cr_assert_lt(s->nb, 20000);
                recon_border *b = &s->b[s->nb++];
                *b = (recon_border){s->n, 0, hole, parent};
                ref_follow(f, W, x, y, hole ? x + 1 : x - 1, y, nbd, s);
                b->count = s->n - b->start;
            }
            if (*p != 1)
                lnbd = abs(*p);
        }
    }
    free(f);
}

/* Random masks: unions of discs with holes and islands in the holes (the
 * nesting), or salt and pepper (many tiny borders, isolated pixels). */
static void random_mask(uint8_t *m, int w, int h, int kind)
{
    if (kind == 0) {
        memset(m, 0, (size_t)w * h);
        for (int layer = 0; layer < 3; layer++)
            for (int c = 0; c < 4; c++) {
                double cx = rnd() * w, cy = rnd() * h, r = (0.5 + rnd()) * (w < h ? w : h) / (3.0 + 3 * layer);
                for (int y = 0; y < h; y++)
                    for (int x = 0; x < w; x++)
                        if ((x - cx) * (x - cx) + (y - cy) * (y - cy) < r * r)
                            m[y * w + x] = layer != 1;
            }
    } else {
        double p = 0.25 * kind;
        for (int i = 0; i < w * h; i++)
            m[i] = rnd() < p;
    }
}

Test(recon_reference, border_follow_equals_per_pixel_algorithm)
{
    rng_state = 3;
    static ref_set ref;
    for (int s = 0; s < N_SIZES; s++)
        for (int kind = 0; kind < 4; kind++)
            for (int rep = 0; rep < 3; rep++) {
                const int w = SIZES[s][0], h = SIZES[s][1];
                uint8_t *m = malloc((size_t)w * h);
                random_mask(m, w, h, kind);
                ref_border_follow(m, w, h, &ref);
                recon_border_set bs;
                cr_assert_eq(recon_border_follow(m, w, h, &bs), 0);
                cr_assert_eq(bs.n_borders, ref.nb, "%dx%d kind %d: %d borders, reference %d", w, h, kind,
                             bs.n_borders, ref.nb);
                cr_assert_eq(bs.n_points, ref.n);
                for (int b = 0; b < ref.nb; b++) {
                    cr_assert_eq(bs.borders[b].start, ref.b[b].start);
                    cr_assert_eq(bs.borders[b].count, ref.b[b].count);
                    cr_assert_eq(bs.borders[b].is_hole, ref.b[b].is_hole);
                    cr_assert_eq(bs.borders[b].parent, ref.b[b].parent, "%dx%d kind %d border %d", w, h, kind, b);
                }
                if (ref.n > 0) /* an empty mask has no point array */
                    cr_assert_arr_eq(bs.points, ref.pts, 2 * (size_t)ref.n * sizeof(int));
                recon_border_set_free(&bs);
                free(m);
            }
}

/* ---- mask cleaning against flood fills */

/* Labels the components of pixels equal to v (8- or 4-connected) in raster
 * order of their first pixel: lab[i] = 1, 2, ... or 0; returns the count. */
static int flood_labels(const uint8_t *m, int w, int h, uint8_t v, int conn8, int *lab, int *stack)
{
    int n = 0;
    memset(lab, 0, (size_t)w * h * sizeof *lab);
    for (int s = 0; s < w * h; s++) {
        if (m[s] != v || lab[s])
            continue;
        int top = 0;
        lab[s] = ++n;
        stack[top++] = s;
        while (top) {
            int p = stack[--top], x = p % w, y = p / w;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int u = x + dx, q = (y + dy) * w + u;
                    if ((!conn8 && dx && dy) || u < 0 || u >= w || y + dy < 0 || y + dy >= h || m[q] != v || lab[q])
                        continue;
                    lab[q] = n;
                    stack[top++] = q;
                }
        }
    }
    return n;
}

Test(recon_reference, mask_clean_equals_flood_fills)
{
    rng_state = 4;
    for (int s = 0; s < N_SIZES; s++)
        for (int kind = 0; kind < 4; kind++)
            for (int rep = 0; rep < 3; rep++) {
                const int w = SIZES[s][0], h = SIZES[s][1];
                uint8_t *m = malloc((size_t)w * h), *ref = malloc((size_t)w * h);
                int *lab = malloc((size_t)w * h * sizeof *lab), *stack = malloc((size_t)w * h * 9 * sizeof *stack);
                random_mask(m, w, h, kind);
                /* Largest 8-connected object (ties: the first in raster order). */
                int n = flood_labels(m, w, h, 1, 1, lab, stack), best = 0;
                long *area = calloc((size_t)n + 1, sizeof *area);
                for (int i = 0; i < w * h; i++)
                    area[lab[i]] += lab[i] > 0;
                for (int k = 1; k <= n; k++)
                    if (!best || area[k] > area[best])
                        best = k;
                for (int i = 0; i < w * h; i++)
                    ref[i] = best && lab[i] == best;
                /* Holes: 4-connected background components off the border. */
                int nh = flood_labels(ref, w, h, 0, 0, lab, stack), holes = 0;
                uint8_t *border = calloc((size_t)nh + 1, 1);
                for (int y = 0; y < h; y++)
                    for (int x = 0; x < w; x++)
                        if (x == 0 || y == 0 || x == w - 1 || y == h - 1)
                            border[lab[y * w + x]] = 1;
                for (int k = 1; k <= nh; k++)
                    holes += !border[k];
                for (int i = 0; i < w * h; i++)
                    if (lab[i] && !border[lab[i]])
                        ref[i] = 1;
                /* Rows filled between their outermost object pixels. */
                long kept = 0;
                for (int y = 0; y < h; y++) {
                    int a = -1, b = -1;
                    for (int x = 0; x < w; x++)
                        if (ref[y * w + x]) {
                            a = a < 0 ? x : a;
                            b = x;
                        }
                    for (int x = a; a >= 0 && x <= b; x++)
                        ref[y * w + x] = 1;
                    kept += a >= 0 ? b - a + 1 : 0;
                }
                int dropped, filled;
                long got = recon_mask_clean(m, w, h, &dropped, &filled);
                cr_assert_eq(got, kept, "%dx%d kind %d: kept %ld, reference %ld", w, h, kind, got, kept);
                cr_assert_eq(dropped, n > 0 ? n - 1 : 0);
                cr_assert_eq(filled, holes);
                cr_assert_arr_eq(m, ref, (size_t)w * h);
                free(border);
                free(area);
                free(m);
                free(ref);
                free(lab);
                free(stack);
            }
}

/* ---- gray conversion */

Test(recon_reference, gray_is_the_per_pixel_formula)
{
    rng_state = 6;
    const int w = 37, h = 23;
    for (int c = 1; c <= 5; c++) {
        image_t img = image_alloc(w, h, c);
        for (int i = 0; i < w * h * c; i++)
            img.data[i] = (float)(1.2 * rnd() - 0.1); /* out of [0, 1] too */
        img.data[5] = NAN;
        float *gray = malloc((size_t)w * h * sizeof *gray);
        uint8_t *mask = malloc((size_t)w * h);
        int used;
        recon_mask_mode mode = recon_mask_threshold(&img, 128, gray, mask, &used);
        cr_assert_eq(used, 128);
        for (int i = 0; i < w * h; i++) {
            const float *p = img.data + (size_t)i * c;
            float g = c >= 3 ? 0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2] : p[0];
            g = g > 0 ? (g < 1 ? g : 1) : 0;
            cr_assert_eq(gray[i], g, "c %d pixel %d", c, i);
            int obj = mode == RECON_MASK_GRAY_BELOW ? g < 128 / 255.0f : g > 128 / 255.0f;
            cr_assert_eq(mask[i], obj);
        }
        free(gray);
        free(mask);
        image_free(&img);
    }
}
