/* recon_segment: the object/backdrop min-cut at a reduced resolution.
 * See segment.h and docs/algorithms-recon.md ("Segmentation"). */
#include "segment/segment.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_statistics_double.h>

#include "segment/maxflow.h"

/* The working resolution: the longer side is brought down to about this many
 * pixels (an integer box factor), enough for a vessel's outline to within a
 * few full-resolution pixels, which the full-resolution refinement then
 * settles. */
enum { WORK_SIDE = 200 };
/* Components of the object's colour model (GrabCut's choice). */
enum { OBJECT_COMPONENTS = 5 };
enum { ROUNDS = 3 };
/* Contrast-sensitive smoothness weight between 8-neighbours, in nats (GrabCut's
 * gamma = 50). */
#define SMOOTHNESS_GAMMA 50.0
/* The symmetry link: the prior probability that a pixel and its mirror image
 * across the axis differ is eps = 2%, so a differing pair costs
 * log((1 - eps) / eps) = 3.9 nats. A cast shadow or a reflection of the room
 * in the backdrop, which the colour models leave nearly undecided, goes with
 * its mirror; a handle, whose colours are plainly the object's, stays. */
#define SYMMETRY_EPS 0.02
/* The image border is backdrop with prior probability 0.99 (log 99 nats). */
#define BORDER_PRIOR_EPS 0.01
/* A floor shadow: the backdrop darkened to k = 0.3 .. 1 times its colour, with
 * twice the backdrop's noise (at least 0.01 per channel), making up 5% of the
 * not-object pixels. No heavy tail: a shadow keeps the backdrop's
 * chromaticity (a brown foot ring on a white floor is not one). */
#define SHADOW_K_MIN 0.3
#define SHADOW_SIGMA_SCALE 2.0
/* A smooth surface does not fit every backdrop exactly (a floor's lit front
 * edge, the bend of a sweep, a fold in the paper): its residuals have a heavy
 * tail, modelled as a second Gaussian holding 10% of them, four times wider
 * than the noise and at least 0.03 per channel. */
#define TAIL_WEIGHT 0.1
#define TAIL_SCALE 4.0
#define TAIL_MIN_SIGMA 0.03
#define SHADOW_PRIOR 0.05
/* The object may show colours its mixture has not seen (a thin foot ring, a
 * glint): 5% of its pixels come from a uniform density over the colour cube
 * (density 1), so such a pixel costs at most log 20 = 3 nats as object,
 * whereas the backdrop, a smooth field, explains nothing far from it. */
#define OBJECT_UNSEEN 0.05
/* A shadow has no mirror image: where the mirror pixel across the axis is
 * darkened alike (shadow factors within 0.1, both under 0.97), a shadow is
 * fifty times less likely: a grey foot ring or a white glaze in shade is
 * symmetric, a cast shadow is not. */
#define SHADOW_SYMMETRIC_FACTOR 0.02
#define SHADOW_ALIKE 0.1
/* A stand's colours (when support.c found one) make up 30%. */
#define SUPPORT_PRIOR 0.3
/* Initial object: pixels whose backdrop residual has a squared Mahalanobis
 * distance above the chi-square(3) quantile at 1e-4. */
#define INIT_CHI2 21.1

/* Box-filtered colour at factor f (three channels). */
static float *downsample(const image_t *img, int f, int w, int h)
{
    float *out = calloc((size_t)w * h * 3, sizeof *out);
    if (!out)
        return NULL;
    const int c = img->channels, colour = c >= 3;
    const float inv = 1.0f / (f * f);
    for (int y = 0; y < h; y++)
        for (int j = 0; j < f; j++) {
            const float *row = img->data + ((size_t)(y * f + j) * img->width) * c;
            float *o = out + (size_t)y * w * 3;
            for (int x = 0; x < w; x++)
                for (int i = 0; i < f; i++) {
                    const float *p = row + (size_t)(x * f + i) * c;
                    float r = p[0], g = colour ? p[1] : p[0], b = colour ? p[2] : p[0];
                    /* NaN or HDR values from broken files count as black / white */
                    o[3 * x] += inv * (r > 0 ? (r < 1 ? r : 1) : 0);
                    o[3 * x + 1] += inv * (g > 0 ? (g < 1 ? g : 1) : 0);
                    o[3 * x + 2] += inv * (b > 0 ? (b < 1 ? b : 1) : 0);
                }
        }
    return out;
}

static int invert_sym3(const double a[9], double inv[9], double *logdet)
{
    double c00 = a[4] * a[8] - a[5] * a[7], c01 = a[5] * a[6] - a[3] * a[8], c02 = a[3] * a[7] - a[4] * a[6];
    double det = a[0] * c00 + a[1] * c01 + a[2] * c02;
    if (!(det > 0))
        return -1;
    double id = 1 / det;
    inv[0] = c00 * id;
    inv[1] = inv[3] = c01 * id;
    inv[2] = inv[6] = c02 * id;
    inv[4] = (a[0] * a[8] - a[2] * a[6]) * id;
    inv[5] = inv[7] = (a[2] * a[3] - a[0] * a[5]) * id;
    inv[8] = (a[0] * a[4] - a[1] * a[3]) * id;
    *logdet = log(det);
    return 0;
}

static double quad3(const double q[9], const double d[3])
{
    return d[0] * (q[0] * d[0] + 2 * q[1] * d[1] + 2 * q[2] * d[2]) + d[1] * (q[4] * d[1] + 2 * q[5] * d[2]) +
           d[2] * q[8] * d[2];
}

/* The backdrop and shadow Gaussians from the backdrop's residual covariance,
 * each with its prior weight folded into the normaliser. */
int recon_colour_model_prepare(recon_colour_model *m)
{
    double logdet, cov_s[9];
    double p_support = m->have_support ? SUPPORT_PRIOR : 0;
    if (invert_sym3(m->backdrop.cov, m->bg_icov, &logdet) != 0)
        return -1;
    double p_backdrop = 1 - SHADOW_PRIOR - p_support;
    m->bg_lognorm = log(p_backdrop * (1 - TAIL_WEIGHT)) - 1.5 * log(2 * M_PI) - 0.5 * logdet;
    double cov_t[9];
    for (int i = 0; i < 9; i++)
        cov_t[i] = m->backdrop.cov[i] * TAIL_SCALE * TAIL_SCALE + (i % 4 == 0 ? TAIL_MIN_SIGMA * TAIL_MIN_SIGMA : 0);
    if (invert_sym3(cov_t, m->tail_icov, &logdet) != 0)
        return -1;
    m->tail_lognorm = log(p_backdrop * TAIL_WEIGHT) - 1.5 * log(2 * M_PI) - 0.5 * logdet;
    for (int i = 0; i < 9; i++)
        cov_s[i] = m->backdrop.cov[i] * SHADOW_SIGMA_SCALE * SHADOW_SIGMA_SCALE + (i % 4 == 0 ? 1e-4 : 0);
    if (invert_sym3(cov_s, m->shadow_icov, &logdet) != 0)
        return -1;
    m->shadow_lognorm = log(SHADOW_PRIOR) - 1.5 * log(2 * M_PI) - 0.5 * logdet;
    return 0;
}

static double logsumexp2(double a, double b) { return a > b ? a + log1p(exp(b - a)) : b + log1p(exp(a - b)); }

/* The factor k that scales the backdrop colour bc closest to c. */
static double shadow_factor(const float *c, const float *bc)
{
    double bb = (double)bc[0] * bc[0] + (double)bc[1] * bc[1] + (double)bc[2] * bc[2];
    return bb > 1e-6 ? ((double)c[0] * bc[0] + (double)c[1] * bc[1] + (double)c[2] * bc[2]) / bb : 1;
}

void recon_colour_costs(const recon_colour_model *m, const float *c, const float *bc, const float *mc,
                        const float *mbc, double *cost_object, double *cost_backdrop)
{
    *cost_object = -logsumexp2(log(1 - OBJECT_UNSEEN) + recon_gmm_log_density(&m->object, c), log(OBJECT_UNSEEN));
    double d[3] = {c[0] - bc[0], c[1] - bc[1], c[2] - bc[2]};
    double l_bg = logsumexp2(m->bg_lognorm - 0.5 * quad3(m->bg_icov, d), m->tail_lognorm - 0.5 * quad3(m->tail_icov, d));
    /* The shadow: the backdrop scaled by the k that fits c best. */
    double k0 = shadow_factor(c, bc), k = k0 < SHADOW_K_MIN ? SHADOW_K_MIN : (k0 > 1 ? 1 : k0);
    double ds[3] = {c[0] - k * bc[0], c[1] - k * bc[1], c[2] - k * bc[2]};
    double prior = 0;
    if (mc) {
        double km = shadow_factor(mc, mbc);
        if (k0 < 0.97 && km < 0.97 && fabs(k0 - km) < SHADOW_ALIKE)
            prior = log(SHADOW_SYMMETRIC_FACTOR);
    }
    double l = logsumexp2(l_bg, prior + m->shadow_lognorm - 0.5 * quad3(m->shadow_icov, ds));
    if (m->have_support)
        l = logsumexp2(l, log(SUPPORT_PRIOR) + recon_gmm_log_density(&m->support, c));
    *cost_backdrop = -l;
}

/* ---- the axis of a mask */

/* Tukey's biweight constant, and MAD to sigma for a normal distribution. */
#define TUKEY_C 4.685
#define MAD_TO_SIGMA 1.4826

int recon_mask_axis(const uint8_t *mask, int w, int h, double *x0, double *slope)
{
    double *ys = malloc((size_t)h * 4 * sizeof *ys);
    if (!ys)
        return -1;
    double *xs = ys + h, *res = xs + h, *tmp = res + h;
    int n = 0;
    for (int y = 0; y < h; y++) {
        const uint8_t *m = mask + (size_t)y * w, *a = memchr(m, 1, (size_t)w);
        if (!a)
            continue;
        const uint8_t *b = memrchr(m, 1, (size_t)w);
        ys[n] = y + 0.5;
        xs[n++] = 0.5 * ((a - m) + (b - m) + 1);
    }
    if (n < 4) {
        free(ys);
        return -1;
    }
    /* Least median of squares over lines through pairs of rows (a regular
     * subsample of pairs: a quarter of the height apart or more), slopes up
     * to 30 degrees. */
    double best = INFINITY, a0 = xs[0], b0 = 0;
    int step = n / 48 + 1;
    for (int i = 0; i < n; i += step)
        for (int j = i + n / 4; j < n; j += step) {
            double b = (xs[j] - xs[i]) / (ys[j] - ys[i]);
            if (fabs(b) > 0.58)
                continue;
            double a = xs[i] - b * ys[i];
            for (int k = 0; k < n; k++)
                tmp[k] = fabs(xs[k] - a - b * ys[k]);
            double med = gsl_stats_select(tmp, 1, (size_t)n, (size_t)n / 2);
            if (med < best) {
                best = med;
                a0 = a;
                b0 = b;
            }
        }
    /* Tukey-weighted least squares from there. */
    for (int it = 0; it < 8; it++) {
        for (int k = 0; k < n; k++)
            res[k] = fabs(xs[k] - a0 - b0 * ys[k]);
        memcpy(tmp, res, (size_t)n * sizeof *tmp);
        double sigma = MAD_TO_SIGMA * gsl_stats_select(tmp, 1, (size_t)n, (size_t)n / 2) + 0.25;
        double sw = 0, sy = 0, sx = 0, syy = 0, sxy = 0;
        for (int k = 0; k < n; k++) {
            double u = res[k] / (TUKEY_C * sigma), wt = u < 1 ? (1 - u * u) * (1 - u * u) : 0;
            sw += wt;
            sy += wt * ys[k];
            sx += wt * xs[k];
            syy += wt * ys[k] * ys[k];
            sxy += wt * ys[k] * xs[k];
        }
        double det = sw * syy - sy * sy;
        if (!(det > 0))
            break;
        b0 = (sw * sxy - sy * sx) / det;
        a0 = (sx - b0 * sy) / sw;
    }
    *x0 = a0;
    *slope = b0;
    free(ys);
    return 0;
}

int recon_segment_mirror(const recon_segmentation *seg, int p)
{
    /* Reflect the pixel centre across the line through (x0, 0) with direction
     * (slope, 1). */
    double px = p % seg->w + 0.5, py = p / seg->w + 0.5;
    double dx = seg->axis_slope, dy = 1, inv = 1 / (dx * dx + dy * dy);
    double vx = px - seg->axis_x0, vy = py;
    double t = (vx * dx + vy * dy) * inv;
    double qx = seg->axis_x0 + 2 * t * dx - vx, qy = 2 * t * dy - vy;
    int x = (int)floor(qx), y = (int)floor(qy);
    if (x < 0 || y < 0 || x >= seg->w || y >= seg->h)
        return -1;
    return y * seg->w + x;
}

/* ---- one round */

/* The four forward neighbours of a pixel: each 8-neighbour pair once. */
static const int NEIGHBOUR[4][2] = {{1, 0}, {0, 1}, {1, 1}, {-1, 1}};

/* beta of the contrast term: 1 / (2 <|dc|^2>) over all neighbour pairs. */
double recon_contrast_beta(const float *rgb, int w, int h)
{
    double s = 0;
    long n = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int k = 0; k < 4; k++) {
                int qx = x + NEIGHBOUR[k][0], qy = y + NEIGHBOUR[k][1];
                if (qx < 0 || qx >= w || qy >= h)
                    continue;
                const float *a = rgb + 3 * ((size_t)y * w + x), *b = rgb + 3 * ((size_t)qy * w + qx);
                double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
                s += d0 * d0 + d1 * d1 + d2 * d2;
                n++;
            }
    return s > 0 ? n / (2 * s) : 0;
}

/* The 8-neighbour smoothness weights, four per pixel (right, down,
 * down-right, down-left; 0 past the image edge): the colours do not change
 * between rounds, so they are computed once. */

double recon_contrast_link(const float *a, const float *b, double beta, int diagonal)
{
    double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return SMOOTHNESS_GAMMA * exp(-beta * (d0 * d0 + d1 * d1 + d2 * d2)) / (diagonal ? M_SQRT2 : 1);
}

double recon_segment_link(const recon_segmentation *seg, int p, int q, int diagonal)
{
    return recon_contrast_link(seg->rgb + 3 * (size_t)p, seg->rgb + 3 * (size_t)q, seg->beta, diagonal);
}

static void smoothness_weights(const recon_segmentation *seg, float *wt)
{
    const int w = seg->w, h = seg->h;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int k = 0; k < 4; k++) {
                int qx = x + NEIGHBOUR[k][0], qy = y + NEIGHBOUR[k][1];
                size_t p = (size_t)y * w + x;
                wt[4 * p + k] = qx < 0 || qx >= w || qy >= h
                                    ? 0.0f
                                    : (float)recon_segment_link(seg, (int)p, qy * w + qx, k >= 2);
            }
}

static void add_smoothness(maxflow_graph *g, const float *wt, int w, int h)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int k = 0; k < 4; k++) {
                int p = y * w + x;
                double c = wt[4 * (size_t)p + k];
                if (c > 0)
                    maxflow_add_edge(g, p, (y + NEIGHBOUR[k][1]) * w + x + NEIGHBOUR[k][0], c, c);
            }
}

/* t-links from the colour costs, with the border prior. */
static void add_data_terms(maxflow_graph *g, const recon_segmentation *seg, const float *backdrop_rgb)
{
    const int w = seg->w, h = seg->h;
    const double border = log((1 - BORDER_PRIOR_EPS) / BORDER_PRIOR_EPS);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int p = y * w + x;
            double co, cb;
            int q = seg->have_axis ? recon_segment_mirror(seg, p) : -1;
            recon_colour_costs(&seg->model, seg->rgb + 3 * (size_t)p, backdrop_rgb + 3 * (size_t)p,
                               q >= 0 ? seg->rgb + 3 * (size_t)q : NULL, q >= 0 ? backdrop_rgb + 3 * (size_t)q : NULL,
                               &co, &cb);
            if (x == 0 || y == 0 || x == w - 1 || y == h - 1)
                co += border;
            double lo = co < cb ? co : cb;
            /* the source side is the object: a pixel left on the sink side pays cb */
            maxflow_add_terminals(g, p, cb - lo, co - lo);
        }
}

static void add_symmetry(maxflow_graph *g, const recon_segmentation *seg)
{
    const double lambda = log((1 - SYMMETRY_EPS) / SYMMETRY_EPS);
    for (int p = 0; p < seg->w * seg->h; p++) {
        double x = p % seg->w + 0.5, y = p / seg->w + 0.5;
        if (x >= seg->axis_x0 + seg->axis_slope * y) /* each pair once: from its left pixel */
            continue;
        int q = recon_segment_mirror(seg, p);
        if (q >= 0)
            maxflow_add_edge(g, p, q, lambda, lambda);
    }
}

/* ---- models from a labelling */

/* Indices of the pixels of the largest object component whose 4-neighbours
 * are all object (edge pixels mix object and backdrop). */
static int object_samples(const int *lab, int main_c, int w, int h, int *idx)
{
    int n = 0;
    for (int y = 1; y + 1 < h; y++)
        for (int x = 1; x + 1 < w; x++) {
            int p = y * w + x;
            if (lab[p] == main_c && lab[p - 1] == main_c && lab[p + 1] == main_c && lab[p - w] == main_c &&
                lab[p + w] == main_c)
                idx[n++] = p;
        }
    return n;
}

static void eval_backdrop(const recon_backdrop *b, float *out)
{
    for (int y = 0; y < b->height; y++)
        recon_backdrop_row(b, y, out + (size_t)y * b->width * 3);
}

/* Colours for the object's model: its largest component's interior pixels,
 * at most MODEL_SAMPLES of them (a regular subsample: the mixture needs a few
 * thousand, not all). */
enum { MODEL_SAMPLES = 6000 };

static int fit_object_model(recon_segmentation *seg, const int *lab, int main_c, int *idx)
{
    const int w = seg->w, h = seg->h;
    int ns = object_samples(lab, main_c, w, h, idx);
    if (ns < 2 * OBJECT_COMPONENTS) { /* a thin object: take its edge pixels too */
        ns = 0;
        for (int p = 0; p < w * h; p++)
            if (lab[p] == main_c)
                idx[ns++] = p;
    }
    int stride = ns / MODEL_SAMPLES + 1, m = 0;
    for (int i = 0; i < ns; i += stride)
        idx[m++] = idx[i];
    return recon_gmm_fit(&seg->model.object, seg->rgb, idx, m, OBJECT_COMPONENTS, 2);
}

/* The largest component of the object labels (0 when there is none). */
static int largest_component(const long *area, int n)
{
    int best = 0;
    for (int k = 1; k <= n; k++)
        if (!best || area[k] > area[best])
            best = k;
    return best;
}

/* ---- the whole segmentation */

int recon_segment(const image_t *img, recon_segmentation *seg)
{
    memset(seg, 0, sizeof *seg);
    int longest = img->width > img->height ? img->width : img->height;
    int f = (longest + WORK_SIDE / 2) / WORK_SIDE;
    f = f < 1 ? 1 : f;
    const int w = img->width / f, h = img->height / f;
    const size_t n = (size_t)w * h;
    seg->factor = f;
    seg->w = w;
    seg->h = h;
    seg->rgb = downsample(img, f, w, h);
    seg->object = calloc(n, 1);
    float *bgc = malloc(n * 3 * sizeof *bgc);
    uint8_t *use = malloc(n * 2);
    int *lab = malloc(n * sizeof *lab), *idx = malloc(n * sizeof *idx);
    float *nlw = malloc(n * 4 * sizeof *nlw);
    long *area = NULL;
    maxflow_graph *g = maxflow_create((int)n, (int)(5 * n));
    int rc = -1;
    if (!seg->rgb || !seg->object || !bgc || !use || !lab || !idx || !nlw || !g)
        goto out;

    /* The backdrop first from a ring along the image border (6% of the
     * shorter side), robustly: a stand or a caption reaching the border
     * weighs nothing. */
    int ring = (int)(0.06 * (w < h ? w : h)) + 2;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            use[(size_t)y * w + x] = x < ring || y < ring || x >= w - ring || y >= h - ring;
    if (recon_backdrop_fit(&seg->model.backdrop, seg->rgb, w, h, use, 1, 6, 4) != 0 ||
        recon_colour_model_prepare(&seg->model) != 0)
        goto out;
    eval_backdrop(&seg->model.backdrop, bgc);
    /* The initial object: what the backdrop cannot explain. */
    for (size_t p = 0; p < n; p++) {
        double d[3];
        for (int c = 0; c < 3; c++)
            d[c] = seg->rgb[3 * p + c] - bgc[3 * p + c];
        seg->object[p] = quad3(seg->model.bg_icov, d) > INIT_CHI2;
    }

    seg->beta = recon_contrast_beta(seg->rgb, w, h);
    smoothness_weights(seg, nlw);
    for (int r = 0; r < ROUNDS; r++) {
        free(area);
        area = NULL;
        int nc = recon_mask_label(seg->object, w, h, lab, &area);
        if (nc < 0)
            goto out;
        int main_c = largest_component(area, nc);
        if (!main_c) {
            rc = 1;
            goto out;
        }
        /* Models from the current labels: the object's colours from its
         * largest component, the backdrop from the pixels at least 2 px
         * from any object. */
        if (fit_object_model(seg, lab, main_c, idx) != 0) {
            rc = 1;
            goto out;
        }
        /* The axis of the symmetry links comes from the initial object
         * (what the backdrop cannot explain: a highlight that the colour
         * models will take for backdrop is still there), and the rounds
         * keep it: only the colour models change, so only the t-links are
         * rebuilt. */
        if (r == 0) {
            maxflow_reset(g);
            add_smoothness(g, nlw, w, h);
            for (size_t p = 0; p < n; p++)
                use[p] = lab[p] == main_c;
            seg->have_axis = recon_mask_axis(use, w, h, &seg->axis_x0, &seg->axis_slope) == 0;
            if (seg->have_axis)
                add_symmetry(g, seg);
        } else {
            maxflow_reset_terminals(g);
        }
        add_data_terms(g, seg, bgc);
        maxflow_solve(g);
        for (size_t p = 0; p < n; p++)
            seg->object[p] = (uint8_t)maxflow_source_side(g, (int)p);
        seg->rounds = r + 1;
    }
    rc = 0;
out:
    maxflow_destroy(g);
    free(area);
    free(lab);
    free(idx);
    free(nlw);
    free(use);
    free(bgc);
    return rc;
}

void recon_segmentation_free(recon_segmentation *seg)
{
    free(seg->rgb);
    free(seg->object);
    memset(seg, 0, sizeof *seg);
}
