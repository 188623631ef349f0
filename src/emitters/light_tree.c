/* Picking an emitter for next-event estimation in proportion to its
 * estimated contribution at the shading point: infinite emitters by their
 * irradiance, the others down a binary bounding volume hierarchy over their
 * light_bounds (Estevez & Kulla 2018; pbrt-v4's BVHLightSampler), each step
 * choosing a child in proportion to its importance. The importance of a
 * node at a point is phi cos(theta') cos(theta_i') / d^2: d the distance to
 * its bounds' centre, theta' the smallest angle any of its normals can make
 * with the direction to the point (0 past the emission cone: no light
 * there), theta_i' the smallest angle between that direction and the
 * point's normal, both widened by the angle the bounds subtend. It is an
 * estimate of the irradiance the node's lights give, exact in the limit of a
 * small far light, and never 0 where a light of the node can contribute. */
#include <stdlib.h>

#include "emitters/emitter_impl.h"

typedef struct {
    light_bounds b;     /* of every light below */
    int child[2];       /* node indices; -1 for a leaf */
    int light;          /* a leaf's emitter index */
    int parent;         /* -1 for the root */
} tree_node;

struct light_tree {
    tree_node *nodes;
    int n_nodes, root;  /* root -1: no finite light worth picking */
    bool only_one;      /* one finite light, no infinite one: always it */
    int *leaf_of;       /* per emitter: its leaf, or -1 */
    double *inf_phi;    /* per emitter: phi of an infinite one, else 0 */
    double inf_total;
};

/* ------------------------------------------------------------ importance */

/* cos(max(0, a - b)) and sin of it from the angles' sines and cosines. */
static double cos_sub_clamped(double sin_a, double cos_a, double sin_b, double cos_b)
{
    return cos_a > cos_b ? 1.0 : cos_a * cos_b + sin_a * sin_b;
}

static double sin_sub_clamped(double sin_a, double cos_a, double sin_b, double cos_b)
{
    return cos_a > cos_b ? 0.0 : sin_a * cos_b - cos_a * sin_b;
}

static double safe_sqrt(double x) { return sqrt(fmax(0.0, x)); }

static double importance(const light_bounds *b, const emitter_ref *ref)
{
    if (b->infinite)
        return b->phi;
    vec3 c = v3_scale(v3_add(b->lo, b->hi), 0.5);
    vec3 d = v3_sub(ref->p, c);
    double d2 = v3_dot(d, d), r2 = 0.25 * v3_dot(v3_sub(b->hi, b->lo), v3_sub(b->hi, b->lo));
    /* The bounding sphere's directions from the point: all of them from
     * inside it. */
    double cos_b = -1.0, sin_b = 0.0;
    if (d2 > r2) {
        double sin2 = r2 / d2;
        cos_b = sqrt(1.0 - sin2), sin_b = sqrt(sin2);
    }
    vec3 wi = d2 > 0.0 ? v3_scale(d, 1.0 / sqrt(d2)) : v3(0.0, 0.0, 1.0);
    double cos_w = v3_dot(b->axis, wi), sin_w = safe_sqrt(1.0 - cos_w * cos_w);
    double cos_o = b->cos_theta_o, sin_o = safe_sqrt(1.0 - cos_o * cos_o);
    double cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, cos_o), sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, cos_o);
    double cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
    if (cos_p <= b->cos_theta_e)
        return 0.0;
    double imp = b->phi * cos_p / fmax(d2, fmax(r2, 1e-12));
    if (v3_dot(ref->n, ref->n) > 0.0) {
        double cos_i = fabs(v3_dot(wi, ref->n)), sin_i = safe_sqrt(1.0 - cos_i * cos_i);
        imp *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
    }
    return fmax(imp, 0.0);
}

/* ------------------------------------------------------------------ build */

/* The cone holding both cones (pbrt-v4's DirectionCone union). */
static void cone_union(vec3 wa, double cos_a, vec3 wb, double cos_b, vec3 *w, double *cos_o)
{
    *w = v3(0.0, 0.0, 1.0), *cos_o = -1.0;
    if (cos_a <= -1.0 || cos_b <= -1.0)
        return;
    double ta = acos(fmin(1.0, cos_a)), tb = acos(fmin(1.0, cos_b));
    double td = acos(fmax(-1.0, fmin(1.0, v3_dot(wa, wb))));
    if (fmin(td + tb, M_PI) <= ta) {
        *w = wa, *cos_o = cos_a;
        return;
    }
    if (fmin(td + ta, M_PI) <= tb) {
        *w = wb, *cos_o = cos_b;
        return;
    }
    double to = 0.5 * (ta + td + tb);
    vec3 k = v3_cross(wa, wb);
    if (to >= M_PI || !(v3_len(k) > 1e-12))
        return;
    k = v3_norm(k);
    double tr = to - ta; /* turn wa toward wb by tr about k */
    *w = v3_norm(v3_add(v3_scale(wa, cos(tr)), v3_scale(v3_cross(k, wa), sin(tr))));
    *cos_o = cos(to);
}

static light_bounds bounds_union(const light_bounds *a, const light_bounds *b)
{
    if (a->phi <= 0.0)
        return *b;
    if (b->phi <= 0.0)
        return *a;
    light_bounds u;
    u.infinite = false;
    u.lo = v3(fmin(a->lo.x, b->lo.x), fmin(a->lo.y, b->lo.y), fmin(a->lo.z, b->lo.z));
    u.hi = v3(fmax(a->hi.x, b->hi.x), fmax(a->hi.y, b->hi.y), fmax(a->hi.z, b->hi.z));
    cone_union(a->axis, a->cos_theta_o, b->axis, b->cos_theta_o, &u.axis, &u.cos_theta_o);
    u.cos_theta_e = fmin(a->cos_theta_e, b->cos_theta_e);
    u.phi = a->phi + b->phi;
    return u;
}

/* The split cost of a group: its power, the solid angle measure of its
 * emission (the cone's M_Omega of Estevez & Kulla) and its bounds' area. */
static double group_cost(const light_bounds *b)
{
    double to = acos(fmax(-1.0, fmin(1.0, b->cos_theta_o))), te = acos(fmax(-1.0, fmin(1.0, b->cos_theta_e)));
    double tw = fmin(to + te, M_PI), so = sin(to);
    double m = 2.0 * M_PI * (1.0 - cos(to)) + 0.5 * M_PI * (2.0 * tw * so - cos(to - 2.0 * tw) - 2.0 * to * so + cos(to));
    vec3 e = v3_sub(b->hi, b->lo);
    double area = 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    return b->phi * m * (area + 1e-12);
}

typedef struct {
    light_bounds b;
    int light;
    vec3 centroid;
} build_item;

static double axis_of(vec3 v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }

static int centroid_cmp(const void *pa, const void *pb, void *axis)
{
    const build_item *a = pa, *b = pb;
    double ca = axis_of(a->centroid, *(int *)axis), cb = axis_of(b->centroid, *(int *)axis);
    return (ca > cb) - (ca < cb) ? (ca > cb) - (ca < cb) : a->light - b->light;
}

/* The split of items[0, n) into [0, k) and [k, n) with the least cost
 * after sorting along each axis (light counts are small: an exhaustive
 * sweep). Leaves the items sorted along the chosen axis. */
static int best_split(build_item *items, int n)
{
    double best = INFINITY;
    int best_axis = 0, best_k = n / 2;
    light_bounds *suffix = malloc(sizeof *suffix * (size_t)n);
    if (!suffix)
        return -1;
    for (int axis = 0; axis < 3; axis++) {
        qsort_r(items, (size_t)n, sizeof *items, centroid_cmp, &axis);
        if (axis_of(items[n - 1].centroid, axis) <= axis_of(items[0].centroid, axis))
            continue;
        suffix[n - 1] = items[n - 1].b;
        for (int i = n - 2; i >= 0; i--)
            suffix[i] = bounds_union(&items[i].b, &suffix[i + 1]);
        light_bounds prefix = items[0].b;
        for (int k = 1; k < n; k++) {
            double c = group_cost(&prefix) + group_cost(&suffix[k]);
            if (c < best)
                best = c, best_axis = axis, best_k = k;
            prefix = bounds_union(&prefix, &items[k].b);
        }
    }
    free(suffix);
    qsort_r(items, (size_t)n, sizeof *items, centroid_cmp, &best_axis);
    return best_k;
}

/* Builds the subtree of items[0, n); returns its node index or -1. */
static int build(light_tree *t, build_item *items, int n, int parent)
{
    int id = t->n_nodes++;
    tree_node *node = &t->nodes[id];
    node->parent = parent;
    node->child[0] = node->child[1] = -1;
    if (n == 1) {
        node->b = items[0].b;
        node->light = items[0].light;
        t->leaf_of[items[0].light] = id;
        return id;
    }
    int k = best_split(items, n);
    if (k < 0)
        return -1;
    int left = build(t, items, k, id), right = left < 0 ? -1 : build(t, items + k, n - k, id);
    if (right < 0)
        return -1;
    node = &t->nodes[id]; /* (the array does not move: sized up front) */
    node->child[0] = left, node->child[1] = right;
    node->light = -1;
    node->b = bounds_union(&t->nodes[left].b, &t->nodes[right].b);
    return id;
}

int emitter_list_commit(emitter_list *l)
{
    light_tree_destroy(l->tree);
    light_tree *t = l->tree = calloc(1, sizeof *t);
    int n = l->count;
    build_item *items = malloc(sizeof *items * (size_t)(n > 0 ? n : 1));
    if (!t || !items) {
        free(items);
        return -1;
    }
    t->nodes = malloc(sizeof *t->nodes * (size_t)(2 * n + 1));
    t->leaf_of = malloc(sizeof *t->leaf_of * (size_t)(n + 1));
    t->inf_phi = calloc((size_t)n + 1, sizeof *t->inf_phi);
    if (!t->nodes || !t->leaf_of || !t->inf_phi) {
        free(items);
        return -1;
    }
    int finite = 0;
    for (int i = 0; i < n; i++) {
        light_bounds b;
        emitter_bounds(l->items[i], &b);
        t->leaf_of[i] = -1;
        if (!(b.phi > 0.0) || !isfinite(b.phi))
            continue;
        if (b.infinite) {
            t->inf_phi[i] = b.phi;
            t->inf_total += b.phi;
            continue;
        }
        items[finite++] = (build_item){b, i, v3_scale(v3_add(b.lo, b.hi), 0.5)};
    }
    t->root = finite > 0 ? build(t, items, finite, -1) : -1;
    t->only_one = finite == 1 && !(t->inf_total > 0.0);
    free(items);
    return finite > 0 && t->root < 0 ? -1 : 0;
}

void light_tree_destroy(light_tree *t)
{
    if (!t)
        return;
    free(t->nodes);
    free(t->leaf_of);
    free(t->inf_phi);
    free(t);
}

/* ------------------------------------------------------------------ pick */

static double below_one(double u) { return u < 0x1.fffffffffffffp-1 ? u : 0x1.fffffffffffffp-1; }

const emitter_t *emitter_list_only(const emitter_list *l)
{
    const light_tree *t = l->tree;
    return t && t->only_one ? l->items[t->nodes[t->root].light] : NULL;
}

/* With one light to pick, picking it where it cannot shine costs nothing
 * its sampler would not refuse anyway: no importance is computed. */
const emitter_t *emitter_list_pick(const emitter_list *l, const emitter_ref *ref, double u, double *pmf,
                                   double *u_reuse)
{
    const light_tree *t = l->tree;
    *pmf = t->only_one ? 1.0 : 0.0;
    *u_reuse = u;
    if (t->only_one)
        return l->items[t->nodes[t->root].light];
    double tree = t->root >= 0 ? importance(&t->nodes[t->root].b, ref) : 0.0, total = tree + t->inf_total;
    if (!(total > 0.0))
        return NULL;
    double p_inf = t->inf_total / total;
    if (u < p_inf) {
        double acc = 0.0, x = u * total;
        int last = -1;
        for (int i = 0; i < l->count; i++) {
            if (!(t->inf_phi[i] > 0.0))
                continue;
            last = i;
            if (x < (acc += t->inf_phi[i]))
                break;
        }
        *pmf = t->inf_phi[last] / total;
        *u_reuse = below_one(fmax(0.0, x - (acc - t->inf_phi[last])) / t->inf_phi[last]);
        return l->items[last];
    }
    u = below_one((u - p_inf) / (1.0 - p_inf));
    double p = tree / total;
    int node = t->root;
    while (t->nodes[node].child[0] >= 0) {
        const tree_node *nd = &t->nodes[node];
        double i0 = importance(&t->nodes[nd->child[0]].b, ref), i1 = importance(&t->nodes[nd->child[1]].b, ref);
        if (!(i0 + i1 > 0.0))
            return NULL;
        double p0 = i0 / (i0 + i1), p1 = i1 / (i0 + i1); /* as emitter_list_pmf has them */
        if (u < p0) {
            u = below_one(u / p0), p *= p0, node = nd->child[0];
        } else {
            u = below_one((u - p0) / p1), p *= p1, node = nd->child[1];
        }
    }
    *pmf = p;
    *u_reuse = u;
    return l->items[t->nodes[node].light];
}

double emitter_list_pmf(const emitter_list *l, const emitter_ref *ref, const emitter_t *e)
{
    const light_tree *t = l->tree;
    int node = t->leaf_of[e->index];
    if (node < 0 && !(t->inf_phi[e->index] > 0.0))
        return 0.0; /* never picked: no importance needed */
    if (t->only_one)
        return 1.0;
    double tree = t->root >= 0 ? importance(&t->nodes[t->root].b, ref) : 0.0, total = tree + t->inf_total;
    if (!(total > 0.0))
        return 0.0;
    if (node < 0)
        return t->inf_phi[e->index] / total;
    double p = tree / total;
    for (int parent = t->nodes[node].parent; parent >= 0; node = parent, parent = t->nodes[node].parent) {
        const tree_node *pn = &t->nodes[parent];
        double i0 = importance(&t->nodes[pn->child[0]].b, ref), i1 = importance(&t->nodes[pn->child[1]].b, ref);
        double mine = pn->child[0] == node ? i0 : i1;
        if (!(mine > 0.0))
            return 0.0;
        p *= mine / (i0 + i1);
    }
    return p;
}
