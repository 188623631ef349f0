/* Ray queries: the ray in the (r, h) half-plane, the strip-tree walk (nearest
 * node first, culling annuli the ray's hyperbola cannot reach and, at leaf
 * pairs, strips its parabola in (r^2, h) cannot reach), the analytic caps,
 * and the hit record. */
#include <math.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "sor_internal.h"

#define TREE_STACK 64

int sor_ray_setup(const sor_t *sor, const ray3 *ray, sor_ray *ry)
{
    vec3 o = ray->o, d = ray->d;
    double a = d.x * d.x + d.z * d.z, dy = d.y;
    if (!(a + dy * dy > 0.0) || !isfinite(a + dy * dy) || !isfinite(o.x + o.y + o.z))
        return 0;
    /* A tilt so small that 1/dy (or 1/a) overflows is horizontal (vertical) to
     * double precision. */
    double inv_dy = 1.0 / dy, inv_a = 1.0 / a;
    if (!isfinite(inv_dy))
        dy = 0.0, inv_dy = 0.0;
    if (!isfinite(inv_a))
        a = 0.0, inv_a = 0.0;
    ry->o = o, ry->d = d, ry->a = a, ry->dy = dy, ry->inv_dy = inv_dy;
    ry->steep = a < dy * dy;
    ry->tc = ry->steep ? (0.5 * (sor->h_min + sor->h_max) - o.y) * inv_dy : -(o.x * d.x + o.z * d.z) * inv_a;
    vec3 pc = v3_add(o, v3_scale(d, ry->tc));
    ry->pc = pc;
    ry->hc = pc.y;
    ry->rho2c = pc.x * pc.x + pc.z * pc.z;
    ry->beta = ry->steep ? pc.x * d.x + pc.z * d.z : 0.0;
    double cr = pc.x * d.z - pc.z * d.x; /* invariant along the ray: no cancellation */
    ry->s_star = -ry->beta * inv_a;
    ry->d2 = a > 0.0 ? cr * cr * inv_a : ry->rho2c;
    return 1;
}

/* Can the ray meet the annulus r^2 in [q0,q1], h in [h0,h1] for s in [smin, smax]?
 * On success *slo is a lower bound of s over the meeting. Over the node's
 * h-slab, rho^2 is a parabola in s: its maximum is at an end of the slab, its
 * minimum at the vertex clamped into it. `usual` (dy != 0 and a > 0, known
 * per ray) selects the branch-free test: min/max compile to single
 * instructions, and the comparisons are combined at the end. */
static inline __attribute__((always_inline)) int node_hit(const sor_node *nd, const sor_ray *ry, double smin,
                                                          double smax, double *slo, int usual)
{
    double sa, sb;
    if (usual || ry->dy != 0.0) {
        double s0 = (nd->h0 - ry->hc) * ry->inv_dy, s1 = (nd->h1 - ry->hc) * ry->inv_dy;
        sa = sor_max(sor_min(s0, s1), smin);
        sb = sor_min(sor_max(s0, s1), smax);
    } else {
        if (ry->hc < nd->h0 || ry->hc > nd->h1)
            return 0;
        sa = smin, sb = smax;
    }
    *slo = sa;
    if (usual || ry->a > 0.0) {
        double ea = sa - ry->s_star, eb = sb - ry->s_star;
        double em = sor_max(ea, sor_min(eb, 0.0)); /* the vertex clamped into [ea, eb] */
        double fa = ry->a * ea * ea, fb = ry->a * eb * eb, fm = ry->a * em * em;
        return (sa <= sb) & (sor_max(fa, fb) + ry->d2 >= nd->q0) & (fm + ry->d2 <= nd->q1);
    }
    return (sa <= sb) & (ry->rho2c >= nd->q0) & (ry->rho2c <= nd->q1);
}

/* The strip test (a node's strip against the ray's parabola in the (R, h)
 * plane). Along the ray, g(s) = nr rho^2(s) + nh h(s) = A s^2 + B s + C with
 * A = nr a >= 0 (strips are oriented so that nr >= 0), B = 2 nr beta + nh dy,
 * C = nr rho2c + nh hc. Around the middle m of [sa, sb] (half-width hw),
 * g = g(m) + g'(m) x + A x^2 for |x| <= hw, so its range lies in
 * [g(m) - |g'(m)| hw, g(m) + |g'(m)| hw + A hw^2]: exact when the vertex is at
 * m, wider by at most A hw^2 otherwise, true for any m in the interval, and
 * with no division. It is widened for rounding by 1e-12 of the magnitude of
 * the terms, a X^2 + (2|beta| + size|dy|) X + rho2c + size|hc| at X = |m| + hw
 * (as |nr| <= 1, |nh| <= size): evaluating g rounds by at most about 20
 * epsilon of that, so the margin covers it some 200 times over. */
#define STRIP_ROUNDING 1e-12

static inline __attribute__((always_inline)) void strip_range(double nr, double nh, double size, const sor_ray *ry,
                                                              double sa, double sb, double *lo, double *hi)
{
    double A = nr * ry->a, B = nr * (2.0 * ry->beta) + nh * ry->dy, C = nr * ry->rho2c + nh * ry->hc;
    double m = 0.5 * (sa + sb), hw = 0.5 * (sb - sa);
    double Am = A * m, gm = (Am + B) * m + C, spread = fabs(Am + Am + B) * hw, curv = A * hw * hw;
    double X = fabs(m) + hw, bx = 2.0 * fabs(ry->beta) + size * fabs(ry->dy), cx = ry->rho2c + size * fabs(ry->hc);
    double margin = STRIP_ROUNDING * ((ry->a * X + bx) * X + cx);
    *lo = gm - spread - margin;
    *hi = gm + spread + curv + margin;
}

void sor_strip_range(const sor_t *sor, const sor_strip *st, const sor_ray *ry, double sa, double sb, double *lo,
                     double *hi)
{
    strip_range(st->nr, st->nh, sor->size, ry, sa, sb, lo, hi);
}

/* Which children of internal node `node` the ray can meet (bit 0: node + 1,
 * bit 1: skip), with their lower bounds of s in slo[]. For the usual ray both
 * are tested at once, the same arithmetic as node_hit in two vector lanes,
 * and where the pair asks for it (both children leaves) and `strips` is set,
 * their strips too, the same arithmetic as strip_range. A NaN keeps a child:
 * the strip cull is written as two negated comparisons. */
static inline __attribute__((always_inline)) int children_hit(const sor_t *sor, int node, const sor_ray *ry,
                                                              double smin, double smax, double slo[2], int usual,
                                                              int strips)
{
    const sor_pair *pr = &sor->pairs[node];
#ifdef __SSE2__
    if (usual) {
        __m128d hc = _mm_set1_pd(ry->hc), inv_dy = _mm_set1_pd(ry->inv_dy), s_star = _mm_set1_pd(ry->s_star);
        __m128d a = _mm_set1_pd(ry->a), d2 = _mm_set1_pd(ry->d2);
        __m128d s0 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(pr->h0), hc), inv_dy);
        __m128d s1 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(pr->h1), hc), inv_dy);
        __m128d sa = _mm_max_pd(_mm_min_pd(s0, s1), _mm_set1_pd(smin));
        __m128d sb = _mm_min_pd(_mm_max_pd(s0, s1), _mm_set1_pd(smax));
        __m128d ea = _mm_sub_pd(sa, s_star), eb = _mm_sub_pd(sb, s_star);
        __m128d em = _mm_max_pd(ea, _mm_min_pd(eb, _mm_setzero_pd()));
        __m128d fa = _mm_mul_pd(_mm_mul_pd(a, ea), ea), fb = _mm_mul_pd(_mm_mul_pd(a, eb), eb);
        __m128d fm = _mm_mul_pd(_mm_mul_pd(a, em), em);
        __m128d ok = _mm_and_pd(_mm_cmple_pd(sa, sb),
                                _mm_and_pd(_mm_cmpge_pd(_mm_add_pd(_mm_max_pd(fa, fb), d2), _mm_loadu_pd(pr->q0)),
                                           _mm_cmple_pd(_mm_add_pd(fm, d2), _mm_loadu_pd(pr->q1))));
        _mm_storeu_pd(slo, sa);
        if (strips && pr->strips) {
            __m128d nr = _mm_loadu_pd(pr->nr), nh = _mm_loadu_pd(pr->nh), half = _mm_set1_pd(0.5);
            __m128d sign = _mm_set1_pd(-0.0);
            __m128d A = _mm_mul_pd(nr, a);
            __m128d B = _mm_add_pd(_mm_mul_pd(nr, _mm_set1_pd(2.0 * ry->beta)), _mm_mul_pd(nh, _mm_set1_pd(ry->dy)));
            __m128d C = _mm_add_pd(_mm_mul_pd(nr, _mm_set1_pd(ry->rho2c)), _mm_mul_pd(nh, hc));
            __m128d m = _mm_mul_pd(half, _mm_add_pd(sa, sb)), hw = _mm_mul_pd(half, _mm_sub_pd(sb, sa));
            __m128d Am = _mm_mul_pd(A, m);
            __m128d gm = _mm_add_pd(_mm_mul_pd(_mm_add_pd(Am, B), m), C);
            __m128d spread = _mm_mul_pd(_mm_andnot_pd(sign, _mm_add_pd(_mm_add_pd(Am, Am), B)), hw);
            __m128d curv = _mm_mul_pd(_mm_mul_pd(A, hw), hw);
            __m128d X = _mm_add_pd(_mm_andnot_pd(sign, m), hw);
            __m128d bx = _mm_set1_pd(2.0 * fabs(ry->beta) + sor->size * fabs(ry->dy));
            __m128d cx = _mm_set1_pd(ry->rho2c + sor->size * fabs(ry->hc));
            __m128d margin = _mm_mul_pd(_mm_set1_pd(STRIP_ROUNDING),
                                        _mm_add_pd(_mm_mul_pd(_mm_add_pd(_mm_mul_pd(a, X), bx), X), cx));
            __m128d lo = _mm_sub_pd(_mm_sub_pd(gm, spread), margin);
            __m128d hi = _mm_add_pd(_mm_add_pd(_mm_add_pd(gm, spread), curv), margin);
            ok = _mm_and_pd(ok, _mm_and_pd(_mm_cmpnlt_pd(hi, _mm_loadu_pd(pr->d0)),
                                           _mm_cmpngt_pd(lo, _mm_loadu_pd(pr->d1))));
        }
        return _mm_movemask_pd(ok);
    }
#endif
    const sor_node *nodes = sor->nodes;
    int hit = node_hit(&nodes[node + 1], ry, smin, smax, &slo[0], usual) |
              node_hit(&nodes[nodes[node].skip], ry, smin, smax, &slo[1], usual) << 1;
    if (strips && usual && pr->strips) {
        for (int j = 0; j < 2; j++) {
            double sb = sor_min(sor_max((pr->h0[j] - ry->hc) * ry->inv_dy, (pr->h1[j] - ry->hc) * ry->inv_dy), smax);
            double lo, hi;
            strip_range(pr->nr[j], pr->nh[j], sor->size, ry, slo[j], sb, &lo, &hi);
            if ((hi < pr->d0[j]) | (lo > pr->d1[j]))
                hit &= ~(1 << j);
        }
    }
    return hit;
}

int sor_children_test(const sor_t *sor, int node, const sor_ray *ry, double smin, double smax, int strips)
{
    double slo[2];
    int usual = ry->dy != 0.0 && ry->a > 0.0;
    if (strips)
        return usual ? children_hit(sor, node, ry, smin, smax, slo, 1, 1)
                     : children_hit(sor, node, ry, smin, smax, slo, 0, 1);
    return usual ? children_hit(sor, node, ry, smin, smax, slo, 1, 0)
                 : children_hit(sor, node, ry, smin, smax, slo, 0, 0);
}

/* The walk, nearest child first; `usual` as in node_hit, so the usual rays get
 * a copy of the loop without the degenerate branches. */
static inline __attribute__((always_inline)) int tree_walk(const sor_t *sor, int root, const sor_ray *ry, double smin,
                                                           sor_best *best, int any, int usual)
{
    const sor_node *nodes = sor->nodes;
    int stack_n[TREE_STACK];
    double stack_s[TREE_STACK];
    int sp = 0, found = 0, node = root;
    double slo;
    if (!node_hit(&nodes[root], ry, smin, best->s, &slo, usual))
        return 0;
    for (;;) {
        const sor_node *nd = &nodes[node];
        if (nd->piece >= 0) {
            if (sor_piece_intersect(sor, &sor->pieces[nd->piece], nd->piece, ry, smin, best)) {
                found = 1;
                if (any)
                    return 1;
            }
        } else {
            double s[2] = {0.0, 0.0};
            int hit = children_hit(sor, node, ry, smin, best->s, s, usual, 1);
            if (hit == 3) {
                int first = s[0] <= s[1];
                stack_n[sp] = first ? nd->skip : node + 1, stack_s[sp] = first ? s[1] : s[0], sp++;
                node = first ? node + 1 : nd->skip;
                continue;
            }
            if (hit) {
                node = hit == 1 ? node + 1 : nd->skip;
                continue;
            }
        }
        /* Pop the nearest pending node that can still hold a nearer hit. */
        for (;;) {
            if (sp == 0)
                return found;
            sp--;
            if (stack_s[sp] < best->s) {
                node = stack_n[sp];
                break;
            }
        }
    }
}

static inline int ray_usual(const sor_ray *ry) { return ry->dy != 0.0 && ry->a > 0.0; }

/* The bounding cylinder of wall and caps. */
static inline int bound_hit(const sor_t *sor, const sor_ray *ry, double smin, double smax)
{
    double slo;
    return ray_usual(ry) ? node_hit(&sor->bound, ry, smin, smax, &slo, 1) : node_hit(&sor->bound, ry, smin, smax, &slo, 0);
}

int sor_tree_intersect(const sor_t *sor, int root, const sor_ray *ry, double smin, sor_best *best, int any)
{
    return ray_usual(ry) ? tree_walk(sor, root, ry, smin, best, any, 1) : tree_walk(sor, root, ry, smin, best, any, 0);
}

int sor_caps_intersect(const sor_t *sor, const sor_ray *ry, unsigned which, double smin, sor_best *best)
{
    int found = 0;
    if (ry->dy == 0.0)
        return 0; /* a ray in a cap's plane only grazes it */
    which &= sor->caps;
    for (unsigned cap = SOR_CAP_BASE; cap <= SOR_CAP_MOUTH; cap <<= 1) {
        if (!(which & cap))
            continue;
        double y = cap == SOR_CAP_BASE ? 0.0 : sor->height, R = cap == SOR_CAP_BASE ? sor->r_base : sor->r_mouth;
        double s = (y - ry->hc) * ry->inv_dy;
        if (!(s > smin && s < best->s))
            continue;
        double x = ry->pc.x + s * ry->d.x, z = ry->pc.z + s * ry->d.z, lim = R + sor->tol;
        if (x * x + z * z <= lim * lim) {
            best->s = s, best->piece = -1, best->w = 0.0;
            best->part = cap == SOR_CAP_BASE ? SOR_PART_BASE : SOR_PART_MOUTH;
            found = 1;
        }
    }
    return found;
}

void sor_fill_hit(const sor_t *sor, const sor_piece *pieces, const sor_ray *ry, const sor_best *best, int prim,
                  sor_hit *hit)
{
    double t = ry->tc + best->s;
    vec3 p = v3_add(ry->pc, v3_scale(ry->d, best->s));
    double rho = sqrt(p.x * p.x + p.z * p.z), c = 1.0, sn = 0.0, phi = 0.0;
    if (rho > 0.0) {
        double inv_rho = 1.0 / rho;
        c = p.x * inv_rho, sn = p.z * inv_rho;
        phi = atan2(p.z, p.x);
        if (phi < 0.0)
            phi += 2.0 * M_PI;
        if (phi >= 2.0 * M_PI)
            phi = 0.0;
    }
    vec3 n;
    double u;
    if (best->part == SOR_PART_WALL) {
        const sor_piece *pc = &pieces[best->piece];
        double w = best->w, m = 1.0 - w;
        double rw = m * m * (pc->r[1] - pc->r[0]) + 2.0 * w * m * (pc->r[2] - pc->r[1]) + w * w * (pc->r[3] - pc->r[2]);
        double hw = m * m * (pc->h[1] - pc->h[0]) + 2.0 * w * m * (pc->h[2] - pc->h[1]) + w * w * (pc->h[3] - pc->h[2]);
        if (fabs(rw) + fabs(hw) <= pc->tangent_floor) {
            /* A vanishing tangent (coincident control points at an end): the
             * tangent's limit is the direction to the next distinct control point. */
            int end = w > 0.5;
            rw = end ? pc->r[3] - pc->r[1] : pc->r[2] - pc->r[0];
            hw = end ? pc->h[3] - pc->h[1] : pc->h[2] - pc->h[0];
        }
        double len2 = hw * hw + rw * rw; /* |(hw c, -rw, hw sn)|^2, as c^2 + sn^2 = 1 */
        double inv_len = len2 > 0.0 ? 1.0 / sqrt(len2) : 0.0;
        n = v3(hw * c * inv_len, -rw * inv_len, hw * sn * inv_len);
        u = pc->u0 + w * (pc->u1 - pc->u0);
    } else {
        n = v3(0.0, best->part == SOR_PART_BASE ? -1.0 : 1.0, 0.0);
        u = best->part == SOR_PART_BASE ? 0.0 : 1.0;
    }
    hit->t = t;
    hit->u = u;
    hit->phi = phi;
    hit->p = p;
    hit->ng = n;
    hit->shading.n = n;
    hit->shading.s = v3(-sn, 0.0, c);
    hit->shading.t = v3_cross(n, hit->shading.s);
    double tu = phi <= M_PI ? 1.0 - phi * M_1_PI : phi * M_1_PI - 1.0;
    hit->uv = v2(tu, sor_min(1.0, sor_max(0.0, p.y * sor->inv_height)));
    hit->part = best->part;
    hit->prim = prim;
}

/* Primitive index of a hit. */
static int hit_prim(const sor_t *sor, const sor_piece *pieces, const sor_best *best)
{
    if (best->part == SOR_PART_BASE)
        return sor->n_intervals;
    if (best->part == SOR_PART_MOUTH)
        return sor->n_intervals + !!(sor->caps & SOR_CAP_BASE);
    if (pieces == sor->pieces)
        return sor->pieces[best->piece].interval;
    /* A raw Bézier piece (naive search): the leaf that covers its parameter. */
    const sor_piece *pc = &pieces[best->piece];
    double u = pc->u0 + best->w * (pc->u1 - pc->u0);
    int lo = 0, hi = sor->n_pieces - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (sor->pieces[mid].u1 < u)
            lo = mid + 1;
        else
            hi = mid;
    }
    return sor->pieces[lo].interval;
}

/* Per-ray state shared by every query: the ray in the solver's frame, no hit
 * yet, and the search window (tmin, tmax) in the frame's parameter s = t - tc. */
static inline int ray_begin(const sor_t *sor, const ray3 *ray, double tmin, double tmax, sor_ray *ry, sor_best *best,
                            double *smin)
{
    if (!sor_ray_setup(sor, ray, ry))
        return 0;
    *best = (sor_best){tmax - ry->tc, -1, 0.0, SOR_PART_WALL};
    *smin = tmin - ry->tc;
    return 1;
}

static int finish(const sor_t *sor, const sor_piece *pieces, const sor_ray *ry, const sor_best *best, int found,
                  sor_hit *hit)
{
    if (found && hit)
        sor_fill_hit(sor, pieces, ry, best, hit_prim(sor, pieces, best), hit);
    return found;
}

/* The whole SOR: caps and the tree from its root, behind the bounding
 * cylinder. any_hit stops at the first confirmed hit (shadow rays). */
static int trace(const sor_t *sor, const ray3 *ray, double tmin, double tmax, int any_hit, sor_hit *hit)
{
    sor_ray ry;
    sor_best best;
    double smin;
    if (!ray_begin(sor, ray, tmin, tmax, &ry, &best, &smin) || !bound_hit(sor, &ry, smin, best.s))
        return 0;
    int found = sor_caps_intersect(sor, &ry, SOR_CAPS_ALL, smin, &best);
    if (!(found && any_hit))
        found |= sor_tree_intersect(sor, 0, &ry, smin, &best, any_hit);
    return finish(sor, sor->pieces, &ry, &best, found, hit);
}

int sor_intersect(const sor_t *sor, const ray3 *ray, double tmin, double tmax, sor_hit *hit)
{
    return trace(sor, ray, tmin, tmax, 0, hit);
}

int sor_occluded(const sor_t *sor, const ray3 *ray, double tmin, double tmax)
{
    return trace(sor, ray, tmin, tmax, 1, NULL);
}

int sor_prim_intersect(const sor_t *sor, int prim, const ray3 *ray, double tmin, double tmax, sor_hit *hit)
{
    sor_ray ry;
    sor_best best;
    double smin;
    if (prim < 0 || prim >= sor_prim_count(sor) || !ray_begin(sor, ray, tmin, tmax, &ry, &best, &smin))
        return 0;
    int found = prim < sor->n_intervals ? sor_tree_intersect(sor, sor->interval_root[prim], &ry, smin, &best, 0)
                                        : sor_caps_intersect(sor, &ry, sor_prim_cap(sor, prim), smin, &best);
    return finish(sor, sor->pieces, &ry, &best, found, hit);
}

int sor_intersect_naive(const sor_t *sor, const ray3 *ray, double tmin, double tmax, sor_hit *hit)
{
    sor_ray ry;
    sor_best best;
    double smin;
    if (!ray_begin(sor, ray, tmin, tmax, &ry, &best, &smin))
        return 0;
    int found = sor_caps_intersect(sor, &ry, SOR_CAPS_ALL, smin, &best);
    for (int j = 0; j < sor->n_bez; j++)
        found |= sor_piece_intersect(sor, &sor->bez[j], j, &ry, smin, &best);
    return finish(sor, sor->bez, &ry, &best, found, hit);
}
