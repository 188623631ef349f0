/* recon_segment: the object/backdrop min-cut at a reduced resolution.
 * See segment.h and docs/algorithms-recon.md ("Segmentation"). */
#include "segment/segment.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_statistics_double.h>

#include "segment/maxflow.h"
#include "segment/robust.h"
#include "core/core.h"

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
/* The learned object prior (prior/prior.h) is a likelihood ratio on each
 * pixel, PRIOR_WEIGHT log(pi / (1 - pi)) nats for object, the network's
 * probability pi held in [PRIOR_EPS, 1 - PRIOR_EPS]: a network sure of a
 * pixel weighs 3.9 nats, as much as a symmetry link, so the colour models,
 * the contrast links and the mirror still decide where they are sure (a
 * handle's window, a shadow, a stand's edge) and the network where they are
 * not (a wall band or a floor the backdrop's surface cannot explain, a glaze
 * of the backdrop's own grey). */
#define PRIOR_EPS 0.02
#define PRIOR_WEIGHT 1.0
/* Initial object: pixels whose backdrop residual has a squared Mahalanobis
 * distance above the chi-square(3) quantile at 1e-4. */
#define INIT_CHI2 21.1

/* out[i] = inv times row[i] clamped to [0, 1] (NaN or HDR values from
 * broken files count as black / white), n values. */
RECON_VECTOR_CLONES static void clamp01_scaled(float *restrict out, const float *restrict row, size_t n, float inv)
{
#pragma omp simd
    for (size_t i = 0; i < n; i++) {
        float v = row[i], u = v < 1 ? v : 1; /* two selects: the compiler vectorises this form */
        out[i] = inv * (v > 0 ? u : 0);
    }
}

/* Adds one photo row's scaled values q (w * f pixels of c channels) to the
 * w output colours o, each output's f pixels in order. A colour pixel's
 * three channels go as one 4-lane vector (the fourth lane reads the next
 * value, or the padding after the row, and is dropped); a gray pixel's one
 * value goes to all three. */
static void add_row(float *restrict o, const float *restrict q, int w, int f, int c)
{
    if (c >= 3) {
        for (int x = 0; x < w; x++) {
            const float *p = q + (size_t)x * f * c;
            float s[4] = {o[3 * x], o[3 * x + 1], o[3 * x + 2], 0};
            for (int i = 0; i < f; i++, p += c) {
#pragma omp simd
                for (int k = 0; k < 4; k++)
                    s[k] += p[k];
            }
            o[3 * x] = s[0];
            o[3 * x + 1] = s[1];
            o[3 * x + 2] = s[2];
        }
        return;
    }
    for (int x = 0; x < w; x++) {
        const float *p = q + (size_t)x * f * c;
        float s = o[3 * x];
        for (int i = 0; i < f; i++, p += c)
            s += p[0];
        o[3 * x] = o[3 * x + 1] = o[3 * x + 2] = s;
    }
}

/* Box-filtered colour at factor f (three channels): each output the sum, in
 * order, of its f * f pixels' clamped values times 1 / f^2. */
static float *downsample(const image_t *img, int f, int w, int h)
{
    const int c = img->channels;
    const size_t n = (size_t)w * f * c;
    float *out = calloc((size_t)w * h * 3, sizeof *out), *row = malloc((n + 1) * sizeof *row);
    if (!out || !row) {
        free(out);
        free(row);
        return NULL;
    }
    row[n] = 0; /* the last colour pixel's fourth lane */
    const float inv = 1.0f / (f * f);
    for (int y = 0; y < h; y++)
        for (int j = 0; j < f; j++) {
            clamp01_scaled(row, img->data + ((size_t)(y * f + j) * img->width) * c, n, inv);
            add_row(out + (size_t)y * w * 3, row, w, f, c);
        }
    free(row);
    return out;
}

/* The object prior box-filtered at factor f, like the colours. */
static float *downsample_prior(const float *prior, int W, int f, int w, int h)
{
    float *out = calloc((size_t)w * h, sizeof *out);
    if (!out)
        return NULL;
    const float inv = 1.0f / (f * f);
    for (int y = 0; y < h; y++)
        for (int j = 0; j < f; j++) {
            const float *row = prior + (size_t)(y * f + j) * W;
            for (int x = 0; x < w; x++)
                for (int i = 0; i < f; i++)
                    out[(size_t)y * w + x] += inv * row[x * f + i];
        }
    return out;
}

/* The backdrop and shadow Gaussians from the backdrop's residual covariance,
 * each with its prior weight folded into the normaliser. */
int recon_colour_model_prepare(recon_colour_model *m)
{
    double logdet, cov_s[9];
    double p_support = m->have_support ? SUPPORT_PRIOR : 0;
    if (recon_invert_sym3(m->backdrop.cov, m->bg_icov, &logdet) != 0)
        return -1;
    double p_backdrop = 1 - SHADOW_PRIOR - p_support;
    m->bg_lognorm = log(p_backdrop * (1 - TAIL_WEIGHT)) - 1.5 * log(2 * M_PI) - 0.5 * logdet;
    double cov_t[9];
    for (int i = 0; i < 9; i++)
        cov_t[i] = m->backdrop.cov[i] * TAIL_SCALE * TAIL_SCALE + (i % 4 == 0 ? TAIL_MIN_SIGMA * TAIL_MIN_SIGMA : 0);
    if (recon_invert_sym3(cov_t, m->tail_icov, &logdet) != 0)
        return -1;
    m->tail_lognorm = log(p_backdrop * TAIL_WEIGHT) - 1.5 * log(2 * M_PI) - 0.5 * logdet;
    for (int i = 0; i < 9; i++)
        cov_s[i] = m->backdrop.cov[i] * SHADOW_SIGMA_SCALE * SHADOW_SIGMA_SCALE + (i % 4 == 0 ? 1e-4 : 0);
    if (recon_invert_sym3(cov_s, m->shadow_icov, &logdet) != 0)
        return -1;
    m->shadow_lognorm = log(SHADOW_PRIOR) - 1.5 * log(2 * M_PI) - 0.5 * logdet;
    return 0;
}

/* log(e^a + e^b) = hi + log1p(exp(d)), hi the larger, d = lo - hi <= 0. For
 * d < -40, exp(d) < 4.3e-18 is under a quarter of hi's last bit when |hi| >=
 * 1/4, so the sum rounds to hi exactly: the two calls are skipped (a pixel
 * plainly of one kind, most of a photo). */
static double logsumexp2(double a, double b)
{
    double hi = a > b ? a : b, d = a > b ? b - a : a - b;
    return d < -40 && fabs(hi) >= 0.25 ? hi : hi + log1p(exp(d));
}

/* The factor k that scales the backdrop colour bc closest to c. */
static double shadow_factor(const float *c, const float *bc)
{
    double bb = (double)bc[0] * bc[0] + (double)bc[1] * bc[1] + (double)bc[2] * bc[2];
    return bb > 1e-6 ? ((double)c[0] * bc[0] + (double)c[1] * bc[1] + (double)c[2] * bc[2]) / bb : 1;
}

static double object_cost(const recon_colour_model *m, recon_cost_memo *memo, const float *c)
{
    if (!memo)
        return -logsumexp2(log(1 - OBJECT_UNSEEN) + recon_gmm_log_density(&m->object, c), log(OBJECT_UNSEEN));
    uint32_t b[3];
    memcpy(b, c, sizeof b);
    uint32_t slot = (b[0] * 0x9E3779B1u ^ b[1] * 0x85EBCA77u ^ b[2] * 0xC2B2AE3Du) >> (32 - RECON_COST_MEMO_BITS);
    if (!memo->e[slot].used || memcmp(memo->e[slot].c, c, sizeof memo->e[slot].c) != 0) {
        memo->e[slot].used = 1;
        memcpy(memo->e[slot].c, c, sizeof memo->e[slot].c);
        memo->e[slot].cost = object_cost(m, NULL, c);
    }
    return memo->e[slot].cost;
}

/* The standard normal's upper tail Q(z) = Phi(-z), and its log beyond 9
 * sigmas (Mills' ratio, within 1%), where erfc underflows soon. */
static double upper_tail(double z) { return 0.5 * erfc(z * M_SQRT1_2); }
static double log_far_tail(double z) { return -0.5 * z * z - log(z * sqrt(2 * M_PI)); }

/* log of the shadow's density at c (its prior folded in): the backdrop
 * colour bc darkened by a factor k uniform on [SHADOW_K_MIN, 1], plus the
 * shadow's noise (inverse covariance S). Along k the squared Mahalanobis
 * distance of c from k bc is the parabola q* + a (k - k*)^2, so the integral
 * over k is a Gaussian's mass on [SHADOW_K_MIN, 1]: the shadow's colours are
 * a line, not a point. Its density at the best k alone counted the line as a
 * point, sqrt(a / 2 pi) (1 - SHADOW_K_MIN) times too likely: 38 times
 * (3.6 nats) on a white backdrop, which took a light grey glaze for shadow. */
/* The shadow's line through the backdrop colour bc under the inverse
 * covariance S: a = bc' S bc and b = bc' S c, so that the squared distance of
 * c from k bc is c' S c - 2 k b + k^2 a. */
static void shadow_line(const double *S, const float *c, const float *bc, double *a, double *b)
{
    double Sv[3];
    for (int i = 0; i < 3; i++)
        Sv[i] = S[3 * i] * bc[0] + S[3 * i + 1] * bc[1] + S[3 * i + 2] * bc[2];
    *a = Sv[0] * bc[0] + Sv[1] * bc[1] + Sv[2] * bc[2];
    *b = Sv[0] * c[0] + Sv[1] * c[1] + Sv[2] * c[2];
}

static double shadow_log_density(const recon_colour_model *m, const float *c, const float *bc)
{
    const double *S = m->shadow_icov;
    double a, b;
    shadow_line(S, c, bc, &a, &b);
    if (!(a > 1e-12)) { /* a black backdrop: its shadow is itself */
        double d[3] = {c[0] - bc[0], c[1] - bc[1], c[2] - bc[2]};
        return m->shadow_lognorm - 0.5 * recon_quad3(S, d);
    }
    double ks = b / a, sa = sqrt(a);
    double cd[3] = {c[0], c[1], c[2]}, q = recon_quad3(S, cd) - b * ks;
    /* the mass Phi(z1) - Phi(z0) of [SHADOW_K_MIN, 1], from the tail it lies
     * in (no difference of two numbers near 1); beyond 9 sigmas of one end
     * the other end's tail weighs under 1e-19 of it */
    double z1 = sa * (1 - ks), z0 = sa * (SHADOW_K_MIN - ks), mass;
    if (z1 < -9) /* far lighter than the backdrop */
        mass = log_far_tail(-z1);
    else if (z0 > 9) /* far darker than its darkest shadow */
        mass = log_far_tail(z0);
    else if (z0 > 0)
        mass = log(upper_tail(z0) - upper_tail(z1));
    else
        mass = log(upper_tail(-z1) - upper_tail(-z0));
    return m->shadow_lognorm - 0.5 * (q > 0 ? q : 0) + 0.5 * log(2 * M_PI / a) + mass - log(1 - SHADOW_K_MIN);
}

double recon_shadow_misfit(const recon_colour_model *m, const float *c, const float *bc)
{
    double a, b, d[3] = {c[0], c[1], c[2]};
    shadow_line(m->shadow_icov, c, bc, &a, &b);
    return a > 1e-12 ? fmax(recon_quad3(m->shadow_icov, d) - b * b / a, 0) : recon_quad3(m->shadow_icov, d);
}

/* log p(c | backdrop or shadow), before the support's colours. */
static double backdrop_log_likelihood(const recon_colour_model *m, const float *c, const float *bc, const float *mc,
                                      const float *mbc)
{
    double d[3] = {c[0] - bc[0], c[1] - bc[1], c[2] - bc[2]};
    double l_bg = logsumexp2(m->bg_lognorm - 0.5 * recon_quad3(m->bg_icov, d),
                             m->tail_lognorm - 0.5 * recon_quad3(m->tail_icov, d));
    double k0 = shadow_factor(c, bc);
    double prior = 0;
    if (mc) {
        double km = shadow_factor(mc, mbc);
        if (k0 < 0.97 && km < 0.97 && fabs(k0 - km) < SHADOW_ALIKE)
            prior = log(SHADOW_SYMMETRIC_FACTOR);
    }
    return logsumexp2(l_bg, prior + shadow_log_density(m, c, bc));
}

/* -log p(c | not object) from the backdrop's log-likelihood l. */
static double cost_not_object(const recon_colour_model *m, const float *c, double l)
{
    if (m->have_support)
        l = logsumexp2(l, log(SUPPORT_PRIOR) + recon_gmm_log_density(&m->support, c));
    return -l;
}

void recon_colour_costs(const recon_colour_model *m, recon_cost_memo *memo, const float *c, const float *bc,
                        const float *mc, const float *mbc, double *cost_object, double *cost_backdrop)
{
    *cost_object = object_cost(m, memo, c);
    *cost_backdrop = cost_not_object(m, c, backdrop_log_likelihood(m, c, bc, mc, mbc));
}

/* ---- the axis of a mask */

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
            /* the median (the (n/2 + 1)-th smallest) is under best only if
             * that many residuals are: most lines fail this count, and skip
             * the selection */
            int under = 0;
            for (int k = 0; k < n; k++) {
                tmp[k] = fabs(xs[k] - a - b * ys[k]);
                under += tmp[k] < best;
            }
            if (under <= n / 2)
                continue;
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
    double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2], x = -beta * (d0 * d0 + d1 * d1 + d2 * d2);
    /* exp(0) is 1 and exp(x) is 0 below -746, without the call (equal
     * neighbours are common in a photo's flat parts) */
    double e = x == 0 ? 1.0 : (x < -746 ? 0.0 : exp(x));
    return SMOOTHNESS_GAMMA * e / (diagonal ? M_SQRT2 : 1);
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

/* ---- the steps of the segmentation */

/* What the rounds keep between steps. */
struct recon_segment_work {
    float *bgc;        /* w*h*3 backdrop colour */
    float *nlw;        /* w*h*4 smoothness weights */
    double *l_bg;      /* w*h log-likelihood of backdrop or shadow: fixed once the axis is */
    double *t_src, *t_snk; /* w*h the round's t-links */
    int *lab, *idx;    /* w*h */
    uint8_t *use;      /* w*h */
    long *area;
    int main_c;        /* the largest object component of lab */
    recon_gmm last_object; /* the object's model the t-links were computed with */
    recon_cost_memo memo;  /* its costs by colour */
    maxflow_graph *g;
};

/* The two mixtures are the same, bit for bit. */
static int same_gmm(const recon_gmm *a, const recon_gmm *b)
{
    if (a->k != b->k)
        return 0;
    for (int k = 0; k < a->k; k++)
        if (memcmp(a->mean[k], b->mean[k], sizeof a->mean[k]) || memcmp(a->icov[k], b->icov[k], sizeof a->icov[k]) ||
            a->lognorm[k] != b->lognorm[k])
            return 0;
    return 1;
}

int recon_segment_start(const image_t *img, const float *prior, recon_segmentation *seg)
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
    recon_segment_work *k = seg->work = calloc(1, sizeof *seg->work);
    if (!k)
        return -1;
    seg->rgb = downsample(img, f, w, h);
    seg->object = calloc(n, 1);
    if (prior && !(seg->prior = downsample_prior(prior, img->width, f, w, h)))
        return -1;
    k->bgc = malloc(n * 3 * sizeof *k->bgc);
    k->use = malloc(n);
    k->lab = malloc(n * sizeof *k->lab);
    k->idx = malloc(n * sizeof *k->idx);
    k->nlw = malloc(n * 4 * sizeof *k->nlw);
    k->l_bg = malloc(n * 3 * sizeof *k->l_bg);
    k->t_src = k->l_bg ? k->l_bg + n : NULL;
    k->t_snk = k->l_bg ? k->l_bg + 2 * n : NULL;
    k->g = maxflow_create((int)n, (int)(5 * n));
    if (!seg->rgb || !seg->object || !k->bgc || !k->use || !k->lab || !k->idx || !k->nlw || !k->l_bg || !k->g)
        return -1;

    /* The backdrop first from a ring along the image border (6% of the
     * shorter side), robustly: a stand or a caption reaching the border
     * weighs nothing. */
    uint8_t *use = k->use;
    int ring = (int)(0.06 * (w < h ? w : h)) + 2;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            use[(size_t)y * w + x] = x < ring || y < ring || x >= w - ring || y >= h - ring;
    if (recon_backdrop_fit(&seg->model.backdrop, seg->rgb, w, h, use, 1, 6, 4) != 0 ||
        recon_colour_model_prepare(&seg->model) != 0)
        return -1;
    eval_backdrop(&seg->model.backdrop, k->bgc);
    /* The initial object: what the backdrop cannot explain, or what the
     * network sees (a dark wall band or a floor shadow that the backdrop
     * cannot explain would give the object's model its colours). */
    for (size_t p = 0; p < n; p++) {
        double d[3];
        for (int c = 0; c < 3; c++)
            d[c] = seg->rgb[3 * p + c] - k->bgc[3 * p + c];
        seg->object[p] = seg->prior ? seg->prior[p] > 0.5f : recon_quad3(seg->model.bg_icov, d) > INIT_CHI2;
    }
    seg->beta = recon_contrast_beta(seg->rgb, w, h);
    smoothness_weights(seg, k->nlw);
    return 0;
}

int recon_segment_models(recon_segmentation *seg)
{
    recon_segment_work *k = seg->work;
    const int w = seg->w, h = seg->h;
    free(k->area);
    k->area = NULL;
    int nc = recon_mask_label(seg->object, w, h, k->lab, &k->area);
    if (nc < 0)
        return -1;
    k->main_c = largest_component(k->area, nc);
    /* Models from the current labels: the object's colours from its
     * largest component. */
    if (!k->main_c || fit_object_model(seg, k->lab, k->main_c, k->idx) != 0)
        return 1;
    /* The axis of the symmetry links comes from the initial object (what
     * the backdrop cannot explain: a highlight that the colour models will
     * take for backdrop is still there), and the rounds keep it. */
    if (seg->rounds == 0) {
        for (size_t p = 0; p < (size_t)w * h; p++)
            k->use[p] = k->lab[p] == k->main_c;
        seg->have_axis = recon_mask_axis(k->use, w, h, &seg->axis_x0, &seg->axis_slope) == 0;
    }
    return 0;
}

void recon_segment_data_terms(recon_segmentation *seg)
{
    recon_segment_work *k = seg->work;
    const int w = seg->w, h = seg->h;
    const double border = log((1 - BORDER_PRIOR_EPS) / BORDER_PRIOR_EPS);
    /* the mixture converged: the last round's t-links stand (and its cut) */
    if (seg->rounds > 0 && same_gmm(&seg->model.object, &k->last_object))
        return;
    k->last_object = seg->model.object;
    memset(&k->memo, 0, sizeof k->memo);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int p = y * w + x;
            const float *c = seg->rgb + 3 * (size_t)p;
            /* the backdrop's part depends on neither the object's model nor
             * the labels: the first round's serves them all */
            if (seg->rounds == 0) {
                int q = seg->have_axis ? recon_segment_mirror(seg, p) : -1;
                k->l_bg[p] = backdrop_log_likelihood(&seg->model, c, k->bgc + 3 * (size_t)p,
                                                     q >= 0 ? seg->rgb + 3 * (size_t)q : NULL,
                                                     q >= 0 ? k->bgc + 3 * (size_t)q : NULL);
            }
            double co = object_cost(&seg->model, &k->memo, c), cb = cost_not_object(&seg->model, c, k->l_bg[p]);
            if (x == 0 || y == 0 || x == w - 1 || y == h - 1)
                co += border;
            if (seg->prior) {
                double pi = fmin(fmax(seg->prior[p], PRIOR_EPS), 1 - PRIOR_EPS);
                co -= PRIOR_WEIGHT * log(pi);
                cb -= PRIOR_WEIGHT * log1p(-pi);
            }
            double lo = co < cb ? co : cb;
            /* the source side is the object: a pixel left on the sink side pays cb */
            k->t_src[p] = cb - lo;
            k->t_snk[p] = co - lo;
        }
}

int recon_segment_cut(recon_segmentation *seg)
{
    recon_segment_work *k = seg->work;
    const int w = seg->w, h = seg->h;
    const size_t n = (size_t)w * h;
    /* The links stay; later rounds change only the t-links and go on from
     * the last round's flow. */
    if (seg->rounds == 0) {
        maxflow_reset(k->g);
        add_smoothness(k->g, k->nlw, w, h);
        if (seg->have_axis)
            add_symmetry(k->g, seg);
        for (size_t p = 0; p < n; p++)
            maxflow_add_terminals(k->g, (int)p, k->t_src[p], k->t_snk[p]);
    } else {
        for (size_t p = 0; p < n; p++)
            maxflow_set_terminals(k->g, (int)p, k->t_src[p], k->t_snk[p]);
    }
    maxflow_solve(k->g);
    for (size_t p = 0; p < n; p++)
        seg->object[p] = (uint8_t)maxflow_source_side(k->g, (int)p);
    seg->rounds++;
    return 0;
}

static void work_free(recon_segment_work *k)
{
    if (!k)
        return;
    maxflow_destroy(k->g);
    free(k->area);
    free(k->lab);
    free(k->idx);
    free(k->nlw);
    free(k->use);
    free(k->bgc);
    free(k->l_bg);
    free(k);
}

int recon_segment(const image_t *img, const float *prior, recon_segmentation *seg)
{
    if (recon_segment_start(img, prior, seg) != 0)
        return -1;
    for (int r = 0; r < ROUNDS; r++) {
        int rc = recon_segment_models(seg);
        if (rc != 0)
            return rc;
        recon_segment_data_terms(seg);
        if (recon_segment_cut(seg) != 0)
            return -1;
    }
    /* the rounds' buffers are not needed after them */
    work_free(seg->work);
    seg->work = NULL;
    return 0;
}

void recon_segmentation_free(recon_segmentation *seg)
{
    work_free(seg->work);
    free(seg->rgb);
    free(seg->prior);
    free(seg->object);
    memset(seg, 0, sizeof *seg);
}
