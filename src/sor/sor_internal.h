/* Internal layout of an SOR: monotone cubic pieces of the wall, a strip tree
 * of annuli over them, the caps, and the per-ray quantities the solver uses.
 * Everything is in object space (the profile already scaled). */
#ifndef CELADON_SOR_INTERNAL_H
#define CELADON_SOR_INTERNAL_H

#include <stdint.h>

#include "celadon/sor.h"

/* A cubic piece of the wall, its own parameter w in [0,1]. On the leaves of the
 * tree r(w) and h(w) are both monotone; the naive baseline uses the raw Bézier
 * pieces, which need not be. r2 caches the degree-6 Bernstein coefficients of
 * r(w)^2, the ray-independent half of the leaf polynomial. */
typedef struct {
    double r[4], h[4];
    double r2[7];
    double rp[4], hp[4]; /* power-basis coefficients (p0 + p1 w + p2 w^2 + p3 w^3) for fast evaluation */
    double u0, u1;       /* profile parameter range covered */
    double tangent_floor; /* |r'| + |h'| below this is a vanishing tangent (1e-12 of the control polygon) */
    int interval;  /* monotone interval of a leaf (its primitive index) */
} sor_piece;

/* A strip-tree node: the annulus r^2 in [q0, q1], h in [h0, h1] that holds its
 * part of the wall (exact on a monotone run: the endpoints, slightly inflated).
 * Depth-first layout: an internal node's first child follows it, the second is
 * at index skip. A leaf has piece >= 0. */
typedef struct {
    double q0, q1, h0, h1;
    int32_t skip;
    int32_t piece;
} sor_node;

/* A node's strip: a thin oriented box around its arc in the (R = r^2, h)
 * plane, where the ray is a parabola. Every point (R, h) of the arc satisfies
 * d0 <= nr R + nh h <= d1. (nr, nh / size) is the unit normal of the arc's
 * chord in the plane (R, size h), whose axes are both areas, so the strip is
 * oriented the same way at every scale; its sign makes nr >= 0. d0 and d1
 * come from the arc's control points (the arc lies in their convex hull),
 * widened by a margin that covers the solver's acceptance tolerances. */
typedef struct {
    double nr, nh, d0, d1;
} sor_strip;

/* The annuli and strips of an internal node's two children (node + 1 and
 * skip) side by side, so that the usual ray tests both at once (two lanes of
 * a vector). */
typedef struct {
    double q0[2], q1[2], h0[2], h1[2];
    double nr[2], nh[2], d0[2], d1[2];
    int strips; /* the walk tests the strips too: set where both children are leaves */
} sor_pair;

struct sor {
    double height, scale;   /* rim height; object units per profile unit */
    double inv_height;
    double size;            /* max(height, rim/base extent): the tolerance scale */
    double tol;             /* a hit is accepted within tol of the surface */
    double r_max, h_min, h_max;
    unsigned caps;
    double r_base, r_mouth; /* cap radii */
    int n_pieces;           /* monotone leaves, in profile order */
    sor_piece *pieces;
    sor_node bound;         /* the bounding cylinder of wall and caps */
    int n_nodes;
    sor_node *nodes;
    sor_pair *pairs;        /* per node; set for internal nodes */
    sor_strip *strips;      /* per node */
    int n_intervals;        /* monotone intervals: one subtree each */
    int *interval_root;
    int n_bez;              /* raw Bézier pieces for sor_intersect_naive */
    sor_piece *bez;
};

/* The ray re-expressed around a centre point t_c chosen for conditioning:
 * s = t - t_c, rho^2(s) = a s^2 + 2 beta s + rho2c, h(s) = hc + dy s.
 * Shallow rays (a >= dy^2) are centred at their closest approach to the axis
 * (beta = 0), steep ones where they cross the object's mid-height. */
typedef struct {
    vec3 o, d;
    double tc;
    vec3 pc; /* the centre point o + t_c d */
    double a, dy, inv_dy, hc, beta, rho2c;
    double s_star, d2; /* vertex and minimum of rho^2(s) when a > 0 */
    int steep;
} sor_ray;

/* The candidate being improved: best s so far and where it lies. */
typedef struct {
    double s;
    int piece; /* index into the piece array searched, -1 for a cap */
    double w;
    sor_part part;
} sor_best;

int sor_ray_setup(const sor_t *sor, const ray3 *ray, sor_ray *out);

/* Exact intersection of the ray with one cubic piece for s in (smin, best->s);
 * improves *best (piece index idx) and returns 1 when it found a nearer hit. */
int sor_piece_intersect(const sor_t *sor, const sor_piece *pc, int idx, const sor_ray *ry, double smin,
                        sor_best *best);

/* Both caps (as masked), same contract. */
int sor_caps_intersect(const sor_t *sor, const sor_ray *ry, unsigned which, double smin, sor_best *best);

/* The strip test: the range of nr rho^2(s) + nh h(s) over s in [sa, sb]
 * (finite) for the strip st. Conservative: [*lo, *hi] holds every value the
 * ray takes there; the ray misses the strip when it is disjoint from
 * [d0, d1]. Requires a usual ray (dy != 0, a > 0). */
void sor_strip_range(const sor_t *sor, const sor_strip *st, const sor_ray *ry, double sa, double sb, double *lo,
                     double *hi);

/* Which children of internal node `node` the walk keeps for s in [smin, smax]
 * (bit 0: node + 1, bit 1: skip): by their annuli, and with strips set also
 * by their strips where the walk tests them. For tests. */
int sor_children_test(const sor_t *sor, int node, const sor_ray *ry, double smin, double smax, int strips);

/* Walks the subtree at root nearest first. any: stop at the first hit. */
int sor_tree_intersect(const sor_t *sor, int root, const sor_ray *ry, double smin, sor_best *best, int any);

/* Fills the public hit record from a best candidate (pieces: the array that
 * best->piece indexes). */
void sor_fill_hit(const sor_t *sor, const sor_piece *pieces, const sor_ray *ry, const sor_best *best, int prim,
                  sor_hit *hit);

/* SOR_CAP_BASE or SOR_CAP_MOUTH: the cap a primitive index past the intervals names. */
unsigned sor_prim_cap(const sor_t *sor, int prim);

/* min/max that compile to one instruction (fmin/fmax are libm calls here). */
static inline double sor_max(double a, double b) { return a > b ? a : b; }
static inline double sor_min(double a, double b) { return a < b ? a : b; }

/* Bernstein helpers shared by the build and the solver. */
void sor_bernstein_square3(const double p[4], double out[7]);
void sor_cubic_split(const double p[4], double w, double left[4], double right[4]);

#endif
