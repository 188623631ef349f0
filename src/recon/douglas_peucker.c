/* Douglas–Peucker polyline approximation of a closed contour. */
#include <stdlib.h>
#include <string.h>

#include "recon/recon_internal.h"

/* Distance from p to the segment [a, b]. */
static double seg_dist(vec2 p, vec2 a, vec2 b)
{
    vec2 ab = v2_sub(b, a), ap = v2_sub(p, a);
    double l2 = v2_dot(ab, ab);
    double t = l2 > 0 ? v2_dot(ap, ab) / l2 : 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    return v2_len(v2_sub(ap, v2_scale(ab, t)));
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
        vec2 pa = pts[i], pb = pts[j % n];
        double best = -1;
        int at = -1;
        for (int k = i + 1; k < j; k++) {
            double d = seg_dist(pts[k], pa, pb);
            if (d > best) {
                best = d;
                at = k;
            }
        }
        if (at >= 0 && best > eps) {
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
        double d = v2_len(v2_sub(pts[k], pts[0]));
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
