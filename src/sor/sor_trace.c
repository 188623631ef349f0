/* Ray queries: the ray in the (r, h) half-plane, the strip-tree walk (nearest
 * node first, culling annuli the ray's hyperbola cannot reach), the analytic
 * caps, and the hit record. */
#include <math.h>

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
 * On success *slo is a lower bound of s over the meeting. The usual case
 * (dy != 0, a > 0) is branch-free: min/max compile to single instructions,
 * and the tests are combined at the end. */
static inline int node_hit(const sor_node *nd, const sor_ray *ry, double smin, double smax, double *slo)
{
    double sa, sb;
    if (ry->dy != 0.0) {
        double s0 = (nd->h0 - ry->hc) * ry->inv_dy, s1 = (nd->h1 - ry->hc) * ry->inv_dy;
        sa = sor_max(sor_min(s0, s1), smin);
        sb = sor_min(sor_max(s0, s1), smax);
    } else {
        if (ry->hc < nd->h0 || ry->hc > nd->h1)
            return 0;
        sa = smin, sb = smax;
    }
    *slo = sa;
    if (ry->a > 0.0) {
        double ea = sa - ry->s_star, eb = sb - ry->s_star;
        double em = sor_max(ea, sor_min(eb, 0.0)); /* the vertex clamped into [ea, eb] */
        double fa = ry->a * ea * ea, fb = ry->a * eb * eb, fm = ry->a * em * em;
        return (sa <= sb) & (sor_max(fa, fb) + ry->d2 >= nd->q0) & (fm + ry->d2 <= nd->q1);
    }
    return (sa <= sb) & (ry->rho2c >= nd->q0) & (ry->rho2c <= nd->q1);
}

int sor_tree_intersect(const sor_t *sor, int root, const sor_ray *ry, double smin, sor_best *best, int any)
{
    const sor_node *nodes = sor->nodes;
    int stack_n[TREE_STACK];
    double stack_s[TREE_STACK];
    int sp = 0, found = 0, node = root;
    double slo;
    if (!node_hit(&nodes[root], ry, smin, best->s, &slo))
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
            double s0 = 0.0, s1 = 0.0;
            int h0 = node_hit(&nodes[node + 1], ry, smin, best->s, &s0);
            int h1 = node_hit(&nodes[nd->skip], ry, smin, best->s, &s1);
            if (h0 && h1) {
                int near = s0 <= s1 ? node + 1 : nd->skip, far = s0 <= s1 ? nd->skip : node + 1;
                stack_n[sp] = far, stack_s[sp] = s0 <= s1 ? s1 : s0, sp++;
                node = near;
                continue;
            }
            if (h0 || h1) {
                node = h0 ? node + 1 : nd->skip;
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
        c = p.x / rho, sn = p.z / rho;
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
        double scale = fabs(pc->r[3] - pc->r[0]) + fabs(pc->h[3] - pc->h[0]) + fabs(pc->r[1] - pc->r[0]) +
                       fabs(pc->h[1] - pc->h[0]) + fabs(pc->r[2] - pc->r[3]) + fabs(pc->h[2] - pc->h[3]);
        if (fabs(rw) + fabs(hw) <= 1e-12 * scale) {
            /* A vanishing tangent (coincident control points at an end): the
             * tangent's limit is the direction to the next distinct control point. */
            int end = w > 0.5;
            rw = end ? pc->r[3] - pc->r[1] : pc->r[2] - pc->r[0];
            hw = end ? pc->h[3] - pc->h[1] : pc->h[2] - pc->h[0];
        }
        n = v3_norm(v3(hw * c, -rw, hw * sn));
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
    double tu = phi <= M_PI ? 1.0 - phi / M_PI : phi / M_PI - 1.0;
    hit->uv = v2(tu, sor_min(1.0, sor_max(0.0, p.y / sor->height)));
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

static int finish(const sor_t *sor, const sor_piece *pieces, const sor_ray *ry, const sor_best *best, int found,
                  sor_hit *hit)
{
    if (found && hit)
        sor_fill_hit(sor, pieces, ry, best, hit_prim(sor, pieces, best), hit);
    return found;
}

int sor_intersect(const sor_t *sor, const ray3 *ray, double tmin, double tmax, sor_hit *hit)
{
    sor_ray ry;
    if (!sor_ray_setup(sor, ray, &ry))
        return 0;
    sor_best best = {tmax - ry.tc, -1, 0.0, SOR_PART_WALL};
    double smin = tmin - ry.tc, slo;
    if (!node_hit(&sor->bound, &ry, smin, best.s, &slo))
        return 0;
    int found = sor_caps_intersect(sor, &ry, SOR_CAPS_ALL, smin, &best);
    found |= sor_tree_intersect(sor, 0, &ry, smin, &best, 0);
    return finish(sor, sor->pieces, &ry, &best, found, hit);
}

int sor_occluded(const sor_t *sor, const ray3 *ray, double tmin, double tmax)
{
    sor_ray ry;
    if (!sor_ray_setup(sor, ray, &ry))
        return 0;
    sor_best best = {tmax - ry.tc, -1, 0.0, SOR_PART_WALL};
    double smin = tmin - ry.tc, slo;
    if (!node_hit(&sor->bound, &ry, smin, best.s, &slo))
        return 0;
    return sor_caps_intersect(sor, &ry, SOR_CAPS_ALL, smin, &best) || sor_tree_intersect(sor, 0, &ry, smin, &best, 1);
}

int sor_prim_intersect(const sor_t *sor, int prim, const ray3 *ray, double tmin, double tmax, sor_hit *hit)
{
    sor_ray ry;
    if (prim < 0 || prim >= sor_prim_count(sor) || !sor_ray_setup(sor, ray, &ry))
        return 0;
    sor_best best = {tmax - ry.tc, -1, 0.0, SOR_PART_WALL};
    double smin = tmin - ry.tc;
    int found = prim < sor->n_intervals ? sor_tree_intersect(sor, sor->interval_root[prim], &ry, smin, &best, 0)
                                        : sor_caps_intersect(sor, &ry, sor_prim_cap(sor, prim), smin, &best);
    return finish(sor, sor->pieces, &ry, &best, found, hit);
}

int sor_intersect_naive(const sor_t *sor, const ray3 *ray, double tmin, double tmax, sor_hit *hit)
{
    sor_ray ry;
    if (!sor_ray_setup(sor, ray, &ry))
        return 0;
    sor_best best = {tmax - ry.tc, -1, 0.0, SOR_PART_WALL};
    double smin = tmin - ry.tc;
    int found = sor_caps_intersect(sor, &ry, SOR_CAPS_ALL, smin, &best);
    for (int j = 0; j < sor->n_bez; j++)
        found |= sor_piece_intersect(sor, &sor->bez[j], j, &ry, smin, &best);
    return finish(sor, sor->bez, &ry, &best, found, hit);
}
