/* Min-cut benchmark: GrabCut-like s-t graphs built from real museum photos,
 * solved by celadon's Boykov–Kolmogorov max-flow (src/segment/maxflow.c) and by
 * igraph's push-relabel (igraph_maxflow, Debian's libigraph-dev), CPU time of
 * the thread per solve, graph construction included. Run by `make bench`;
 * docs/BENCHMARKS.md ("Min-cut") explains it. Photos: three of
 * $CELADON_SHARED/data/real-dev (default ../shared); skipped without them.
 *
 * The graph of a photo: the photo area-averaged to about 120k pixels
 * (~300x400), one node per pixel.
 *  - n-links (4- or 8-connected): GrabCut's contrast-sensitive weight
 *    gamma / distance * exp(-beta |z_p - z_q|^2), gamma = 50,
 *    beta = 1 / (2 <|z_p - z_q|^2>) over the neighbour pairs, z in 0..255.
 *  - mirror links (optional): each pixel left of the middle column to its
 *    mirror image across it, weight gamma / 2 * exp(-beta |z_p - z_mirror|^2):
 *    a symmetry prior for a vessel photographed side-on.
 *  - t-links: colour likelihoods from 16^3-bin colour histograms (add-one
 *    smoothed). A border strip 6% of the smaller side wide is known background
 *    (sink capacity K = 1 + the largest sum of a pixel's n-links, source 0);
 *    any other pixel gets -log P(colour | background) toward the source and
 *    -log P(colour | object) toward the sink. Round 1 takes the object's
 *    histogram from everything inside the strip (GrabCut's rectangle), round 2
 *    from round 1's source side (the background's from the rest), with the
 *    same n-links (maxflow_reset_terminals). */
#include <igraph.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "celadon/image.h"
#include "segment/maxflow.h"

#define REPS 5        /* ours, after a warm-up run: median */
#define REPS_IGRAPH 3 /* about a second each: median, no warm-up */
#define GAMMA 50.0
#define BINS 16 /* histogram bins per colour channel */
#define N_BINS (BINS * BINS * BINS)

typedef struct {
    int w, h, n;
    const float *rgb;              /* w * h RGB, 0..255 */
    unsigned char *known_bg;       /* the border strip */
    double k_hard;                 /* t-link of a known background pixel */
    int m;                         /* n-links, each pair once, both directions alike */
    int *ei, *ej;
    double *cap;
    double *cap_source, *cap_sink; /* t-links */
} cut_problem;

static void die(const char *what)
{
    fprintf(stderr, "bench_maxflow: %s\n", what);
    exit(1);
}

static void *xcalloc(size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size);
    if (!p)
        die("out of memory");
    return p;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* CPU time of the calling thread, s (the machine is shared). */
static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Area average to about `pixels` pixels, RGB in 0..255: the output pixel
 * (X, Y) averages the source pixels whose centres fall in its footprint. */
static float *downsample(const image_t *img, double pixels, int *ow, int *oh)
{
    double s = fmin(1.0, sqrt(pixels / ((double)img->width * img->height)));
    int w = (int)lround(img->width * s), h = (int)lround(img->height * s);
    float *out = xcalloc((size_t)w * h * 3, sizeof *out);
    for (int Y = 0; Y < h; Y++) {
        int y0 = (int)(Y / s), y1 = (int)((Y + 1) / s);
        y1 = y1 > img->height ? img->height : (y1 > y0 ? y1 : y0 + 1);
        for (int X = 0; X < w; X++) {
            int x0 = (int)(X / s), x1 = (int)((X + 1) / s);
            x1 = x1 > img->width ? img->width : (x1 > x0 ? x1 : x0 + 1);
            double sum[3] = {0, 0, 0};
            for (int y = y0; y < y1; y++)
                for (int x = x0; x < x1; x++) {
                    const float *px = img->data + ((size_t)y * img->width + x) * img->channels;
                    for (int c = 0; c < 3; c++)
                        sum[c] += px[img->channels >= 3 ? c : 0];
                }
            for (int c = 0; c < 3; c++)
                out[((size_t)Y * w + X) * 3 + c] = (float)(255.0 * sum[c] / ((y1 - y0) * (x1 - x0)));
        }
    }
    *ow = w;
    *oh = h;
    return out;
}

static double dist2(const float *rgb, int p, int q)
{
    double d = 0;
    for (int c = 0; c < 3; c++) {
        double e = (double)rgb[3 * p + c] - rgb[3 * q + c];
        d += e * e;
    }
    return d;
}

static int colour_bin(const float *rgb, int p)
{
    int b = 0;
    for (int c = 0; c < 3; c++) {
        int v = (int)(rgb[3 * p + c] * BINS / 256.0f);
        b = b * BINS + (v < 0 ? 0 : v >= BINS ? BINS - 1 : v);
    }
    return b;
}

/* The n-links, K and the border strip (the comment at the top). */
static void build_links(const float *rgb, int w, int h, int connectivity, int mirror, cut_problem *p)
{
    int n = w * h;
    *p = (cut_problem){.w = w, .h = h, .n = n, .rgb = rgb};
    int max_links = 4 * n + n / 2 + w;
    p->ei = xcalloc((size_t)max_links, sizeof(int));
    p->ej = xcalloc((size_t)max_links, sizeof(int));
    p->cap = xcalloc((size_t)max_links, sizeof(double));
    p->cap_source = xcalloc((size_t)n, sizeof(double));
    p->cap_sink = xcalloc((size_t)n, sizeof(double));
    p->known_bg = xcalloc((size_t)n, 1);

    /* neighbour offsets (dx, dy) that reach each pair once; the last two are diagonal */
    const int off[4][2] = {{1, 0}, {0, 1}, {1, 1}, {-1, 1}};
    const int n_off = connectivity == 8 ? 4 : 2;
    double sum = 0;
    long count = 0;
    for (int pass = 0; pass < 2; pass++) {
        double beta = pass ? 1.0 / (2.0 * sum / count) : 0;
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                for (int k = 0; k < n_off; k++) {
                    int qx = x + off[k][0], qy = y + off[k][1];
                    if (qx < 0 || qx >= w || qy >= h)
                        continue;
                    double d = dist2(rgb, y * w + x, qy * w + qx);
                    if (pass == 0) {
                        sum += d;
                        count++;
                        continue;
                    }
                    p->ei[p->m] = y * w + x;
                    p->ej[p->m] = qy * w + qx;
                    p->cap[p->m++] = GAMMA / (k < 2 ? 1.0 : sqrt(2.0)) * exp(-beta * d);
                }
        if (pass && mirror)
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w / 2; x++) {
                    p->ei[p->m] = y * w + x;
                    p->ej[p->m] = y * w + (w - 1 - x);
                    p->cap[p->m] = GAMMA / 2 * exp(-beta * dist2(rgb, p->ei[p->m], p->ej[p->m]));
                    p->m++;
                }
    }
    double *link_sum = xcalloc((size_t)n, sizeof(double));
    for (int e = 0; e < p->m; e++) {
        link_sum[p->ei[e]] += p->cap[e];
        link_sum[p->ej[e]] += p->cap[e];
    }
    for (int i = 0; i < n; i++)
        p->k_hard = fmax(p->k_hard, link_sum[i]);
    p->k_hard += 1;
    free(link_sum);
    int strip = (int)(0.06 * (w < h ? w : h)) + 1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            p->known_bg[y * w + x] = x < strip || y < strip || x >= w - strip || y >= h - strip;
}

/* t-links from the colour histograms of the pixels labelled object (object[i]
 * and not known background) and of the rest. */
static void set_tlinks(cut_problem *p, const unsigned char *object)
{
    double *hist[2] = {xcalloc(N_BINS, sizeof(double)), xcalloc(N_BINS, sizeof(double))};
    double total[2] = {N_BINS, N_BINS}; /* add-one smoothing */
    for (int i = 0; i < p->n; i++) {
        int fg = object[i] && !p->known_bg[i];
        hist[fg][colour_bin(p->rgb, i)]++;
        total[fg]++;
    }
    for (int i = 0; i < p->n; i++) {
        if (p->known_bg[i]) {
            p->cap_source[i] = 0;
            p->cap_sink[i] = p->k_hard;
        } else {
            int b = colour_bin(p->rgb, i);
            p->cap_source[i] = -log((hist[0][b] + 1) / total[0]);
            p->cap_sink[i] = -log((hist[1][b] + 1) / total[1]);
        }
    }
    free(hist[0]);
    free(hist[1]);
}

static void free_problem(cut_problem *p)
{
    free(p->ei);
    free(p->ej);
    free(p->cap);
    free(p->cap_source);
    free(p->cap_sink);
    free(p->known_bg);
}

/* igraph: a directed graph with the source n and the sink n + 1; every n-link
 * is two arcs. Returns the flow. */
static double solve_igraph(const cut_problem *p)
{
    int n = p->n, s = n, t = n + 1;
    igraph_integer_t n_arcs = 2 * (igraph_integer_t)p->m + 2 * n, k = 0;
    igraph_vector_int_t edges, partition;
    igraph_vector_t caps;
    igraph_t g;
    igraph_real_t value;
    if (igraph_vector_int_init(&edges, 2 * n_arcs) || igraph_vector_init(&caps, n_arcs) ||
        igraph_vector_int_init(&partition, 0))
        die("igraph: out of memory");
    for (int i = 0; i < n; i++) {
        VECTOR(edges)[2 * k] = s;
        VECTOR(edges)[2 * k + 1] = i;
        VECTOR(caps)[k++] = p->cap_source[i];
        VECTOR(edges)[2 * k] = i;
        VECTOR(edges)[2 * k + 1] = t;
        VECTOR(caps)[k++] = p->cap_sink[i];
    }
    for (int e = 0; e < p->m; e++) {
        VECTOR(edges)[2 * k] = p->ei[e];
        VECTOR(edges)[2 * k + 1] = p->ej[e];
        VECTOR(caps)[k++] = p->cap[e];
        VECTOR(edges)[2 * k] = p->ej[e];
        VECTOR(edges)[2 * k + 1] = p->ei[e];
        VECTOR(caps)[k++] = p->cap[e];
    }
    if (igraph_create(&g, &edges, n + 2, IGRAPH_DIRECTED) ||
        igraph_maxflow(&g, &value, NULL, NULL, &partition, NULL, s, t, &caps, NULL))
        die("igraph_maxflow failed");
    igraph_vector_int_destroy(&partition);
    igraph_destroy(&g);
    igraph_vector_destroy(&caps);
    igraph_vector_int_destroy(&edges);
    return value;
}

/* One round of ours on graph g: with new_links, everything is added anew
 * (round 1); else only the t-links change (maxflow_reset_terminals, round 2).
 * Timed: the add calls and the solve. Returns the flow; side[] gets the cut. */
static double solve_ours(maxflow_graph *g, const cut_problem *p, int new_links, double *ms, unsigned char *side)
{
    double c0 = cpu_seconds();
    if (new_links) {
        maxflow_reset(g);
        for (int e = 0; e < p->m; e++)
            maxflow_add_edge(g, p->ei[e], p->ej[e], p->cap[e], p->cap[e]);
    } else {
        maxflow_reset_terminals(g);
    }
    for (int i = 0; i < p->n; i++)
        maxflow_add_terminals(g, i, p->cap_source[i], p->cap_sink[i]);
    double flow = maxflow_solve(g);
    *ms = 1e3 * (cpu_seconds() - c0);
    for (int i = 0; i < p->n; i++)
        side[i] = (unsigned char)maxflow_source_side(g, i);
    return flow;
}

/* Median CPU ms of ours over REPS runs after a warm-up; flow and side of the last. */
static double time_ours(maxflow_graph *g, const cut_problem *p, int new_links, double *flow, unsigned char *side)
{
    double t[REPS], ms;
    for (int r = -1; r < REPS; r++) {
        *flow = solve_ours(g, p, new_links || r < 0, &ms, side);
        if (r >= 0)
            t[r] = ms;
    }
    return median(t, REPS);
}

static double time_igraph(const cut_problem *p, double *flow)
{
    double t[REPS_IGRAPH];
    for (int r = 0; r < REPS_IGRAPH; r++) {
        double c0 = cpu_seconds();
        *flow = solve_igraph(p);
        t[r] = 1e3 * (cpu_seconds() - c0);
    }
    return median(t, REPS_IGRAPH);
}

static const char *const PHOTOS[] = {
    "met_maiolica_albarello_199721.jpg",
    "met_alabaster_alabastron_258094.jpg",
    "met_glass_beaker_bw_196030.jpg",
};
#define N_PHOTOS (int)(sizeof PHOTOS / sizeof *PHOTOS)

static const struct {
    int connectivity, mirror;
    const char *name;
} GRAPHS[] = {{4, 0, "4-conn"}, {8, 0, "8-conn"}, {8, 1, "8-conn+mirror"}};
#define N_GRAPHS (int)(sizeof GRAPHS / sizeof *GRAPHS)

/* "met_maiolica_albarello_199721.jpg" -> "maiolica_albarello" */
static const char *short_name(const char *file, char *name, size_t len)
{
    snprintf(name, len, "%s", strncmp(file, "met_", 4) == 0 ? file + 4 : file);
    char *cut = strrchr(name, '_');
    if (cut)
        *cut = 0;
    return name;
}

static long count_ones(const unsigned char *v, int n)
{
    long c = 0;
    for (int i = 0; i < n; i++)
        c += v[i];
    return c;
}

/* Both rounds of one graph; with_igraph: igraph too, and the flows compared. */
static void bench_graph(const char *photo, const float *rgb, int w, int h, int gi, int with_igraph)
{
    cut_problem p;
    build_links(rgb, w, h, GRAPHS[gi].connectivity, GRAPHS[gi].mirror, &p);
    maxflow_graph *g = maxflow_create(p.n, p.m);
    unsigned char *side = xcalloc((size_t)p.n, 1);
    if (!g)
        die("out of memory");
    memset(side, 1, (size_t)p.n); /* round 1: the object is everything inside the strip */
    char name[64];
    for (int round = 1; round <= 2; round++) {
        set_tlinks(&p, side);
        double flow, flow_ig = 0, ms_ig = 0;
        double ms = time_ours(g, &p, round == 1, &flow, side);
        if (with_igraph) {
            ms_ig = time_igraph(&p, &flow_ig);
            if (fabs(flow - flow_ig) > 1e-9 * flow_ig) {
                fprintf(stderr, "bench_maxflow: %s %s round %d: flow %.17g, igraph %.17g\n", photo,
                        GRAPHS[gi].name, round, flow, flow_ig);
                exit(1);
            }
        }
        printf("  %-20s %-13s %7d %7d %5d %12.3f %7ld %9.2f", short_name(photo, name, sizeof name),
               GRAPHS[gi].name, p.n, p.m, round, flow, count_ones(side, p.n), ms);
        if (with_igraph)
            printf(" %9.1f %11.1f", ms_ig, ms_ig / ms);
        printf("\n");
    }
    maxflow_destroy(g);
    free(side);
    free_problem(&p);
}

int main(void)
{
    const char *shared = getenv("CELADON_SHARED");
    char dir[512], path[1024], err[512];
    snprintf(dir, sizeof dir, "%s/data/real-dev", shared && *shared ? shared : "../shared");
    struct stat st;
    if (stat(dir, &st) != 0) { /* like the tests: no data, no benchmark, the others still run */
        printf("bench_maxflow: skipped, no photos at %s (set CELADON_SHARED)\n", dir);
        return 0;
    }
    image_t photos[N_PHOTOS];
    for (int f = 0; f < N_PHOTOS; f++) {
        snprintf(path, sizeof path, "%s/%s", dir, PHOTOS[f]);
        if (image_read(path, &photos[f], err, sizeof err) != 0) {
            fprintf(stderr, "bench_maxflow: %s: %s (set CELADON_SHARED)\n", path, err);
            return 1;
        }
    }
    const char *header = "  %-20s %-13s %7s %7s %5s %12s %7s %9s";
    printf("min-cut of GrabCut-like graphs, ~300x400 px; CPU ms of the thread per solve, construction included\n");
    printf("(ours: median of %d after a warm-up, round 2 keeps the n-links; igraph: median of %d);\n", REPS,
           REPS_IGRAPH);
    printf("source: nodes on the source (object) side\n");
    printf(header, "photo", "graph", "nodes", "n-links", "round", "flow", "source", "ours ms");
    printf(" %9s %11s\n", "igraph ms", "igraph/ours");
    for (int f = 0; f < N_PHOTOS; f++) {
        int w, h;
        float *rgb = downsample(&photos[f], 120000, &w, &h);
        for (int gi = 0; gi < N_GRAPHS; gi++)
            bench_graph(PHOTOS[f], rgb, w, h, gi, 1);
        free(rgb);
    }
    printf("\nscaling with the image size, 8-connected + mirror links, ours only\n");
    printf(header, "photo", "graph", "nodes", "n-links", "round", "flow", "source", "ours ms");
    printf("\n");
    const double sizes[] = {7500, 30000};
    for (int f = 0; f < N_PHOTOS; f++)
        for (int k = 0; k < 2; k++) {
            int w, h;
            float *rgb = downsample(&photos[f], sizes[k], &w, &h);
            bench_graph(PHOTOS[f], rgb, w, h, N_GRAPHS - 1, 0);
            free(rgb);
        }
    for (int f = 0; f < N_PHOTOS; f++)
        image_free(&photos[f]);
    return 0;
}
