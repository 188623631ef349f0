/* Boykov–Kolmogorov max-flow (Boykov & Kolmogorov, "An experimental
 * comparison of min-cut/max-flow algorithms for energy minimization in
 * vision", PAMI 2004): a search tree S grows from the source and a tree T
 * from the sink through unsaturated links; where they touch, the path
 * source..S..T..sink is augmented by its bottleneck; the nodes cut off from
 * their tree by a saturated link (orphans) look for a new parent in their
 * tree with a valid origin, or become free. It stops when no active node can
 * grow: S is then exactly the set of nodes reachable from the source.
 *
 * Layout: the n-links are kept as added (edges[]) and laid out at solve time
 * as arcs sorted by their tail (first[i] .. first[i+1]), each arc with the
 * index of its reverse arc; a node's links are contiguous in memory. A
 * round after maxflow_reset_terminals lays the arcs out again from edges[]
 * (the same layout): a copy of every arc's first capacity would save that
 * counting sort but add 16 bytes an edge that the segmentation, which
 * solves each graph once or goes on from its flow, pays for in fresh pages
 * at every call. A t-link pair is held as one signed residual (tr_cap > 0:
 * source -> node, < 0: node -> sink) after pushing min(cap_source, cap_sink)
 * straight through.
 *
 * A solved graph can take new t-links (maxflow_set_terminals) and be solved
 * again from its flow and search trees, as Kohli & Torr's dynamic graph cuts
 * do (PAMI 2007) and as Kolmogorov's implementation reuses its trees: a
 * node's signed residual moves by the change of its net capacity (a residual
 * beyond the new capacity only adds a constant to both of its t-links, which
 * no cut notices), a node whose residual changed sign changes trees, one
 * whose terminal link vanished becomes an orphan, and the search goes on
 * from the changed nodes. The minimum cut, and so the source side, does not
 * depend on which maximum flow is reached.
 *
 * Capacities are doubles, not floats: float arcs (12 bytes instead of 16)
 * were no faster on the benchmark's graphs (the search waits on scattered
 * nodes, not on arc bytes), and doubles keep integer capacities exact up to
 * 2^53 and the flow, a sum of ~1e5 terms, to ~1e-16 instead of ~1e-8. A
 * bottleneck subtracted from itself leaves an exact zero either way, so a
 * saturated link is recognised exactly. */
#include "segment/maxflow.h"

#include <assert.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>

/* values of mf_node.parent other than an arc index */
enum { PARENT_NONE = -1, PARENT_TERMINAL = -2, PARENT_ORPHAN = -3 };

typedef struct {
    int head;    /* the node the arc points to */
    int sister;  /* the reverse arc */
    double rcap; /* residual capacity, >= 0 */
} mf_arc;

typedef struct {
    double tr_cap; /* residual t-link: > 0 from the source, < 0 to the sink */
    int parent;    /* arc from this node to its parent in its tree, or PARENT_* */
    int pnode;     /* the parent node when parent is an arc (its head: walks up a tree need no arc) */
    int ts;        /* the augmentation count at which dist was last known exact */
    int dist;      /* links to the tree's terminal (valid at ts) */
    unsigned char in_sink_tree;
    unsigned char queued; /* in the active queue */
} mf_node;

typedef struct {
    int i, j;
    double cap_ij, cap_ji;
} mf_edge;

/* A FIFO of node indices; each node is in it at most once, so n slots do. */
typedef struct {
    int *slot;
    int size, head, count;
} mf_queue;

struct maxflow_graph {
    int n, max_edges, n_edges;
    int n_cap, max_edges_cap; /* what its buffers hold (a spare graph is reused for fewer) */
    mf_node *nodes;
    mf_edge *edges;
    int *first; /* n + 1 */
    mf_arc *arcs;
    mf_queue active, orphans;
    double *tcap;  /* per node: the source and the sink capacity as given (for the flow's value) */
    int *changed;  /* nodes whose t-links maxflow_set_terminals changed since the last solve */
    int n_changed;
    unsigned char *is_changed;
    double flow;
    int time;
    int solved; /* the flow is maximal for the links as they are */
    int trees;  /* the search trees hold a solve's state: maxflow_set_terminals may follow */
};

static void queue_push(mf_queue *q, int v)
{
    int k = q->head + q->count++;
    q->slot[k >= q->size ? k - q->size : k] = v;
}

static int queue_pop(mf_queue *q)
{
    int v = q->slot[q->head];
    q->head = q->head + 1 == q->size ? 0 : q->head + 1;
    q->count--;
    return v;
}

static void graph_free(maxflow_graph *g)
{
    if (!g)
        return;
    free(g->nodes);
    free(g->edges);
    free(g->first);
    free(g->arcs);
    free(g->active.slot);
    free(g->orphans.slot);
    free(g->tcap);
    free(g->changed);
    free(g->is_changed);
    free(g);
}

/* Graphs given back by maxflow_destroy, kept for the thread's next
 * maxflow_create: a photo's segmentation builds three graphs of a few MB,
 * and fresh pages for them cost about a fifth of its CPU time (in the
 * kernel). A thread keeps the SPARES largest, freed when it exits. */
enum { SPARES = 2 };
typedef struct {
    maxflow_graph *g[SPARES];
} spare_graphs;

static tss_t spare_key;
static int spare_key_ok;
static once_flag spare_once = ONCE_FLAG_INIT;

static void spares_free(void *p)
{
    spare_graphs *s = p;
    for (int k = 0; k < SPARES; k++)
        graph_free(s->g[k]);
    free(s);
}

static void spare_key_create(void) { spare_key_ok = tss_create(&spare_key, spares_free) == thrd_success; }

/* The thread's spare graphs, or NULL (no key, out of memory). */
static spare_graphs *thread_spares(void)
{
    call_once(&spare_once, spare_key_create);
    if (!spare_key_ok)
        return NULL;
    spare_graphs *s = tss_get(spare_key);
    if (!s && (s = calloc(1, sizeof *s)) != NULL && tss_set(spare_key, s) != thrd_success) {
        free(s);
        s = NULL;
    }
    return s;
}

/* The smallest spare graph with room for n nodes and m edges, taken out of
 * s, or NULL. */
static maxflow_graph *take_spare(spare_graphs *s, int n, int m)
{
    int best = -1;
    for (int k = 0; k < SPARES; k++)
        if (s->g[k] && s->g[k]->n_cap >= n && s->g[k]->max_edges_cap >= m &&
            (best < 0 || s->g[k]->max_edges_cap < s->g[best]->max_edges_cap))
            best = k;
    if (best < 0)
        return NULL;
    maxflow_graph *g = s->g[best];
    s->g[best] = NULL;
    return g;
}

maxflow_graph *maxflow_create(int n_nodes, int max_edges)
{
    assert(n_nodes >= 0 && max_edges >= 0);
    if (max_edges > INT_MAX / 2) /* arcs are indexed by int */
        return NULL;
    spare_graphs *s = thread_spares();
    maxflow_graph *g = s ? take_spare(s, n_nodes, max_edges) : NULL;
    if (!g) {
        if (!(g = calloc(1, sizeof *g)))
            return NULL;
        g->n_cap = n_nodes;
        g->max_edges_cap = max_edges;
        /* +1: malloc(0) may return NULL */
        g->nodes = malloc(((size_t)n_nodes + 1) * sizeof *g->nodes);
        g->edges = malloc(((size_t)max_edges + 1) * sizeof *g->edges);
        g->first = malloc(((size_t)n_nodes + 1) * sizeof *g->first);
        g->arcs = malloc((2 * (size_t)max_edges + 1) * sizeof *g->arcs);
        g->active.slot = malloc(((size_t)n_nodes + 1) * sizeof(int));
        g->orphans.slot = malloc(((size_t)n_nodes + 1) * sizeof(int));
        g->tcap = malloc(((size_t)n_nodes + 1) * 2 * sizeof *g->tcap);
        g->changed = malloc(((size_t)n_nodes + 1) * sizeof *g->changed);
        g->is_changed = calloc((size_t)n_nodes + 1, 1);
        if (!g->nodes || !g->edges || !g->first || !g->arcs || !g->active.slot || !g->orphans.slot || !g->tcap ||
            !g->changed || !g->is_changed) {
            graph_free(g);
            return NULL;
        }
    }
    g->n = n_nodes;
    g->max_edges = max_edges;
    g->active.size = g->orphans.size = n_nodes;
    maxflow_reset(g);
    return g;
}

void maxflow_destroy(maxflow_graph *g)
{
    if (!g)
        return;
    spare_graphs *s = thread_spares();
    if (!s) {
        graph_free(g);
        return;
    }
    /* a spare marks no node changed (its next graph may have fewer nodes) */
    for (int k = 0; k < g->n_changed; k++)
        g->is_changed[g->changed[k]] = 0;
    g->n_changed = 0;
    /* keep the SPARES largest: g takes the place of a smaller one, which
     * moves on down the list or is freed */
    for (int k = 0; k < SPARES; k++)
        if (!s->g[k] || s->g[k]->max_edges_cap < g->max_edges_cap) {
            maxflow_graph *t = s->g[k];
            s->g[k] = g;
            if (!(g = t))
                return;
        }
    graph_free(g);
}

void maxflow_reset_terminals(maxflow_graph *g)
{
    for (int i = 0; i < g->n; i++)
        g->nodes[i].tr_cap = 0;
    memset(g->tcap, 0, (size_t)g->n * 2 * sizeof *g->tcap);
    for (int k = 0; k < g->n_changed; k++)
        g->is_changed[g->changed[k]] = 0;
    g->n_changed = 0;
    g->flow = 0;
    g->solved = g->trees = 0;
}

void maxflow_reset(maxflow_graph *g)
{
    maxflow_reset_terminals(g);
    g->n_edges = 0;
}

/* The preconditions the add and set calls assert, in few instructions (they
 * are called for every link): 0 <= node < n; 0 <= cap <= DBL_MAX (NaN fails
 * both comparisons, infinity the second). */
static inline int valid_node(const maxflow_graph *g, int i) { return (unsigned)i < (unsigned)g->n; }
static inline int valid_cap(double c) { return c >= 0 && c <= DBL_MAX; }

void maxflow_add_terminals(maxflow_graph *g, int node, double cap_source, double cap_sink)
{
    assert(!g->trees && valid_node(g, node) && valid_cap(cap_source) && valid_cap(cap_sink));
    /* the node's earlier residual joins the new capacities; the common part
     * of the two flows straight from the source to the sink */
    g->tcap[2 * node] += cap_source;
    g->tcap[2 * node + 1] += cap_sink;
    double r = g->nodes[node].tr_cap;
    if (r > 0)
        cap_source += r;
    else
        cap_sink -= r;
    g->flow += cap_source < cap_sink ? cap_source : cap_sink;
    g->nodes[node].tr_cap = cap_source - cap_sink;
}

void maxflow_add_edge(maxflow_graph *g, int i, int j, double cap_ij, double cap_ji)
{
    assert(!g->trees && valid_node(g, i) && valid_node(g, j) && valid_cap(cap_ij) && valid_cap(cap_ji));
    if (i == j || (cap_ij == 0 && cap_ji == 0))
        return;
    assert(g->n_edges < g->max_edges);
    g->edges[g->n_edges++] = (mf_edge){i, j, cap_ij, cap_ji};
}

void maxflow_set_terminals(maxflow_graph *g, int node, double cap_source, double cap_sink)
{
    assert(g->trees && valid_node(g, node) && valid_cap(cap_source) && valid_cap(cap_sink));
    double *t = g->tcap + 2 * node;
    if (t[0] == cap_source && t[1] == cap_sink)
        return;
    /* The flow through the node's t-links stays; with the straight-through
     * part as large as the capacities allow, the flow's value is the sum
     * over nodes of cap_source - max(residual, 0). */
    mf_node *v = &g->nodes[node];
    double r = v->tr_cap, nr = r + ((cap_source - cap_sink) - (t[0] - t[1]));
    g->flow += (cap_source - (nr > 0 ? nr : 0)) - (t[0] - (r > 0 ? r : 0));
    v->tr_cap = nr;
    g->solved = 0;
    t[0] = cap_source;
    t[1] = cap_sink;
    if (!g->is_changed[node]) {
        g->is_changed[node] = 1;
        g->changed[g->n_changed++] = node;
    }
}

/* Lays the edges out as arcs grouped by tail (a counting sort). */
static void build_arcs(maxflow_graph *g)
{
    int *first = g->first;
    memset(first, 0, ((size_t)g->n + 1) * sizeof *first);
    for (int e = 0; e < g->n_edges; e++) {
        first[g->edges[e].i]++;
        first[g->edges[e].j]++;
    }
    /* first[i] = end of node i's arcs; filling backwards moves it to the start */
    for (int i = 1; i <= g->n; i++)
        first[i] += first[i - 1];
    for (int e = g->n_edges - 1; e >= 0; e--) {
        const mf_edge *ed = &g->edges[e];
        int a = --first[ed->i], b = --first[ed->j];
        g->arcs[a] = (mf_arc){ed->j, b, ed->cap_ij};
        g->arcs[b] = (mf_arc){ed->i, a, ed->cap_ji};
    }
}

/* Every node with a t-link residual is a child of its terminal and active;
 * the rest are free. */
static void init_trees(maxflow_graph *g)
{
    g->active.head = g->active.count = 0;
    g->orphans.head = g->orphans.count = 0;
    g->time = 0;
    for (int i = 0; i < g->n; i++) {
        mf_node *v = &g->nodes[i];
        v->ts = 0;
        v->dist = 1;
        v->queued = 0;
        if (v->tr_cap != 0) {
            v->parent = PARENT_TERMINAL;
            v->in_sink_tree = v->tr_cap < 0;
            v->queued = 1;
            queue_push(&g->active, i);
        } else {
            v->parent = PARENT_NONE;
            v->in_sink_tree = 0;
        }
    }
}

static void activate(maxflow_graph *g, int i)
{
    if (!g->nodes[i].queued) {
        g->nodes[i].queued = 1;
        queue_push(&g->active, i);
    }
}

/* The next active node that is still in a tree, or -1. */
static int next_active(maxflow_graph *g)
{
    while (g->active.count) {
        int i = queue_pop(&g->active);
        g->nodes[i].queued = 0;
        if (g->nodes[i].parent != PARENT_NONE)
            return i;
    }
    return -1;
}

static void make_orphan(maxflow_graph *g, int i)
{
    g->nodes[i].parent = PARENT_ORPHAN;
    queue_push(&g->orphans, i);
}

/* Residual capacity of arc a in the direction a tree grows: away from the
 * source in S, toward the sink in T (where it is the reverse arc's). */
static double grow_cap(const maxflow_graph *g, int a, int sink_tree)
{
    return sink_tree ? g->arcs[g->arcs[a].sister].rcap : g->arcs[a].rcap;
}

/* Growth: node i (in a tree) takes every free neighbour it reaches through an
 * unsaturated arc as a child, and re-parents neighbours of its tree that were
 * farther from the terminal (a shorter path, as in Kolmogorov's
 * implementation). Returns the arc where i's tree touches the other tree,
 * oriented from S to T, or -1. */
static int grow(maxflow_graph *g, int i)
{
    const mf_node *vi = &g->nodes[i];
    const int sink_tree = vi->in_sink_tree;
    for (int a = g->first[i]; a < g->first[i + 1]; a++) {
        if (grow_cap(g, a, sink_tree) <= 0)
            continue;
        mf_node *vj = &g->nodes[g->arcs[a].head];
        if (vj->parent == PARENT_NONE) {
            vj->in_sink_tree = (unsigned char)sink_tree;
            vj->parent = g->arcs[a].sister;
            vj->pnode = i;
            vj->ts = vi->ts;
            vj->dist = vi->dist + 1;
            activate(g, g->arcs[a].head);
        } else if (vj->in_sink_tree != sink_tree) {
            return sink_tree ? g->arcs[a].sister : a;
        } else if (vj->ts <= vi->ts && vj->dist > vi->dist) {
            vj->parent = g->arcs[a].sister;
            vj->pnode = i;
            vj->ts = vi->ts;
            vj->dist = vi->dist + 1;
        }
    }
    return -1;
}

/* fmin is a library call (NaN rules); capacities are never NaN: inlined */
static inline double min2(double a, double b) { return b < a ? b : a; }

/* Augmentation along source -> S .. u -> v .. T -> sink, `mid` the arc u -> v.
 * Nodes whose parent link saturates become orphans. */
static void augment(maxflow_graph *g, int mid)
{
    mf_arc *arcs = g->arcs;
    mf_node *nodes = g->nodes;
    const int u = arcs[arcs[mid].sister].head, v = arcs[mid].head;
    double b = arcs[mid].rcap;
    int i;
    for (i = u; nodes[i].parent != PARENT_TERMINAL; i = nodes[i].pnode)
        b = min2(b, arcs[arcs[nodes[i].parent].sister].rcap);
    b = min2(b, nodes[i].tr_cap);
    for (i = v; nodes[i].parent != PARENT_TERMINAL; i = nodes[i].pnode)
        b = min2(b, arcs[nodes[i].parent].rcap);
    b = min2(b, -nodes[i].tr_cap);

    arcs[mid].rcap -= b;
    arcs[arcs[mid].sister].rcap += b;
    /* In S flow runs parent -> child (the sister of the parent arc), in T
     * child -> parent (the parent arc). The bottleneck leaves an exact 0. */
    for (i = u;;) {
        int p = nodes[i].parent;
        if (p == PARENT_TERMINAL) {
            nodes[i].tr_cap -= b;
            if (nodes[i].tr_cap == 0)
                make_orphan(g, i);
            break;
        }
        int next = nodes[i].pnode;
        arcs[p].rcap += b;
        arcs[arcs[p].sister].rcap -= b;
        if (arcs[arcs[p].sister].rcap == 0)
            make_orphan(g, i);
        i = next;
    }
    for (i = v;;) {
        int p = nodes[i].parent;
        if (p == PARENT_TERMINAL) {
            nodes[i].tr_cap += b;
            if (nodes[i].tr_cap == 0)
                make_orphan(g, i);
            break;
        }
        int next = nodes[i].pnode;
        arcs[arcs[p].sister].rcap += b;
        arcs[p].rcap -= b;
        if (arcs[p].rcap == 0)
            make_orphan(g, i);
        i = next;
    }
    g->flow += b;
}

/* Distance of tree node j from its terminal through parents, or INT_MAX when
 * its chain ends at an orphan. A valid chain is stamped with the current time
 * and exact distances, so later walks stop there. */
static int origin_distance(maxflow_graph *g, int j)
{
    mf_node *nodes = g->nodes;
    int d = 0;
    for (int k = j;; k = nodes[k].pnode) {
        if (nodes[k].ts == g->time) {
            d += nodes[k].dist;
            break;
        }
        if (nodes[k].parent == PARENT_ORPHAN)
            return INT_MAX;
        d++;
        if (nodes[k].parent == PARENT_TERMINAL) {
            nodes[k].ts = g->time;
            nodes[k].dist = 1;
            break;
        }
    }
    int dk = d;
    for (int k = j; nodes[k].ts != g->time; k = nodes[k].pnode) {
        nodes[k].ts = g->time;
        nodes[k].dist = dk--;
    }
    return d;
}

/* Adoption of orphan i: the closest neighbour of its tree with a valid origin
 * and an unsaturated link toward i becomes its parent. Without one, i becomes
 * free: its children become orphans, and its tree's neighbours that could
 * grow into it again become active. */
static void adopt(maxflow_graph *g, int i)
{
    mf_node *vi = &g->nodes[i];
    const int sink_tree = vi->in_sink_tree;
    int best = -1, best_d = INT_MAX;
    /* a neighbour j can be i's parent when it could grow into i: the link
     * j -> i in S, i -> j in T, i.e. the reverse of grow_cap of i's arc */
    for (int a = g->first[i]; a < g->first[i + 1]; a++) {
        if (grow_cap(g, a, !sink_tree) <= 0)
            continue;
        const mf_node *vj = &g->nodes[g->arcs[a].head];
        if (vj->parent == PARENT_NONE || vj->in_sink_tree != sink_tree)
            continue;
        int d = origin_distance(g, g->arcs[a].head);
        if (d < best_d) {
            best_d = d;
            best = a;
        }
    }
    if (best >= 0) {
        vi->parent = best;
        vi->pnode = g->arcs[best].head;
        vi->ts = g->time;
        vi->dist = best_d + 1;
        return;
    }
    vi->parent = PARENT_NONE;
    for (int a = g->first[i]; a < g->first[i + 1]; a++) {
        int j = g->arcs[a].head;
        const mf_node *vj = &g->nodes[j];
        if (vj->parent == PARENT_NONE || vj->in_sink_tree != sink_tree)
            continue;
        if (grow_cap(g, a, !sink_tree) > 0)
            activate(g, j);
        if (vj->parent >= 0 && vj->pnode == i)
            make_orphan(g, j);
    }
}

/* Before a solve that continues from the last one: the nodes whose t-links
 * changed become roots of the tree their residual's sign says (their old
 * tree's children of them orphans) or, without a residual, orphans if they
 * hung on their terminal; each is active. (Kolmogorov's reuse of the trees.) */
static void reuse_trees(maxflow_graph *g)
{
    g->time++;
    for (int k = 0; k < g->n_changed; k++) {
        int i = g->changed[k];
        mf_node *v = &g->nodes[i];
        g->is_changed[i] = 0;
        if (v->tr_cap == 0) {
            if (v->parent == PARENT_TERMINAL)
                make_orphan(g, i);
            continue;
        }
        int sink_tree = v->tr_cap < 0;
        if (v->parent != PARENT_NONE && v->in_sink_tree != sink_tree)
            for (int a = g->first[i]; a < g->first[i + 1]; a++) {
                const mf_node *vj = &g->nodes[g->arcs[a].head];
                if (vj->parent == g->arcs[a].sister)
                    make_orphan(g, g->arcs[a].head);
            }
        v->in_sink_tree = (unsigned char)sink_tree;
        v->parent = PARENT_TERMINAL;
        v->ts = g->time;
        v->dist = 1;
        activate(g, i);
    }
    g->n_changed = 0;
    /* an orphan that a later change made a root is no orphan any more */
    while (g->orphans.count) {
        int i = queue_pop(&g->orphans);
        if (g->nodes[i].parent == PARENT_ORPHAN)
            adopt(g, i);
    }
}

double maxflow_solve(maxflow_graph *g)
{
    if (g->solved)
        return g->flow;
    if (g->trees) {
        reuse_trees(g);
    } else {
        build_arcs(g); /* anew after a reset: the last solve's flow is in the arcs */
        init_trees(g);
    }
    /* A node that found a path stays current: it may touch the other tree
     * through more of its arcs. */
    int current = -1;
    for (;;) {
        int i = current >= 0 && g->nodes[current].parent != PARENT_NONE ? current : next_active(g);
        if (i < 0)
            break;
        int mid = grow(g, i);
        current = mid >= 0 ? i : -1;
        if (mid < 0)
            continue;
        g->time++;
        augment(g, mid);
        while (g->orphans.count)
            adopt(g, queue_pop(&g->orphans));
    }
    g->solved = g->trees = 1;
    return g->flow;
}

int maxflow_source_side(const maxflow_graph *g, int node)
{
    assert(g->solved && valid_node(g, node));
    return g->nodes[node].parent != PARENT_NONE && !g->nodes[node].in_sink_tree;
}
