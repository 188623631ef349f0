/* Douglas–Peucker polyline approximation of a closed contour. */
#include <stdlib.h>
#include <string.h>

#include "recon/recon_internal.h"

/* The point of pts(i, j) farthest from the segment [a, b] and its squared
 * distance times scale = |b - a|^2 (1 when a = b): no square root and no
 * division per point, and exact for pixel coordinates. */
static int farthest(const vec2 *pts, int i, int j, vec2 a, vec2 b, double *best_scaled)
{
    const vec2 ab = v2_sub(b, a);
    const double l2 = v2_dot(ab, ab), scale = l2 > 0 ? l2 : 1;
    double best = -1;
    int at = -1;
    for (int k = i + 1; k < j; k++) {
        vec2 ap = v2_sub(pts[k], a);
        double t = v2_dot(ap, ab), d;
        if (t <= 0) /* nearest to a (also when a = b) */
            d = v2_dot(ap, ap) * scale;
        else if (t >= l2) { /* nearest to b */
            vec2 bp = v2_sub(pts[k], b);
            d = v2_dot(bp, bp) * scale;
        } else { /* nearest inside: the distance to the line */
            double c = v2_cross(ab, ap);
            d = c * c;
        }
        if (d > best) {
            best = d;
            at = k;
        }
    }
    *best_scaled = best / scale;
    return at;
}

/* Marks the vertices DP keeps strictly between indices a and b (b may be n,
 * meaning point 0 again), with an explicit stack of index pairs. */
static void simplify(const vec2 *pts, int n, int a, int b, double eps, uint8_t *flag, int *stack)
{
    int top = 0;
    stack[top++] = a;
    stack[top++] = b;
    while (top > 0) {
        int j = stack[--top], i = stack[--top];
        double best;
        int at = farthest(pts, i, j, pts[i], pts[j % n], &best);
        if (at >= 0 && best > eps * eps) {
            flag[at] = 1;
            stack[top++] = i;
            stack[top++] = at;
            stack[top++] = at;
            stack[top++] = j;
        }
    }
}

int recon_douglas_peucker_closed(const vec2 *pts, int n, double eps, int *keep)
{
    if (n <= 0)
        return 0;
    if (n == 1) {
        keep[0] = 0;
        return 1;
    }
    /* Split the loop at point 0 and the point farthest from it. */
    int far = 1;
    double best = -1;
    for (int k = 1; k < n; k++) {
        vec2 d0 = v2_sub(pts[k], pts[0]);
        double d = v2_dot(d0, d0);
        if (d > best) {
            best = d;
            far = k;
        }
    }
    uint8_t *flag = calloc((size_t)n, 1);
    int *stack = malloc((size_t)(2 * n + 4) * sizeof *stack);
    if (!flag || !stack) {
        free(flag);
        free(stack);
        keep[0] = 0;
        keep[1] = far;
        return 2;
    }
    flag[0] = flag[far] = 1;
    simplify(pts, n, 0, far, eps, flag, stack);
    simplify(pts, n, far, n, eps, flag, stack);
    int m = 0;
    for (int k = 0; k < n; k++)
        if (flag[k])
            keep[m++] = k;
    free(flag);
    free(stack);
    return m;
}
