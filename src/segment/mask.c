/* The gray signal and the masks that need no segmentation (alpha, a forced
 * gray threshold), and the cleaning of masks: components, holes, morphology. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "segment/segment.h"
#include "core/core.h"

/* Clamps a signal value to [0, 1]; NaN (HDR or broken files) becomes 0. */
static inline float finite01(float v) { return v > 0 ? (v < 1 ? v : 1) : 0; }

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* Gray (Rec.601 luminance of the encoded values, or the first channel) of
 * the n pixels px (c channels each) into g. Constant strides for the common
 * layouts, so that the loops vectorise. */
RECON_VECTOR_CLONES static void gray_row(const float *restrict px, int c, int n, float *restrict g)
{
    if (c == 3) {
#pragma omp simd
        for (int i = 0; i < n; i++)
            g[i] = finite01(0.299f * px[3 * i] + 0.587f * px[3 * i + 1] + 0.114f * px[3 * i + 2]);
    } else if (c == 4) {
#pragma omp simd
        for (int i = 0; i < n; i++)
            g[i] = finite01(0.299f * px[4 * i] + 0.587f * px[4 * i + 1] + 0.114f * px[4 * i + 2]);
    } else {
        for (int i = 0; i < n; i++) {
            const float *p = px + (size_t)i * c;
            g[i] = finite01(c >= 3 ? 0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2] : p[0]);
        }
    }
}

RECON_VECTOR_CLONES recon_mask_mode recon_mask_threshold(const image_t *img, int threshold, float *gray,
                                                         uint8_t *mask, int *threshold_used)
{
    const int w = img->width, h = img->height, c = img->channels;
    const size_t n = (size_t)w * h, row = (size_t)w * c;
    const float *px = img->data;
    *threshold_used = -1;

    /* Alpha is the mask when most of the border is transparent. */
    if (img->has_alpha && c >= 2) {
        long clear = 0, total = 0;
        for (int i = 0; i < w; i++, total += 2)
            clear += (px[(size_t)i * c + c - 1] < 0.5f) + (px[((size_t)(h - 1) * w + i) * c + c - 1] < 0.5f);
        for (int j = 0; j < h; j++, total += 2)
            clear += (px[(size_t)j * w * c + c - 1] < 0.5f) + (px[((size_t)j * w + w - 1) * c + c - 1] < 0.5f);
        if (2 * clear > total) {
            for (size_t i = 0; i < n; i++) {
                gray[i] = finite01(px[i * c + c - 1]);
                mask[i] = gray[i] >= 0.5f;
            }
            return RECON_MASK_ALPHA;
        }
    }
    /* A colour photo's outline is measured on its colours (extract.c): the
     * segmentation needs no gray, and skipping it spares a pass over the
     * photo and the pages of a W*H float buffer. */
    if (threshold < 0 && c >= 3)
        return RECON_MASK_GRAPH_CUT;
    for (int j = 0; j < h; j++)
        gray_row(px + (size_t)j * row, c, w, gray + (size_t)j * w);
    if (threshold < 0)
        return RECON_MASK_GRAPH_CUT;

    /* Forced: the polarity from the border's median gray against the threshold. */
    float *b = malloc(((size_t)2 * w + 2 * h) * sizeof *b);
    float med = gray[0];
    if (b) {
        size_t k = 0;
        for (int i = 0; i < w; i++) {
            b[k++] = gray[i];
            b[k++] = gray[(size_t)(h - 1) * w + i];
        }
        for (int j = 0; j < h; j++) {
            b[k++] = gray[(size_t)j * w];
            b[k++] = gray[(size_t)j * w + w - 1];
        }
        qsort(b, k, sizeof *b, cmp_float);
        med = b[k / 2];
        free(b);
    }
    float t = threshold / 255.0f;
    int below = med > t;
#pragma omp simd
    for (size_t i = 0; i < n; i++)
        mask[i] = below ? gray[i] < t : gray[i] > t;
    *threshold_used = threshold;
    return below ? RECON_MASK_GRAY_BELOW : RECON_MASK_GRAY_ABOVE;
}

/* ---- closing and opening of a row-convex mask */

/* Row intervals [lo, hi] of the mask (lo = -1: empty row). */
static void row_extents(const uint8_t *mask, int w, int h, int *lo, int *hi)
{
    for (int j = 0; j < h; j++) {
        const uint8_t *m = mask + (size_t)j * w, *p = memchr(m, 1, (size_t)w);
        lo[j] = p ? (int)(p - m) : -1;
        hi[j] = p ? (int)((const uint8_t *)memrchr(m, 1, (size_t)w) - m) : -1;
    }
}

/* One square (2r+1) dilation (grow = 1) or erosion (grow = 0) of a set given
 * by row intervals, from (lo, hi) into (nlo, nhi). For dilation the union of
 * the neighbour rows' intervals is taken as its hull (the mask is row-filled
 * anyway); erosion keeps a row only where all rows around it in the image are
 * occupied (rows beyond the image do not count). */
static void interval_step(const int *lo, const int *hi, int *nlo, int *nhi, int w, int h, int r, int grow)
{
    for (int j = 0; j < h; j++) {
        int a = grow ? w : -1, b = grow ? -1 : w, ok = 1;
        for (int k = j - r < 0 ? 0 : j - r; k <= j + r && k < h; k++) {
            int empty = lo[k] < 0;
            if (grow) {
                if (!empty) {
                    a = lo[k] < a ? lo[k] : a;
                    b = hi[k] > b ? hi[k] : b;
                }
            } else if (empty) {
                ok = 0;
            } else {
                a = lo[k] > a ? lo[k] : a;
                b = hi[k] < b ? hi[k] : b;
            }
        }
        if (grow && b >= 0) {
            a = a - r < 0 ? 0 : a - r;
            b = b + r >= w ? w - 1 : b + r;
        } else if (!grow) {
            a += r;
            b -= r;
        }
        int valid = grow ? b >= 0 : (ok && a <= b);
        nlo[j] = valid ? a : -1;
        nhi[j] = valid ? b : -1;
    }
}

static int morph(uint8_t *mask, int w, int h, int r, int close)
{
    int *lo = calloc((size_t)4 * h, sizeof *lo);
    if (!lo)
        return -1;
    int *hi = lo + h, *tlo = hi + h, *thi = tlo + h;
    row_extents(mask, w, h, lo, hi);
    interval_step(lo, hi, tlo, thi, w, h, r, close);
    interval_step(tlo, thi, lo, hi, w, h, r, !close);
    for (int j = 0; j < h; j++) {
        uint8_t *m = mask + (size_t)j * w;
        memset(m, 0, (size_t)w);
        if (lo[j] >= 0)
            memset(m + lo[j], 1, (size_t)(hi[j] - lo[j] + 1));
    }
    free(lo);
    return 0;
}

int recon_mask_close(uint8_t *mask, int w, int h, int r) { return morph(mask, w, h, r, 1); }

int recon_mask_open(uint8_t *mask, int w, int h, int r) { return morph(mask, w, h, r, 0); }

/* ---- connected components over runs */

typedef struct {
    int row, x0, x1; /* [x0, x1) */
    int label;
} run_t;

static int uf_find(int *parent, int a)
{
    while (parent[a] != a) {
        parent[a] = parent[parent[a]];
        a = parent[a];
    }
    return a;
}

/* End of the run of value v (0 or 1) that starts at p, in a row of 0/1
 * bytes ending at end: the next byte of the other value (memchr scans a word
 * or more at a time), or end. */
static const uint8_t *run_end(const uint8_t *p, const uint8_t *end, uint8_t v)
{
    const uint8_t *q = memchr(p, !v, (size_t)(end - p));
    return q ? q : end;
}

/* Labels the runs of pixels equal to value; conn8 selects 8- or 4-connectivity.
 * Returns the number of runs (runs and parent sized for the worst case). */
static int label_runs(const uint8_t *mask, int w, int h, uint8_t value, int conn8, run_t *runs, int *parent)
{
    int nr = 0, prev0 = 0, prev1 = 0;
    const int e = conn8; /* the previous row's runs widened by one for 8-conn */
    for (int j = 0; j < h; j++) {
        const uint8_t *m = mask + (size_t)j * w, *end = m + w, *p = memchr(m, value, (size_t)w);
        int cur0 = nr, k0 = prev0;
        while (p) {
            const uint8_t *q = run_end(p, end, value);
            int s = (int)(p - m), i = (int)(q - m);
            runs[nr] = (run_t){j, s, i, nr};
            parent[nr] = nr;
            /* Both rows' runs are sorted: those left of this run are left of
             * the next one too. */
            while (k0 < prev1 && runs[k0].x1 + e <= s)
                k0++;
            for (int k = k0; k < prev1 && runs[k].x0 < i + e; k++) {
                int ra = uf_find(parent, k), rb = uf_find(parent, nr);
                if (ra != rb)
                    parent[ra > rb ? ra : rb] = ra < rb ? ra : rb;
            }
            nr++;
            p = q < end ? memchr(q, value, (size_t)(end - q)) : NULL;
        }
        prev0 = cur0;
        prev1 = nr;
    }
    for (int k = 0; k < nr; k++)
        runs[k].label = uf_find(parent, k);
    return nr;
}

/* Runs of 1s of a mask, an upper bound: one per row more than there are
 * runs, so it also bounds the runs of 0s. */
static size_t run_capacity(const uint8_t *mask, int w, int h)
{
    size_t ones = 0;
    for (int j = 0; j < h; j++) {
        const uint8_t *m = mask + (size_t)j * w, *end = m + w;
        for (const uint8_t *p = memchr(m, 1, (size_t)w); p; ones++) {
            const uint8_t *q = run_end(p, end, 1);
            p = q < end ? memchr(q, 1, (size_t)(end - q)) : NULL;
        }
    }
    return ones + (size_t)h;
}

int recon_mask_components(const uint8_t *mask, int w, int h)
{
    size_t cap = run_capacity(mask, w, h);
    run_t *runs = malloc(cap * sizeof *runs);
    int *parent = malloc(cap * sizeof *parent), n = -1;
    if (runs && parent) {
        int nr = label_runs(mask, w, h, 1, 1, runs, parent);
        n = 0;
        for (int k = 0; k < nr; k++)
            n += runs[k].label == k;
    }
    free(runs);
    free(parent);
    return n;
}

int recon_mask_box(const uint8_t *mask, int w, int h, int box[4])
{
    int x0 = w, x1 = -1, y0 = h, y1 = -1;
    for (int y = 0; y < h; y++) {
        const uint8_t *m = mask + (size_t)y * w, *a = memchr(m, 1, (size_t)w);
        if (!a)
            continue;
        y0 = y0 < y ? y0 : y;
        y1 = y;
        x0 = x0 < a - m ? x0 : (int)(a - m);
        int r = (int)((const uint8_t *)memrchr(m, 1, (size_t)w) - m);
        x1 = x1 > r ? x1 : r;
    }
    if (y1 < 0)
        return 0;
    box[0] = x0, box[1] = y0, box[2] = x1, box[3] = y1;
    return 1;
}

int recon_mask_label(const uint8_t *mask, int w, int h, int *lab, long **area_out)
{
    size_t cap = run_capacity(mask, w, h);
    run_t *runs = malloc(cap * sizeof *runs);
    int *parent = malloc(cap * sizeof *parent), *id = malloc(cap * sizeof *id);
    long *area = calloc(cap + 1, sizeof *area);
    int n = -1;
    if (!runs || !parent || !id || !area)
        goto out;
    int nr = label_runs(mask, w, h, 1, 1, runs, parent);
    n = 0;
    for (int k = 0; k < nr; k++)
        if (runs[k].label == k)
            id[k] = ++n;
    memset(lab, 0, (size_t)w * h * sizeof *lab);
    for (int k = 0; k < nr; k++) {
        int c = id[runs[k].label];
        int *row = lab + (size_t)runs[k].row * w;
        for (int x = runs[k].x0; x < runs[k].x1; x++)
            row[x] = c;
        area[c] += runs[k].x1 - runs[k].x0;
    }
    *area_out = area;
    area = NULL;
out:
    free(runs);
    free(parent);
    free(id);
    free(area);
    return n;
}

long recon_mask_clean(uint8_t *mask, int w, int h, int *dropped_objects, int *holes_filled)
{
    *dropped_objects = 0;
    *holes_filled = 0;
    size_t cap = run_capacity(mask, w, h);
    run_t *runs = malloc(cap * sizeof *runs);
    int *parent = malloc(cap * sizeof *parent);
    long *area = calloc(cap, sizeof *area);
    if (!runs || !parent || !area) {
        free(runs);
        free(parent);
        free(area);
        return -1;
    }
    int nr = label_runs(mask, w, h, 1, 1, runs, parent);
    int best = -1, objects = 0;
    for (int k = 0; k < nr; k++) {
        if (runs[k].label == k)
            objects++;
        area[runs[k].label] += runs[k].x1 - runs[k].x0;
    }
    for (int k = 0; k < nr; k++)
        if (runs[k].label == k && (best < 0 || area[k] > area[best]))
            best = k;
    long kept = best >= 0 ? area[best] : 0;
    *dropped_objects = objects > 0 ? objects - 1 : 0;
    for (int k = 0; k < nr; k++)
        if (runs[k].label != best)
            memset(mask + (size_t)runs[k].row * w + runs[k].x0, 0, (size_t)(runs[k].x1 - runs[k].x0));

    /* Holes: background components (4-connected) that miss the image border. */
    nr = label_runs(mask, w, h, 0, 0, runs, parent);
    memset(area, 0, (size_t)nr * sizeof *area); /* reused: 1 = touches the border */
    for (int k = 0; k < nr; k++)
        if (runs[k].row == 0 || runs[k].row == h - 1 || runs[k].x0 == 0 || runs[k].x1 == w)
            area[runs[k].label] = 1;
    for (int k = 0; k < nr; k++) {
        if (area[runs[k].label])
            continue;
        if (runs[k].label == k)
            (*holes_filled)++;
        memset(mask + (size_t)runs[k].row * w + runs[k].x0, 1, (size_t)(runs[k].x1 - runs[k].x0));
        kept += runs[k].x1 - runs[k].x0;
    }
    /* A vessel's silhouette meets each row in one interval: fill between the
     * row's outermost object pixels (closes notches that an object colour as
     * light as the backdrop leaves inside the outline). */
    for (int j = 0; j < h; j++) {
        uint8_t *m = mask + (size_t)j * w, *a = memchr(m, 1, (size_t)w);
        if (!a)
            continue;
        uint8_t *b = memrchr(m, 1, (size_t)w);
        int len = (int)(b - a) + 1, zeros = 0;
#pragma omp simd reduction(+ : zeros)
        for (int i = 0; i < len; i++)
            zeros += a[i] == 0;
        memset(a, 1, (size_t)len);
        kept += zeros;
    }
    free(runs);
    free(parent);
    free(area);
    return kept;
}
