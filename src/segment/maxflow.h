/* s-t minimum cut of a graph with terminal links, for segmentation
 * (GrabCut-style energies: t-links from colour models, n-links between
 * neighbouring pixels, any other pairwise links). Boykov–Kolmogorov max-flow;
 * docs/algorithms-recon.md ("Min-cut") describes it, its cost and its tests.
 *
 * Usage (one allocation, reused round after round):
 *     maxflow_graph *g = maxflow_create(n, max_edges);
 *     maxflow_add_terminals(g, p, cost_if_sink_side, cost_if_source_side);  (every p that has one)
 *     maxflow_add_edge(g, p, q, cap_pq, cap_qp);                             (each pair once)
 *     double cut = maxflow_solve(g);
 *     ... maxflow_source_side(g, p) ...
 *     maxflow_set_terminals(g, p, ...);  (new t-links, solved again from this flow) or
 *     maxflow_reset_terminals(g);   (same n-links, new t-links) or maxflow_reset(g)
 *     ...
 *     maxflow_destroy(g);
 *
 * Preconditions (checked by assert): node indices in [0, n), capacities
 * finite and >= 0, at most max_edges calls of maxflow_add_edge since the last
 * maxflow_reset (maxflow_reset_terminals keeps the links, so they still
 * count), no additions between maxflow_solve and the next reset
 * (maxflow_set_terminals only after a solve). Capacities are
 * doubles: with integer capacities (below 2^53 in total) the flow and the cut
 * are exact. One graph is used by one thread at a time. */
#ifndef CELADON_SEGMENT_MAXFLOW_H
#define CELADON_SEGMENT_MAXFLOW_H

typedef struct maxflow_graph maxflow_graph;

/* A graph of n_nodes >= 0 nodes (numbered 0..n_nodes-1, no links yet) with
 * room for max_edges >= 0 calls of maxflow_add_edge. NULL when out of memory
 * or when max_edges > INT_MAX / 2.
 * Memory: about 65 * n_nodes + 56 * max_edges bytes (of which the edges
 * added and their nodes are touched), or a spare graph's that had room (see
 * maxflow_destroy). */
maxflow_graph *maxflow_create(int n_nodes, int max_edges);

/* Adds cap_source to the capacity of the link source -> node and cap_sink to
 * that of node -> sink (a cut pays cap_source when the node ends on the sink
 * side, cap_sink when it ends on the source side). Repeated calls add up. */
void maxflow_add_terminals(maxflow_graph *g, int node, double cap_source, double cap_sink);

/* Adds the links i -> j (cap_ij) and j -> i (cap_ji); a cut pays cap_ij when i
 * is on the source side and j on the sink side. Links between the same pair
 * added twice add up. A self-link (i == j) or two zero capacities add
 * nothing (and use no room). */
void maxflow_add_edge(maxflow_graph *g, int i, int j, double cap_ij, double cap_ji);

/* Computes a maximum flow from the source to the sink and returns its value,
 * which equals the capacity of a minimum cut. A second call without a reset
 * returns the same value again. */
double maxflow_solve(maxflow_graph *g);

/* After maxflow_solve: 1 when the node is on the source side of the minimum
 * cut, else 0. The source side is the set of nodes reachable from the source
 * through unsaturated links, which is the smallest source side of all minimum
 * cuts: a node that could go either way without changing the cut's value
 * (a tie, e.g. a node with no links at all) is on the sink side. */
int maxflow_source_side(const maxflow_graph *g, int node);

/* After maxflow_solve: sets the node's terminal capacities anew (replacing
 * what was added or set before; same meaning as maxflow_add_terminals). The
 * next maxflow_solve continues from the flow and the search trees it left,
 * which is much cheaper than solving again when few t-links change, and
 * finds the same minimum cut. */
void maxflow_set_terminals(maxflow_graph *g, int node, double cap_source, double cap_sink);

/* Removes every link and the flow; the graph keeps its node count and its
 * memory, ready for the next round. */
void maxflow_reset(maxflow_graph *g);

/* Removes the t-links and the flow but keeps the n-links (with the capacities
 * they were added with): for rounds that change only the terminal costs, and
 * cheaper than adding the n-links again (the next solve lays them out anew). */
void maxflow_reset_terminals(maxflow_graph *g);

/* Gives the graph back. Its memory is kept for the calling thread's next
 * maxflow_create (a thread keeps its two largest graphs, freed when it
 * exits): fresh pages for a segmentation's graphs cost a fifth of its CPU. */
void maxflow_destroy(maxflow_graph *g);

#endif
