/* The object mask: alpha, or a threshold on the distance to a background
 * model (automatic, either polarity), or a forced gray threshold. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "recon/recon_internal.h"

/* Clamps a signal value to [0, 1]; NaN (HDR or broken files) becomes 0. */
static inline float finite01(float v) { return v > 0 ? (v < 1 ? v : 1) : 0; }

/* Median of 5 values (the border curves are denoised with it). */
static float median5(float a, float b, float c, float d, float e)
{
    float v[5] = {a, b, c, d, e};
    for (int i = 1; i < 5; i++)
        for (int k = i; k > 0 && v[k - 1] > v[k]; k--) {
            float t = v[k];
            v[k] = v[k - 1];
            v[k - 1] = t;
        }
    return v[2];
}

/* Gray values along one image border (stride apart), median-of-5 filtered. */
static void border_curve(const float *gray, int n, size_t stride, float *out)
{
    for (int i = 0; i < n; i++) {
        float v[5];
        for (int k = -2; k <= 2; k++) {
            int q = i + k < 0 ? 0 : (i + k >= n ? n - 1 : i + k);
            v[k + 2] = gray[(size_t)q * stride];
        }
        out[i] = median5(v[0], v[1], v[2], v[3], v[4]);
    }
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* Noise of the background: robust sigma of neighbour differences along the
 * top and bottom borders (MAD * 1.4826 / sqrt 2). */
static double border_noise(const float *gray, int w, int h)
{
    int n = 2 * (w - 1);
    float *d = malloc((size_t)n * sizeof *d);
    if (!d)
        return 0;
    for (int i = 0; i + 1 < w; i++) {
        d[i] = fabsf(gray[i + 1] - gray[i]);
        d[w - 1 + i] = fabsf(gray[(size_t)(h - 1) * w + i + 1] - gray[(size_t)(h - 1) * w + i]);
    }
    qsort(d, (size_t)n, sizeof *d, cmp_float);
    double s = d[n / 2] * 1.4826 / sqrt(2.0);
    free(d);
    return s;
}

/* Otsu's threshold on a histogram of nb bins; returns the bin index t such
 * that classes are [0, t] and (t, nb). */
static int otsu_bin(const long *hist, int nb)
{
    double total = 0, sum = 0;
    for (int i = 0; i < nb; i++) {
        total += hist[i];
        sum += (double)i * hist[i];
    }
    double wb = 0, sb = 0, best = -1;
    int bt = 0;
    for (int t = 0; t < nb - 1; t++) {
        wb += hist[t];
        sb += (double)t * hist[t];
        double wf = total - wb;
        if (wb <= 0 || wf <= 0)
            continue;
        double mb = sb / wb, mf = (sum - sb) / wf, v = wb * wf * (mb - mf) * (mb - mf);
        if (v > best) {
            best = v;
            bt = t;
        }
    }
    return bt;
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

RECON_VECTOR_CLONES recon_mask_mode recon_mask_threshold(const image_t *img, int threshold, float *gray, uint8_t *mask,
                                     int *threshold_used)
{
    const int w = img->width, h = img->height, c = img->channels;
    const size_t n = (size_t)w * h, row = (size_t)w * c;
    const float *px = img->data;

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
            *threshold_used = -1;
            return RECON_MASK_ALPHA;
        }
    }

    /* Background model: the Coons patch of the four (denoised) border curves,
     * exact for backdrops that vary linearly or along one direction only.
     * The border's gray comes first; the rest of the image is converted row
     * by row below, in the same pass that measures it. */
    float *top = malloc(((size_t)2 * w + 4 * h) * sizeof *top);
    if (!top) {
        memset(mask, 0, n);
        *threshold_used = 0;
        return RECON_MASK_BACKGROUND;
    }
    float *bot = top + w, *left = bot + w, *right = left + h, *col_l = right + h, *col_r = col_l + h;
    gray_row(px, c, w, gray);
    gray_row(px + (size_t)(h - 1) * row, c, w, gray + (size_t)(h - 1) * w);
    for (int j = 0; j < h; j++) {
        gray_row(px + (size_t)j * row, c, 1, col_l + j);
        gray_row(px + (size_t)j * row + (size_t)(w - 1) * c, c, 1, col_r + j);
    }
    border_curve(gray, w, 1, top);
    border_curve(gray + (size_t)(h - 1) * w, w, 1, bot);
    border_curve(col_l, h, 1, left);
    border_curve(col_r, h, 1, right);

    if (threshold >= 0) {
        /* Forced: polarity from the border's median against the threshold. */
        float *b = malloc(((size_t)2 * w + 2 * h) * sizeof *b);
        float med = top[0];
        if (b) {
            memcpy(b, top, ((size_t)2 * w + 2 * h) * sizeof *b);
            qsort(b, (size_t)2 * w + 2 * h, sizeof *b, cmp_float);
            med = b[w + h];
            free(b);
        }
        free(top);
        float t = threshold / 255.0f;
        int below = med > t;
        for (int j = 0; j < h; j++) {
            float *restrict g = gray + (size_t)j * w;
            uint8_t *restrict m = mask + (size_t)j * w;
            gray_row(px + (size_t)j * row, c, w, g);
#pragma omp simd
            for (int i = 0; i < w; i++)
                m[i] = below ? g[i] < t : g[i] > t;
        }
        *threshold_used = threshold;
        return below ? RECON_MASK_GRAY_BELOW : RECON_MASK_GRAY_ABOVE;
    }

    /* Distance to the background model, its histogram, Otsu. The distance is
     * written into mask as 0..255 first, then thresholded in place. */
    enum { NB = 256 };
    uint32_t sub[4][NB] = {{0}}; /* interleaved: shorter increment chains */
    const float c00 = top[0], c10 = top[w - 1], c01 = bot[0], c11 = bot[w - 1];
    const float iu = w > 1 ? 1.0f / (w - 1) : 0, iv = h > 1 ? 1.0f / (h - 1) : 0;
    for (int j = 0; j < h; j++) {
        float *restrict g = gray + (size_t)j * w;
        uint8_t *restrict m = mask + (size_t)j * w;
        gray_row(px + (size_t)j * row, c, w, g);
        /* The patch on row j is P[i] + alpha + beta u, u = i/(w-1). */
        float v = j * iv, l = left[j], r = right[j];
        float k0 = (1 - v) * c00 + v * c01, k1 = (1 - v) * (c10 - c00) + v * (c11 - c01);
        float alpha = l - k0, beta = (r - l - k1) * iu;
        const float *restrict tp = top, *restrict bt = bot;
#pragma omp simd
        for (int i = 0; i < w; i++) {
            float bgm = (1 - v) * tp[i] + v * bt[i] + alpha + beta * i;
            float d = fabsf(g[i] - bgm) * 255.0f + 0.5f;
            m[i] = (uint8_t)(int)(d < 255.0f ? d : 255.0f);
        }
        int i = 0;
        for (; i + 15 < w; i += 16) {
            /* Sixteen equal distances (a flat stretch of backdrop) count at
             * once; otherwise one by one into four interleaved tables. */
            uint64_t a, b, same = 0x0101010101010101ull * m[i];
            memcpy(&a, m + i, sizeof a);
            memcpy(&b, m + i + 8, sizeof b);
            if (a == same && b == same) {
                sub[0][m[i]] += 16;
                continue;
            }
            for (int k = 0; k < 16; k += 4) {
                sub[0][m[i + k]]++;
                sub[1][m[i + k + 1]]++;
                sub[2][m[i + k + 2]]++;
                sub[3][m[i + k + 3]]++;
            }
        }
        for (; i < w; i++)
            sub[0][m[i]]++;
    }
    long hist[NB];
    for (int k = 0; k < NB; k++)
        hist[k] = (long)sub[0][k] + sub[1][k] + sub[2][k] + sub[3][k];
    free(top);
    /* Otsu separates background from object; half of it keeps the object's
     * outline pixels that are close to the background (anti-aliasing, light
     * glazes), and a floor of four noise sigmas keeps noise out. */
    int t = otsu_bin(hist, NB);
    double floor_t = fmax(4 * 255 * border_noise(gray, w, h), 2.0);
    int tu = (int)fmax(ceil(0.5 * t), floor_t);
    if (tu > 254)
        tu = 254;
    const uint8_t tb = (uint8_t)tu;
#pragma omp simd
    for (size_t i = 0; i < n; i++)
        mask[i] = mask[i] > tb;
    *threshold_used = tu;
    return RECON_MASK_BACKGROUND;
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

long recon_mask_clean(uint8_t *mask, int w, int h, int *dropped_objects, int *holes_filled)
{
    *dropped_objects = 0;
    *holes_filled = 0;
    /* Runs of 1s plus runs of 0s: each row has at most one more run of one
     * value than of the other, so this bounds both labellings. */
    size_t ones = 0;
    for (int j = 0; j < h; j++) {
        const uint8_t *m = mask + (size_t)j * w, *end = m + w;
        for (const uint8_t *p = memchr(m, 1, (size_t)w); p; ones++) {
            const uint8_t *q = run_end(p, end, 1);
            p = q < end ? memchr(q, 1, (size_t)(end - q)) : NULL;
        }
    }
    size_t cap = ones + (size_t)h;
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

/* A sharp step across pixel i of a row, at least step over two pixels. */
static int sharp(const float *g, int w, int i, float step)
{
    return i < 1 || i + 1 >= w || fabsf(g[i - 1] - g[i + 1]) >= step;
}

int recon_mask_trim_soft(uint8_t *mask, const float *gray, int w, int h, float step)
{
    int top = -1, bottom = -1;
    for (int j = 0; j < h; j++)
        if (memchr(mask + (size_t)j * w, 1, (size_t)w)) {
            bottom = j;
            if (top < 0)
                top = j;
        }
    if (top < 0)
        return 0;
    int trimmed = 0, plo = -1, phi = -1;
    for (int j = bottom - (bottom - top) / 8; j <= bottom; j++) {
        uint8_t *m = mask + (size_t)j * w;
        const float *g = gray + (size_t)j * w;
        const uint8_t *pa = memchr(m, 1, (size_t)w);
        if (!pa)
            continue;
        int a = (int)(pa - m), b = (int)((const uint8_t *)memrchr(m, 1, (size_t)w) - m);
        /* An end that juts out more than 3 px past the row above moves
         * inward to the first sharp step (none: it stays). */
        int l = a, r = b;
        if (phi >= 0 && b > phi + 3) {
            while (r > a && !sharp(g, w, r, step))
                r--;
            if (r <= a)
                r = b;
        }
        if (plo >= 0 && a < plo - 3) {
            while (l < r && !sharp(g, w, l, step))
                l++;
            if (l >= r)
                l = a;
        }
        if (l > a || r < b)
            trimmed = 1;
        memset(m + a, 0, (size_t)(l - a));
        memset(m + r + 1, 0, (size_t)(b - r));
        plo = l;
        phi = r;
    }
    return trimmed;
}
