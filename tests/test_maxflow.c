/* The Boykov–Kolmogorov min-cut (src/segment/maxflow.c) against independent
 * truth: every one of the 2^n cuts of small random graphs (the minimum value,
 * and the smallest source side among the minimum cuts, which is what the
 * solver promises on ties), and a plain Edmonds–Karp written here on larger
 * random grids and dense graphs (the flow value, and the set of nodes
 * reachable from the source in its residual graph, which is the same set for
 * every maximum flow). The value of the cut the solver returns is recomputed
 * from its sides each time (max-flow = min-cut). */
#include <criterion/criterion.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "segment/maxflow.h"
#include "support/counted_check.h"

static uint64_t rng_state;
static uint32_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (uint32_t)(rng_state >> 16);
}
static int rnd_int(int lo, int hi) /* in [lo, hi] */
{
    return lo + (int)(rnd() % (uint32_t)(hi - lo + 1));
}
static double rnd_unit(void)
{
    return rnd() / 4294967296.0;
}

/* A test graph, kept as plain lists so that the references and the cut value
 * need nothing from the solver. */
typedef struct {
    int n, m;
    double *cs, *ct; /* t-links: source -> v, v -> sink */
    int *ei, *ej;
    double *cij, *cji;
} test_graph;

static test_graph graph_alloc(int n, int max_edges)
{
    test_graph t = {n, 0, calloc((size_t)n + 1, sizeof(double)), calloc((size_t)n + 1, sizeof(double)),
                    malloc(((size_t)max_edges + 1) * sizeof(int)), malloc(((size_t)max_edges + 1) * sizeof(int)),
                    malloc(((size_t)max_edges + 1) * sizeof(double)), malloc(((size_t)max_edges + 1) * sizeof(double))};
    cr_assert(t.cs && t.ct && t.ei && t.ej && t.cij && t.cji);
    return t;
}

static void graph_free(test_graph *t)
{
    free(t->cs);
    free(t->ct);
    free(t->ei);
    free(t->ej);
    free(t->cij);
    free(t->cji);
}

static void graph_edge(test_graph *t, int i, int j, double cij, double cji)
{
    t->ei[t->m] = i;
    t->ej[t->m] = j;
    t->cij[t->m] = cij;
    t->cji[t->m] = cji;
    t->m++;
}

/* A capacity: zero with probability p_zero, else an integer in 1..max (or a
 * real in (0, max] when real). */
static double rnd_cap(double p_zero, int max, int real)
{
    if (rnd_unit() < p_zero)
        return 0;
    return real ? max * (1 - rnd_unit()) : rnd_int(1, max);
}

/* The value of the cut whose source side is side[v] != 0. */
static double cut_value(const test_graph *t, const unsigned char *side)
{
    double c = 0;
    for (int v = 0; v < t->n; v++)
        c += side[v] ? t->ct[v] : t->cs[v];
    for (int e = 0; e < t->m; e++) {
        if (side[t->ei[e]] && !side[t->ej[e]])
            c += t->cij[e];
        if (side[t->ej[e]] && !side[t->ei[e]])
            c += t->cji[e];
    }
    return c;
}

/* Builds the graph into the solver (t-links split over two calls for some
 * nodes, to exercise the adding up) and solves it; side[] gets the result. */
static double solve(maxflow_graph *g, const test_graph *t, unsigned char *side)
{
    for (int v = 0; v < t->n; v++) {
        if (v % 3 == 1) {
            maxflow_add_terminals(g, v, 0.5 * t->cs[v], 0);
            maxflow_add_terminals(g, v, t->cs[v] - 0.5 * t->cs[v], t->ct[v]);
        } else if (t->cs[v] != 0 || t->ct[v] != 0) {
            maxflow_add_terminals(g, v, t->cs[v], t->ct[v]);
        }
    }
    for (int e = 0; e < t->m; e++)
        maxflow_add_edge(g, t->ei[e], t->ej[e], t->cij[e], t->cji[e]);
    double flow = maxflow_solve(g);
    for (int v = 0; v < t->n; v++)
        side[v] = (unsigned char)maxflow_source_side(g, v);
    return flow;
}

static double solve_fresh(const test_graph *t, unsigned char *side)
{
    maxflow_graph *g = maxflow_create(t->n, t->m);
    cr_assert_not_null(g);
    double flow = solve(g, t, side);
    maxflow_destroy(g);
    return flow;
}

/* ---- brute force: every cut of an integer-capacity graph, in Gray-code
 * order (one node changes side per step), with exact integer sums. */

typedef struct {
    int64_t min_value;
    uint32_t smallest_side; /* intersection of the source sides of all minimum cuts */
} brute_result;

static brute_result brute_force(const test_graph *t)
{
    int n = t->n;
    int64_t w[14][14] = {{0}}; /* w[u][v]: capacity u -> v */
    for (int e = 0; e < t->m; e++) {
        w[t->ei[e]][t->ej[e]] += (int64_t)t->cij[e];
        w[t->ej[e]][t->ei[e]] += (int64_t)t->cji[e];
    }
    uint32_t side = 0;
    int64_t value = 0;
    for (int v = 0; v < n; v++)
        value += (int64_t)t->cs[v];
    brute_result r = {value, 0};
    for (uint32_t k = 1; k < (1u << n); k++) {
        int v = __builtin_ctz(k);
        int joins = !(side >> v & 1);
        /* v moves to the source side (joins) or back: its t-link and its
         * links to the other nodes change whether they are cut */
        int64_t d = (int64_t)t->ct[v] - (int64_t)t->cs[v];
        for (int u = 0; u < n; u++) {
            if (u == v)
                continue;
            d += (side >> u & 1) ? -w[u][v] : w[v][u];
        }
        value += joins ? d : -d;
        side ^= 1u << v;
        if (value < r.min_value) {
            r.min_value = value;
            r.smallest_side = side;
        } else if (value == r.min_value) {
            r.smallest_side &= side;
        }
    }
    return r;
}

/* A random graph of n <= 14 nodes: density, zero capacities and both t-links
 * vary; part of the graphs split into two unlinked halves; some pairs are
 * linked twice. */
static test_graph random_small_graph(int n, int real)
{
    test_graph t = graph_alloc(n, 2 * n * n);
    double density = rnd_unit();
    double p_zero = 0.4 * rnd_unit();
    int split = rnd_int(0, 2) == 0 ? rnd_int(1, n) : n; /* nodes < split and >= split never link */
    for (int v = 0; v < n; v++) {
        t.cs[v] = rnd_cap(0.5, 20, real);
        t.ct[v] = rnd_cap(0.5, 20, real);
    }
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++) {
            if ((i < split) != (j < split) || rnd_unit() >= density)
                continue;
            int reps = rnd_int(0, 5) == 0 ? 2 : 1;
            for (int k = 0; k < reps; k++)
                graph_edge(&t, i, j, rnd_cap(p_zero, 10, real), rnd_cap(p_zero, 10, real));
        }
    return t;
}

Test(maxflow, every_cut_of_small_integer_graphs)
{
    rng_state = 0x243f6a8885a308d3u;
    unsigned char side[14];
    int graphs = 0;
    for (int n = 1; n <= 14; n++) {
        int count = n <= 10 ? 300 : 60;
        for (int s = 0; s < count; s++, graphs++) {
            test_graph t = random_small_graph(n, 0);
            brute_result b = brute_force(&t);
            double flow = solve_fresh(&t, side);
            uint32_t ours = 0;
            for (int v = 0; v < n; v++)
                ours |= (uint32_t)side[v] << v;
            unsigned char smallest[14];
            for (int v = 0; v < n; v++)
                smallest[v] = b.smallest_side >> v & 1;
            CHECK(flow == (double)b.min_value, "n=%d graph %d: flow %g, brute-force minimum %lld", n, s, flow,
                  (long long)b.min_value);
            CHECK(cut_value(&t, side) == flow, "n=%d graph %d: cut %g != flow %g", n, s, cut_value(&t, side), flow);
            CHECK(ours == b.smallest_side, "n=%d graph %d: source side %#x, smallest minimum cut %#x", n, s, ours,
                  b.smallest_side);
            /* minimum cuts are closed under intersection: checks the brute force */
            CHECK(cut_value(&t, smallest) == (double)b.min_value, "n=%d graph %d: intersection is no minimum", n, s);
            graph_free(&t);
        }
    }
    cr_assert_eq(failures, 0, "%d of %d graphs disagree with the brute force", failures, graphs);
}

/* Real capacities: ties have probability zero, the sums round. */
Test(maxflow, every_cut_of_small_real_graphs)
{
    rng_state = 0x13198a2e03707344u;
    unsigned char side[12], s_side[12];
    for (int n = 1; n <= 12; n++)
        for (int s = 0; s < 100; s++) {
            test_graph t = random_small_graph(n, 1);
            double best = INFINITY;
            for (uint32_t k = 0; k < (1u << n); k++) {
                for (int v = 0; v < n; v++)
                    s_side[v] = k >> v & 1;
                best = fmin(best, cut_value(&t, s_side));
            }
            double flow = solve_fresh(&t, side);
            double tol = 1e-12 * (1 + best);
            CHECK(fabs(flow - best) <= tol, "n=%d graph %d: flow %.17g, brute-force minimum %.17g", n, s, flow, best);
            CHECK(fabs(cut_value(&t, side) - best) <= tol, "n=%d graph %d: cut %.17g, minimum %.17g", n, s,
                  cut_value(&t, side), best);
            graph_free(&t);
        }
    cr_assert_eq(failures, 0);
}

/* ---- Edmonds–Karp: shortest augmenting paths by breadth-first search on
 * linked adjacency lists, source n, sink n + 1. */

typedef struct {
    int n;          /* nodes incl. the terminals */
    int *head, *next, *first_arc;
    double *rcap;   /* arc a and a ^ 1 are each other's reverse */
    int arcs;
} ek_graph;

static void ek_arc_pair(ek_graph *k, int u, int v, double cuv, double cvu)
{
    int a = k->arcs;
    k->head[a] = v;
    k->rcap[a] = cuv;
    k->next[a] = k->first_arc[u];
    k->first_arc[u] = a;
    k->head[a + 1] = u;
    k->rcap[a + 1] = cvu;
    k->next[a + 1] = k->first_arc[v];
    k->first_arc[v] = a + 1;
    k->arcs += 2;
}

/* Max-flow value; reach[v] = 1 for the nodes 0..n-1 reachable from the
 * source in the final residual graph. eps: residuals at or below it count as
 * saturated (0 for integers). */
static double edmonds_karp(const test_graph *t, double eps, unsigned char *reach)
{
    int n = t->n, s = n, snk = n + 1, max_arcs = 2 * (2 * n + t->m);
    ek_graph k = {n + 2, malloc((size_t)max_arcs * sizeof(int)), malloc((size_t)max_arcs * sizeof(int)),
                  malloc((size_t)(n + 2) * sizeof(int)), malloc((size_t)max_arcs * sizeof(double)), 0};
    int *pred = malloc((size_t)(n + 2) * sizeof(int)), *bfs = malloc((size_t)(n + 2) * sizeof(int));
    cr_assert(k.head && k.next && k.first_arc && k.rcap && pred && bfs);
    for (int v = 0; v < n + 2; v++)
        k.first_arc[v] = -1;
    for (int v = 0; v < n; v++) {
        ek_arc_pair(&k, s, v, t->cs[v], 0);
        ek_arc_pair(&k, v, snk, t->ct[v], 0);
    }
    for (int e = 0; e < t->m; e++)
        ek_arc_pair(&k, t->ei[e], t->ej[e], t->cij[e], t->cji[e]);
    double flow = 0;
    for (;;) {
        for (int v = 0; v < n + 2; v++)
            pred[v] = -2;
        pred[s] = -1;
        int qh = 0, qt = 0;
        bfs[qt++] = s;
        while (qh < qt && pred[snk] == -2) {
            int u = bfs[qh++];
            for (int a = k.first_arc[u]; a >= 0; a = k.next[a])
                if (k.rcap[a] > eps && pred[k.head[a]] == -2) {
                    pred[k.head[a]] = a;
                    bfs[qt++] = k.head[a];
                }
        }
        if (pred[snk] == -2) {
            for (int v = 0; v < n; v++)
                reach[v] = pred[v] != -2;
            break;
        }
        double b = INFINITY;
        for (int v = snk; v != s; v = k.head[pred[v] ^ 1])
            b = fmin(b, k.rcap[pred[v]]);
        for (int v = snk; v != s; v = k.head[pred[v] ^ 1]) {
            k.rcap[pred[v]] -= b;
            k.rcap[pred[v] ^ 1] += b;
        }
        flow += b;
    }
    free(k.head);
    free(k.next);
    free(k.first_arc);
    free(k.rcap);
    free(pred);
    free(bfs);
    return flow;
}

/* A w x h grid, 4- or 8-connected, GrabCut-like: every pixel has t-links
 * (often both, some none), n-links in both directions (some asymmetric, some
 * zero), plus `extra` long-range links between random pixels (the mirror
 * links of a symmetry prior). */
static test_graph random_grid(int w, int h, int connectivity, int extra, int real)
{
    int n = w * h;
    test_graph t = graph_alloc(n, 4 * n + extra);
    const int off[4][2] = {{1, 0}, {0, 1}, {1, 1}, {-1, 1}};
    for (int v = 0; v < n; v++) {
        t.cs[v] = rnd_cap(0.3, 60, real);
        t.ct[v] = rnd_cap(0.3, 60, real);
    }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int d = 0; d < (connectivity == 8 ? 4 : 2); d++) {
                int qx = x + off[d][0], qy = y + off[d][1];
                if (qx < 0 || qx >= w || qy >= h)
                    continue;
                double c = rnd_cap(0.1, 30, real);
                double c_back = rnd_unit() < 0.2 ? rnd_cap(0.1, 30, real) : c;
                graph_edge(&t, y * w + x, qy * w + qx, c, c_back);
            }
    for (int e = 0; e < extra; e++)
        graph_edge(&t, rnd_int(0, n - 1), rnd_int(0, n - 1), rnd_cap(0.1, 20, real), rnd_cap(0.1, 20, real));
    return t;
}

static void check_against_edmonds_karp(const test_graph *t, int real, const char *what)
{
    int n = t->n;
    unsigned char *side = malloc((size_t)n), *reach = malloc((size_t)n);
    cr_assert(side && reach);
    double flow = solve_fresh(t, side);
    double ek = edmonds_karp(t, real ? 1e-9 : 0, reach);
    double tol = real ? 1e-9 * (1 + ek) : 0;
    CHECK(fabs(flow - ek) <= tol, "%s: flow %.17g, Edmonds-Karp %.17g", what, flow, ek);
    CHECK(fabs(cut_value(t, side) - flow) <= tol, "%s: cut %.17g != flow %.17g", what, cut_value(t, side), flow);
    if (!real) {
        int differ = 0;
        for (int v = 0; v < n; v++)
            differ += side[v] != reach[v];
        CHECK(differ == 0, "%s: %d nodes differ from the residual-reachable set", what, differ);
    }
    free(side);
    free(reach);
}

Test(maxflow, grids_against_edmonds_karp)
{
    rng_state = 0xa4093822299f31d0u;
    char what[96];
    int cases = 0;
    for (int s = 0; s < 12; s++)
        for (int conn = 4; conn <= 8; conn += 4)
            for (int real = 0; real <= 1; real++, cases++) {
                int w = rnd_int(5, 40), h = rnd_int(5, 40);
                int extra = s % 2 ? w * h / 2 : 0;
                test_graph t = random_grid(w, h, conn, extra, real);
                snprintf(what, sizeof what, "%dx%d %d-connected, %d long links, %s caps (case %d)", w, h, conn, extra,
                         real ? "real" : "integer", cases);
                check_against_edmonds_karp(&t, real, what);
                graph_free(&t);
            }
    cr_assert_eq(failures, 0, "%d failures in %d grids", failures, cases);
}

/* Dense graphs make long augmenting paths and many orphans. */
Test(maxflow, dense_graphs_against_edmonds_karp)
{
    rng_state = 0x082efa98ec4e6c89u;
    char what[64];
    for (int s = 0; s < 10; s++) {
        int n = rnd_int(50, 150);
        test_graph t = graph_alloc(n, n * n);
        double density = 0.05 + 0.5 * rnd_unit();
        for (int v = 0; v < n; v++) {
            t.cs[v] = rnd_cap(0.8, 100, 0);
            t.ct[v] = rnd_cap(0.8, 100, 0);
        }
        for (int i = 0; i < n; i++)
            for (int j = i + 1; j < n; j++)
                if (rnd_unit() < density)
                    graph_edge(&t, i, j, rnd_cap(0.3, 15, 0), rnd_cap(0.3, 15, 0));
        snprintf(what, sizeof what, "dense graph %d, n=%d, %d links", s, n, t.m);
        check_against_edmonds_karp(&t, 0, what);
        graph_free(&t);
    }
    cr_assert_eq(failures, 0);
}

Test(maxflow, reset_and_reuse_give_the_same_cut)
{
    rng_state = 0xbe5466cf34e90c6cu;
    test_graph a = random_grid(30, 20, 8, 100, 0), b = random_grid(30, 20, 8, 100, 0);
    int n = a.n, m = a.m > b.m ? a.m : b.m;
    unsigned char *fresh_a = malloc((size_t)n), *fresh_b = malloc((size_t)n), *side = malloc((size_t)n);
    cr_assert(fresh_a && fresh_b && side);
    double flow_a = solve_fresh(&a, fresh_a), flow_b = solve_fresh(&b, fresh_b);
    cr_assert_neq(flow_a, flow_b, "the two graphs must differ for the test to mean anything");

    maxflow_graph *g = maxflow_create(n, m);
    cr_assert_not_null(g);
    cr_expect_eq(solve(g, &a, side), flow_a);
    cr_expect_eq(maxflow_solve(g), flow_a, "a second solve returns the same flow");
    maxflow_reset(g);
    cr_expect_eq(solve(g, &b, side), flow_b, "after reset, another graph");
    cr_expect_eq(memcmp(side, fresh_b, (size_t)n), 0);
    maxflow_reset(g);
    cr_expect_eq(solve(g, &a, side), flow_a, "after reset, the first graph again");
    cr_expect_eq(memcmp(side, fresh_a, (size_t)n), 0);

    /* the same n-links with b's t-links: the n-links are kept as added, not
     * as the last solve left them */
    test_graph mixed = a;
    mixed.cs = b.cs;
    mixed.ct = b.ct;
    unsigned char *fresh_mixed = malloc((size_t)n);
    cr_assert_not_null(fresh_mixed);
    double flow_mixed = solve_fresh(&mixed, fresh_mixed);
    maxflow_reset_terminals(g);
    for (int v = 0; v < n; v++)
        maxflow_add_terminals(g, v, b.cs[v], b.ct[v]);
    cr_expect_eq(maxflow_solve(g), flow_mixed, "reset_terminals keeps the n-links");
    for (int v = 0; v < n; v++)
        side[v] = (unsigned char)maxflow_source_side(g, v);
    cr_expect_eq(memcmp(side, fresh_mixed, (size_t)n), 0);
    /* a's t-links again: the kept n-links lose the last solve's flow */
    maxflow_reset_terminals(g);
    for (int v = 0; v < n; v++)
        maxflow_add_terminals(g, v, a.cs[v], a.ct[v]);
    cr_expect_eq(maxflow_solve(g), flow_a, "reset_terminals twice");
    for (int v = 0; v < n; v++)
        side[v] = (unsigned char)maxflow_source_side(g, v);
    cr_expect_eq(memcmp(side, fresh_a, (size_t)n), 0);
    maxflow_destroy(g);

    /* n-links added after reset_terminals join the kept ones */
    test_graph more = random_grid(30, 20, 8, 150, 0);
    unsigned char *fresh_more = malloc((size_t)n);
    cr_assert_not_null(fresh_more);
    double flow_more = solve_fresh(&more, fresh_more);
    cr_assert_gt(more.m, a.m);
    g = maxflow_create(n, more.m);
    cr_assert_not_null(g);
    test_graph head = more;
    head.m = a.m; /* more's first a.m links, then the rest after a reset */
    solve(g, &head, side);
    maxflow_reset_terminals(g);
    for (int v = 0; v < n; v++)
        maxflow_add_terminals(g, v, more.cs[v], more.ct[v]);
    for (int e = a.m; e < more.m; e++)
        maxflow_add_edge(g, more.ei[e], more.ej[e], more.cij[e], more.cji[e]);
    cr_expect_eq(maxflow_solve(g), flow_more, "links added after reset_terminals");
    for (int v = 0; v < n; v++)
        side[v] = (unsigned char)maxflow_source_side(g, v);
    cr_expect_eq(memcmp(side, fresh_more, (size_t)n), 0);
    maxflow_destroy(g);
    free(fresh_a);
    free(fresh_b);
    free(fresh_mixed);
    free(fresh_more);
    free(side);
    graph_free(&a);
    graph_free(&b);
    graph_free(&more);
}

Test(maxflow, degenerate_graphs)
{
    maxflow_graph *g = maxflow_create(0, 0);
    cr_assert_not_null(g);
    cr_expect_eq(maxflow_solve(g), 0, "no nodes");
    maxflow_destroy(g);
    cr_expect_null(maxflow_create(1, INT_MAX / 2 + 1), "more links than int arc indices reach");

    /* one node: the cheaper t-link is cut; equal ones tie (sink side) */
    const double caps[][3] = {{3, 5, 0}, {5, 3, 1}, {0, 0, 0}, {4, 4, 0}, {0, 7, 0}, {7, 0, 1}};
    g = maxflow_create(1, 1);
    cr_assert_not_null(g);
    for (int k = 0; k < 6; k++) {
        maxflow_reset(g);
        maxflow_add_terminals(g, 0, caps[k][0], caps[k][1]);
        maxflow_add_edge(g, 0, 0, 9, 9); /* a self-link is never cut */
        cr_expect_eq(maxflow_solve(g), fmin(caps[k][0], caps[k][1]), "one node, caps %g %g", caps[k][0], caps[k][1]);
        cr_expect_eq(maxflow_source_side(g, 0), (int)caps[k][2], "one node, caps %g %g", caps[k][0], caps[k][1]);
    }
    maxflow_destroy(g);

    /* links but all capacities zero: nothing flows, every node ties */
    g = maxflow_create(50, 100);
    cr_assert_not_null(g);
    for (int v = 0; v < 50; v++) {
        maxflow_add_terminals(g, v, 0, 0);
        maxflow_add_edge(g, v, (v + 1) % 50, 0, 0);
        maxflow_add_edge(g, v, (v * 7) % 50, 0, 0);
    }
    cr_expect_eq(maxflow_solve(g), 0);
    for (int v = 0; v < 50; v++)
        cr_expect_eq(maxflow_source_side(g, v), 0, "node %d", v);

    /* no links between nodes: each node alone */
    maxflow_reset(g);
    double expect = 0;
    for (int v = 0; v < 50; v++) {
        maxflow_add_terminals(g, v, v % 7, v % 5);
        expect += fmin(v % 7, v % 5);
    }
    cr_expect_eq(maxflow_solve(g), expect);
    for (int v = 0; v < 50; v++)
        cr_expect_eq(maxflow_source_side(g, v), v % 7 > v % 5, "node %d", v);
    maxflow_destroy(g);
}
