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

static int dir_of(int dx, int dy)
{
    for (int k = 0; k < 8; k++)
        if (DX[k] == dx && DY[k] == dy)
            return k;
    return 0;
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
 * background neighbour is (x2, y2); f holds the labels. Returns -1 on OOM. */
static int follow(int *f, int W, int ox, int oy, int x, int y, int x2, int y2, int nbd, sink *s)
{
    int *p = f + (size_t)y * W;
    /* 3.1: clockwise from (x2, y2) around (x, y) for a nonzero pixel. */
    int d0 = dir_of(x2 - x, y2 - y), d1 = -1;
    for (int k = 0; k < 8; k++) {
        int d = (d0 - k + 8) & 7;
        if (f[(size_t)(y + DY[d]) * W + x + DX[d]] != 0) {
            d1 = d;
            break;
        }
    }
    if (push_point(s, x + ox, y + oy))
        return -1;
    if (d1 < 0) { /* isolated pixel */
        p[x] = -nbd;
        return 0;
    }
    int x1 = x + DX[d1], y1 = y + DY[d1];
    int x3 = x, y3 = y, dprev = d1; /* direction from (x3,y3) to (x2,y2) */
    for (;;) {
        /* 3.3: counterclockwise around (x3, y3), starting after (x2, y2). */
        int d4 = -1, east_zero = 0;
        for (int k = 1; k <= 8; k++) {
            int d = (dprev + k) & 7;
            int v = f[(size_t)(y3 + DY[d]) * W + x3 + DX[d]];
            if (v != 0) {
                d4 = d;
                break;
            }
            if (d == 0)
                east_zero = 1;
        }
        int *c = f + (size_t)y3 * W + x3;
        /* 3.4 */
        if (east_zero)
            *c = -nbd;
        else if (*c == 1)
            *c = nbd;
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

int recon_border_follow(const uint8_t *mask, int w, int h, recon_border_set *out)
{
    memset(out, 0, sizeof *out);
    /* Labels on the objects' bounding box with a one-pixel frame of zeros;
     * (ox, oy) maps label coordinates back to the image. */
    int bx0 = w, bx1 = -1, by0 = -1, by1 = -1;
    for (int y = 0; y < h; y++) {
        const uint8_t *m = mask + (size_t)y * w;
        int a = 0, b = w - 1;
        while (a < w && !m[a])
            a++;
        if (a == w)
            continue;
        while (!m[b])
            b--;
        if (by0 < 0)
            by0 = y;
        by1 = y;
        bx0 = a < bx0 ? a : bx0;
        bx1 = b > bx1 ? b : bx1;
    }
    if (by0 < 0)
        return 0;
    const int W = bx1 - bx0 + 3, H = by1 - by0 + 3, ox = bx0 - 1, oy = by0 - 1;
    int *f = calloc((size_t)W * H, sizeof *f);
    if (!f)
        return -1;
    for (int y = 1; y < H - 1; y++)
        for (int x = 1; x < W - 1; x++)
            f[(size_t)y * W + x] = mask[(size_t)(y + oy) * w + x + ox] != 0;
    sink s = {0};
    int nbd = 1, rc = 0;
    for (int y = 1; y < H - 1 && rc == 0; y++) {
        int lnbd = 1;
        for (int x = 1; x < W - 1; x++) {
            int *p = f + (size_t)y * W + x;
            if (*p == 0)
                continue;
            int hole = -1, x2 = 0;
            if (*p == 1 && p[-1] == 0) {
                hole = 0;
                x2 = x - 1;
            } else if (*p >= 1 && p[1] == 0) {
                hole = 1;
                x2 = x + 1;
                if (*p > 1)
                    lnbd = *p;
            }
            if (hole >= 0) {
                nbd++;
                if (s.nb == s.capb) {
                    int cap = s.capb ? 2 * s.capb : 64;
                    recon_border *b = realloc(s.b, (size_t)cap * sizeof *b);
                    if (!b) {
                        rc = -1;
                        break;
                    }
                    s.b = b;
                    s.capb = cap;
                }
                /* Table 1: the parent from the type of border lnbd. */
                int parent = -1;
                if (lnbd >= 2) {
                    const recon_border *lb = &s.b[lnbd - 2];
                    parent = (lb->is_hole == hole) ? lb->parent : lnbd - 2;
                }
                recon_border *nb = &s.b[s.nb++];
                nb->start = s.n;
                nb->is_hole = hole;
                nb->parent = parent;
                if (follow(f, W, ox, oy, x, y, x2, y, nbd, &s)) {
                    rc = -1;
                    break;
                }
                nb->count = s.n - nb->start;
            }
            /* 4 */
            if (*p != 1)
                lnbd = abs(*p);
        }
    }
    free(f);
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
