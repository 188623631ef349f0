/* Suzuki–Abe border following (S. Suzuki, K. Abe, "Topological structural
 * analysis of digitized binary images by border following", CVGIP 30, 1985),
 * algorithm 1: every outer and hole border of the 8-connected objects, with
 * the border hierarchy from the last-seen border number (LNBD, Table 1). */
#include <stdlib.h>
#include <string.h>

#include "recon/recon_internal.h"

/* 8 neighbours, counterclockwise on screen (y down): E, NE, N, NW, W, SW, S, SE. */
static const int DX[8] = {1, 1, 0, -1, -1, -1, 0, 1};
static const int DY[8] = {0, -1, -1, -1, 0, 1, 1, 1};
/* The direction of the step (dx, dy), indexed by (dy + 1) * 3 + dx + 1. */
static const int DIR_OF[9] = {3, 2, 1, 4, 0, 0, 5, 6, 7};

static int dir_of(int dx, int dy) { return DIR_OF[(dy + 1) * 3 + dx + 1]; }

/* The label image of the algorithm (f in the paper) in two parts: state
 * holds 0 (background), 1 (object, not yet on a followed border), 2 (labelled
 * +NBD) or 3 (labelled -NBD), one byte per pixel so that the raster scan can
 * skip uniform stretches a word at a time; nbd holds the NBD of the pixels in
 * state 2 or 3 (and is never read elsewhere, so it needs no initialisation). */
enum { BG = 0, OBJ = 1, POS = 2, NEG = 3 };
typedef struct {
    uint8_t *state;
    int *nbd;
    int W;
} labels;

static inline void set_label(labels *f, size_t i, uint8_t st, int nbd)
{
    f->state[i] = st;
    f->nbd[i] = nbd;
}

typedef struct {
    int *pts;
    int n, cap;
    recon_border *b;
    int nb, capb;
} sink;

static int push_point(sink *s, int x, int y)
{
    if (s->n == s->cap) {
        int cap = s->cap ? 2 * s->cap : 1024;
        int *p = realloc(s->pts, (size_t)cap * 2 * sizeof *p);
        if (!p)
            return -1;
        s->pts = p;
        s->cap = cap;
    }
    s->pts[2 * s->n] = x;
    s->pts[2 * s->n + 1] = y;
    s->n++;
    return 0;
}

/* Follows one border starting at (x, y) (padded coordinates) whose known
 * background neighbour is (x2, y2). Returns -1 on OOM. */
static int follow(labels *f, int ox, int oy, int x, int y, int x2, int y2, int nbd, sink *s)
{
    const int W = f->W;
    const uint8_t *st = f->state;
    /* 3.1: clockwise from (x2, y2) around (x, y) for a nonzero pixel. */
    int d0 = dir_of(x2 - x, y2 - y), d1 = -1;
    for (int k = 0; k < 8; k++) {
        int d = (d0 - k + 8) & 7;
        if (st[(size_t)(y + DY[d]) * W + x + DX[d]] != BG) {
            d1 = d;
            break;
        }
    }
    if (push_point(s, x + ox, y + oy))
        return -1;
    if (d1 < 0) { /* isolated pixel */
        set_label(f, (size_t)y * W + x, NEG, nbd);
        return 0;
    }
    int x1 = x + DX[d1], y1 = y + DY[d1];
    int x3 = x, y3 = y, dprev = d1; /* direction from (x3,y3) to (x2,y2) */
    for (;;) {
        /* 3.3: counterclockwise around (x3, y3), starting after (x2, y2). */
        int d4 = -1, east_zero = 0;
        for (int k = 1; k <= 8; k++) {
            int d = (dprev + k) & 7;
            if (st[(size_t)(y3 + DY[d]) * W + x3 + DX[d]] != BG) {
                d4 = d;
                break;
            }
            if (d == 0)
                east_zero = 1;
        }
        size_t c = (size_t)y3 * W + x3;
        /* 3.4 */
        if (east_zero)
            set_label(f, c, NEG, nbd);
        else if (st[c] == OBJ)
            set_label(f, c, POS, nbd);
        int x4 = x3 + DX[d4], y4 = y3 + DY[d4];
        /* 3.5: (x1, y1) precedes the start on the border: back at the start. */
        if (x4 == x && y4 == y && x3 == x1 && y3 == y1)
            break;
        if (push_point(s, x4 + ox, y4 + oy))
            return -1;
        dprev = dir_of(x3 - x4, y3 - y4);
        x3 = x4;
        y3 = y4;
    }
    return 0;
}

/* Index of the first (last) nonzero byte of a nonzero word of 8 bytes in
 * memory order. */
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define FIRST_BYTE(q) (__builtin_ctzll(q) / 8)
#define LAST_BYTE(q) (7 - __builtin_clzll(q) / 8)
#else
#define FIRST_BYTE(q) (__builtin_clzll(q) / 8)
#define LAST_BYTE(q) (7 - __builtin_ctzll(q) / 8)
#endif

/* The first index in [x, end) whose byte is not v, or end: sixteen bytes at
 * a time (the labels of a row are long runs of 0 and of 1). */
static int skip_value(const uint8_t *row, int x, int end, uint8_t v)
{
    const uint64_t pattern = 0x0101010101010101ull * v;
    for (; x + 16 <= end; x += 16) {
        uint64_t a, b;
        memcpy(&a, row + x, sizeof a);
        memcpy(&b, row + x + 8, sizeof b);
        a ^= pattern;
        b ^= pattern;
        if (a | b)
            return x + (a ? FIRST_BYTE(a) : 8 + FIRST_BYTE(b));
    }
    while (x < end && row[x] == v)
        x++;
    return x;
}

/* The last index in [0, end) whose byte is not 0, or -1; likewise. */
static int last_nonzero(const uint8_t *row, int end)
{
    for (; end >= 16; end -= 16) {
        uint64_t a, b;
        memcpy(&a, row + end - 16, sizeof a);
        memcpy(&b, row + end - 8, sizeof b);
        if (a | b)
            return end - 16 + (b ? 8 + LAST_BYTE(b) : LAST_BYTE(a));
    }
    while (end > 0 && row[end - 1] == 0)
        end--;
    return end - 1;
}

/* Step 1 to 4 of the algorithm at pixel (x, y), a nonzero pixel of the raster
 * scan: starts a border there if it is one's first pixel, and updates LNBD. */
static int scan_pixel(labels *f, int ox, int oy, int x, int y, int *nbd, int *lnbd, sink *s)
{
    const size_t i = (size_t)y * f->W + x;
    const uint8_t *st = f->state;
    int hole = -1, x2 = 0;
    if (st[i] == OBJ && st[i - 1] == BG) {
        hole = 0;
        x2 = x - 1;
    } else if ((st[i] == OBJ || st[i] == POS) && st[i + 1] == BG) {
        hole = 1;
        x2 = x + 1;
        if (st[i] == POS)
            *lnbd = f->nbd[i];
    }
    if (hole >= 0) {
        ++*nbd;
        if (s->nb == s->capb) {
            int cap = s->capb ? 2 * s->capb : 64;
            recon_border *b = realloc(s->b, (size_t)cap * sizeof *b);
            if (!b)
                return -1;
            s->b = b;
            s->capb = cap;
        }
        /* Table 1: the parent from the type of border lnbd. */
        int parent = -1;
        if (*lnbd >= 2) {
            const recon_border *lb = &s->b[*lnbd - 2];
            parent = (lb->is_hole == hole) ? lb->parent : *lnbd - 2;
        }
        recon_border *nb = &s->b[s->nb++];
        nb->start = s->n;
        nb->is_hole = hole;
        nb->parent = parent;
        if (follow(f, ox, oy, x, y, x2, y, *nbd, s))
            return -1;
        nb->count = s->n - nb->start;
    }
    /* 4 */
    if (st[i] != OBJ)
        *lnbd = f->nbd[i];
    return 0;
}

int recon_border_follow(const uint8_t *mask, int w, int h, recon_border_set *out)
{
    memset(out, 0, sizeof *out);
    /* Labels on the objects' bounding box with a one-pixel frame of zeros;
     * (ox, oy) maps label coordinates back to the image. */
    int bx0 = w, bx1 = -1, by0 = -1, by1 = -1;
    for (int y = 0; y < h; y++) {
        const uint8_t *m = mask + (size_t)y * w;
        int a = skip_value(m, 0, w, 0);
        if (a == w)
            continue;
        int b = last_nonzero(m, w);
        if (by0 < 0)
            by0 = y;
        by1 = y;
        bx0 = a < bx0 ? a : bx0;
        bx1 = b > bx1 ? b : bx1;
    }
    if (by0 < 0)
        return 0;
    const int W = bx1 - bx0 + 3, H = by1 - by0 + 3, ox = bx0 - 1, oy = by0 - 1;
    labels f = {malloc((size_t)W * H), malloc((size_t)W * H * sizeof(int)), W};
    if (!f.state || !f.nbd) {
        free(f.state);
        free(f.nbd);
        return -1;
    }
    memset(f.state, BG, (size_t)W);
    memset(f.state + (size_t)(H - 1) * W, BG, (size_t)W);
    for (int y = 1; y < H - 1; y++) {
        uint8_t *restrict r = f.state + (size_t)y * W;
        const uint8_t *restrict m = mask + (size_t)(y + oy) * w + bx0;
        r[0] = r[W - 1] = BG;
#pragma omp simd
        for (int x = 0; x < W - 2; x++)
            r[x + 1] = m[x] != 0;
    }
    sink s = {0};
    int nbd = 1, rc = 0;
    for (int y = 1; y < H - 1 && rc == 0; y++) {
        const uint8_t *r = f.state + (size_t)y * W;
        int lnbd = 1, x = 1;
        for (;;) {
            /* The pixels skipped do nothing in steps 1 to 4: background, and
             * unlabelled object pixels between two object pixels. The frame
             * column W-1 ends both skips. */
            x = skip_value(r, x, W - 1, BG);
            if (x >= W - 1)
                break;
            if ((rc = scan_pixel(&f, ox, oy, x, y, &nbd, &lnbd, &s)) != 0)
                break;
            int t = skip_value(r, x + 1, W - 1, OBJ);
            x = r[t] == BG && t - 1 > x ? t - 1 : t;
        }
    }
    free(f.state);
    free(f.nbd);
    if (rc) {
        free(s.pts);
        free(s.b);
        return -1;
    }
    out->n_borders = s.nb;
    out->borders = s.b;
    out->n_points = s.n;
    out->points = s.pts;
    return 0;
}

void recon_border_set_free(recon_border_set *s)
{
    free(s->borders);
    free(s->points);
    memset(s, 0, sizeof *s);
}
