/* Warps and tabulated distributions; see sampling.h. */
#include "celadon/sampling.h"

#include <stdlib.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

vec2 warp_square_to_concentric_disk(vec2 u)
{
    double a = 2.0 * u.x - 1.0, b = 2.0 * u.y - 1.0;
    if (a == 0.0 && b == 0.0)
        return v2(0.0, 0.0);
    double r, phi;
    if (fabs(a) > fabs(b)) {
        r = a;
        phi = (M_PI / 4.0) * (b / a);
    } else {
        r = b;
        phi = M_PI / 2.0 - (M_PI / 4.0) * (a / b);
    }
    return v2(r * cos(phi), r * sin(phi));
}

double warp_concentric_disk_pdf(vec2 p)
{
    return v2_dot(p, p) <= 1.0 ? 1.0 / M_PI : 0.0;
}

vec3 warp_square_to_cosine_hemisphere(vec2 u)
{
    vec2 d = warp_square_to_concentric_disk(u);
    double z = sqrt(fmax(0.0, 1.0 - d.x * d.x - d.y * d.y));
    return v3(d.x, d.y, z);
}

double warp_cosine_hemisphere_pdf(vec3 w)
{
    return w.z > 0.0 ? w.z / M_PI : 0.0;
}

vec3 warp_square_to_uniform_hemisphere(vec2 u)
{
    double z = u.x, r = sqrt(fmax(0.0, 1.0 - z * z)), phi = 2.0 * M_PI * u.y;
    return v3(r * cos(phi), r * sin(phi), z);
}

double warp_uniform_hemisphere_pdf(vec3 w)
{
    return w.z >= 0.0 ? 1.0 / (2.0 * M_PI) : 0.0;
}

vec3 warp_square_to_uniform_sphere(vec2 u)
{
    double z = 1.0 - 2.0 * u.x, r = sqrt(fmax(0.0, 1.0 - z * z)), phi = 2.0 * M_PI * u.y;
    return v3(r * cos(phi), r * sin(phi), z);
}

double warp_uniform_sphere_pdf(void)
{
    return 1.0 / (4.0 * M_PI);
}

vec3 warp_square_to_uniform_cone(vec2 u, double cos_max)
{
    double z = 1.0 - u.x * (1.0 - cos_max);
    double r = sqrt(fmax(0.0, 1.0 - z * z)), phi = 2.0 * M_PI * u.y;
    return v3(r * cos(phi), r * sin(phi), z);
}

double warp_uniform_cone_pdf(vec3 w, double cos_max)
{
    return w.z >= cos_max && cos_max < 1.0 ? 1.0 / (2.0 * M_PI * (1.0 - cos_max)) : 0.0;
}

vec2 warp_square_to_uniform_triangle(vec2 u)
{
    /* Fold the square along its diagonal: area-preserving onto the triangle. */
    if (u.x + u.y > 1.0)
        return v2(1.0 - u.x, 1.0 - u.y);
    return u;
}

static inline double clamp(double x, double lo, double hi) { return x < lo ? lo : x > hi ? hi : x; }

/* The interior angle of the spherical rectangle at a corner, as its cosine
 * and sine: -n_a . n_b and |n_a x n_b| of the unit normals of the planes
 * through o and the two edges that meet there, which for the corner
 * (x, y, z0) at distance len from o are (cos_num, |z0| len) over
 * sqrt(z0^2 + x^2) sqrt(z0^2 + y^2) (cos_num's sign depends on the
 * corner); exact near 0 and pi, where sqrt(1 - cos^2) would lose the
 * digits. */
typedef struct {
    double c, s;
} unit_complex;

static unit_complex corner_angle(double cos_num, double len, double z0, double ax, double ay)
{
    double inv = 1.0 / (ax * ay);
    return (unit_complex){clamp(cos_num * inv, -1.0, 1.0), fabs(z0) * len * inv};
}

/* tan(omega / 2) of the triangle o, a, b, c as the fraction (num over the
 * returned denominator; Van Oosterom & Strackee 1983): num = |a . (b x c)|,
 * la, lb, lc the corners' distances from o. */
static double triangle_half_tan_den(vec3 a, vec3 b, vec3 c, double la, double lb, double lc)
{
    return la * lb * lc + v3_dot(a, b) * lc + v3_dot(a, c) * lb + v3_dot(b, c) * la;
}

double spherical_rect_init(spherical_rect *r, vec3 o, vec3 corner, vec3 edge_u, vec3 edge_v)
{
    double lu = v3_len(edge_u), lv = v3_len(edge_v);
    r->o = o;
    r->x = v3_scale(edge_u, 1.0 / lu);
    r->y = v3_scale(edge_v, 1.0 / lv);
    r->z = v3_cross(r->x, r->y);
    vec3 d = v3_sub(corner, o);
    r->x0 = v3_dot(d, r->x), r->y0 = v3_dot(d, r->y), r->z0 = v3_dot(d, r->z);
    if (r->z0 > 0.0) { /* the frame's z points from the rectangle toward o */
        r->z0 = -r->z0;
        r->z = v3_neg(r->z);
    }
    r->x1 = r->x0 + lu, r->y1 = r->y0 + lv;
    r->solid_angle = 0.0;
    if (!(r->z0 < 0.0))
        return 0.0;
    /* The corners from o, in the frame. */
    vec3 p00 = v3(r->x0, r->y0, r->z0), p10 = v3(r->x1, r->y0, r->z0);
    vec3 p11 = v3(r->x1, r->y1, r->z0), p01 = v3(r->x0, r->y1, r->z0);
    double l00 = v3_len(p00), l10 = v3_len(p10), l11 = v3_len(p11), l01 = v3_len(p01);
    /* The planes through o and each edge have the normals n0 = (0, z0, -y0),
     * n1 = (-z0, 0, x1), n2 = (0, -z0, y1), n3 = (z0, 0, -x0) (over their
     * lengths); Urena et al.'s internal angles g_i = acos(-n_i . n_(i+1))
     * are kept as cosine and sine, never as angles: the constant
     * k = 2 pi - g2 - g3 enters the sampler only through its cosine and
     * sine. */
    double z2 = r->z0 * r->z0;
    double ax0 = sqrt(z2 + r->x0 * r->x0);
    double ay0 = sqrt(z2 + r->y0 * r->y0), ay1 = sqrt(z2 + r->y1 * r->y1);
    unit_complex g2 = corner_angle(r->x0 * r->y1, l01, r->z0, ax0, ay1);
    unit_complex g3 = corner_angle(-r->x0 * r->y0, l00, r->z0, ax0, ay0);
    r->b0 = -r->y0 / ay0, r->b1 = r->y1 / ay1; /* n0.z, n2.z */
    r->b0_comp = z2 / (ay0 * ay0);              /* 1 - b0^2 without cancellation */
    /* cos k = cos(g2 + g3), sin k = -sin(g2 + g3). */
    r->cos_k = g2.c * g3.c - g2.s * g3.s;
    r->sin_k = -(g2.s * g3.c + g2.c * g3.s);
    /* The solid angle, in [0, 2 pi), as the two triangles' (p00, p10, p11)
     * and (p00, p11, p01): both have the triple product z0 lu lv, and the
     * sum of their half-angles, in [0, pi), is the argument of the product
     * (d1 + i num)(d2 + i num), one atan2 (its sine >= 0 but for
     * rounding). */
    double num = fabs(r->z0) * lu * lv;
    double d1 = triangle_half_tan_den(p00, p10, p11, l00, l10, l11);
    double d2 = triangle_half_tan_den(p00, p11, p01, l00, l11, l01);
    r->solid_angle = 2.0 * atan2(fmax(num * (d1 + d2), 0.0), d1 * d2 - num * num);
    return r->solid_angle;
}

vec3 spherical_rect_sample(const spherical_rect *r, vec2 u)
{
    /* u.x picks the x where the solid angle to its left is u.x S: the angle
     * au = u.x S + k, whose sine and cosine come from those of u.x S turned
     * by k ... */
    double sin_us, cos_us;
    sincos(u.x * r->solid_angle, &sin_us, &cos_us);
    double cos_au = cos_us * r->cos_k - sin_us * r->sin_k, sin_au = sin_us * r->cos_k + cos_us * r->sin_k;
    /* Urena et al.'s fu = n / sin(au), cu = sign(fu) / sqrt(fu^2 + b0^2)
     * and xu = -cu z0 / sqrt(1 - cu^2) fold into
     * xu = -z0 sign(fu) / sqrt(fu^2 - (1 - b0^2)), written over sin(au)
     * (one square root, no division by sin(au)); where the root's argument
     * is not positive xu is beyond the rectangle on sign(fu)'s side. */
    double n = cos_au * r->b0 - r->b1, den2 = n * n - r->b0_comp * sin_au * sin_au;
    double num = -r->z0 * (n > 0.0 ? sin_au : -sin_au);
    double xu = clamp(den2 > 0.0 ? num / sqrt(den2) : copysign(INFINITY, num), r->x0, r->x1);
    /* ... and u.y the y along that line, uniform in the sine of its
     * elevation, which is uniform in solid angle. */
    double d2 = xu * xu + r->z0 * r->z0;
    double h0 = r->y0 / sqrt(d2 + r->y0 * r->y0), h1 = r->y1 / sqrt(d2 + r->y1 * r->y1);
    double hv = h0 + u.y * (h1 - h0), hv2 = hv * hv;
    double yv = hv2 < 1.0 - 1e-12 ? clamp(hv * sqrt(d2 / (1.0 - hv2)), r->y0, r->y1) : r->y1;
    return v3_add(r->o, v3_add(v3_add(v3_scale(r->x, xu), v3_scale(r->y, yv)), v3_scale(r->z, r->z0)));
}

double mis_power_heuristic(double pdf_f, double pdf_g)
{
    double f2 = pdf_f * pdf_f, g2 = pdf_g * pdf_g;
    if (isinf(f2))
        return 1.0;
    return f2 + g2 > 0.0 ? f2 / (f2 + g2) : 0.0;
}

int distribution1d_init(distribution1d *d, const double *func, int n)
{
    d->n = 0;
    d->func = d->cdf = NULL;
    d->integral = 0.0;
    if (n < 1)
        return -1;
    d->func = malloc((size_t)n * sizeof *d->func);
    d->cdf = malloc((size_t)(n + 1) * sizeof *d->cdf);
    if (!d->func || !d->cdf) {
        distribution1d_free(d);
        return -1;
    }
    d->n = n;
    d->cdf[0] = 0.0;
    for (int i = 0; i < n; i++) {
        d->func[i] = func[i] > 0.0 && isfinite(func[i]) ? func[i] : 0.0;
        d->cdf[i + 1] = d->cdf[i] + d->func[i] / n;
    }
    d->integral = d->cdf[n];
    for (int i = 1; i <= n; i++)
        d->cdf[i] = d->integral > 0.0 ? d->cdf[i] / d->integral : (double)i / n;
    d->cdf[n] = 1.0;
    return 0;
}

void distribution1d_free(distribution1d *d)
{
    free(d->func);
    free(d->cdf);
    d->func = d->cdf = NULL;
    d->n = 0;
}

/* Largest i in [0, n-1] with cdf[i] <= u. */
static int find_cell(const distribution1d *d, double u)
{
    int lo = 0, hi = d->n - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (d->cdf[mid] <= u)
            lo = mid;
        else
            hi = mid - 1;
    }
    /* Skip zero-probability cells that share the same cdf value. */
    while (lo < d->n - 1 && d->cdf[lo + 1] <= u)
        lo++;
    return lo;
}

double distribution1d_pmf(const distribution1d *d, int cell)
{
    return d->cdf[cell + 1] - d->cdf[cell];
}

double distribution1d_sample_continuous(const distribution1d *d, double u, double *pdf, int *cell)
{
    int i = find_cell(d, u);
    double w = distribution1d_pmf(d, i);
    double t = w > 0.0 ? (u - d->cdf[i]) / w : 0.5;
    if (t >= 1.0)
        t = nextafter(1.0, 0.0);
    if (pdf)
        *pdf = w * d->n;
    if (cell)
        *cell = i;
    return (i + t) / d->n;
}

int distribution1d_sample_discrete(const distribution1d *d, double u, double *pmf, double *u_reuse)
{
    int i = find_cell(d, u);
    double w = distribution1d_pmf(d, i);
    if (pmf)
        *pmf = w;
    if (u_reuse) {
        double t = w > 0.0 ? (u - d->cdf[i]) / w : 0.0;
        *u_reuse = t < 1.0 ? t : nextafter(1.0, 0.0);
    }
    return i;
}

double distribution1d_pdf(const distribution1d *d, double x)
{
    if (!(x >= 0.0 && x < 1.0))
        return 0.0;
    int i = (int)(x * d->n);
    if (i >= d->n)
        i = d->n - 1;
    return distribution1d_pmf(d, i) * d->n;
}

int distribution2d_init(distribution2d *d, const double *f, int nu, int nv)
{
    d->nu = nu;
    d->nv = nv;
    d->conditional = NULL;
    d->marginal = (distribution1d){0};
    if (nu < 1 || nv < 1)
        return -1;
    d->conditional = calloc((size_t)nv, sizeof *d->conditional);
    double *rows = malloc((size_t)nv * sizeof *rows);
    int ok = d->conditional && rows;
    for (int v = 0; ok && v < nv; v++) {
        ok = distribution1d_init(&d->conditional[v], f + (size_t)v * nu, nu) == 0;
        if (ok)
            rows[v] = d->conditional[v].integral;
    }
    ok = ok && distribution1d_init(&d->marginal, rows, nv) == 0;
    free(rows);
    if (!ok) {
        distribution2d_free(d);
        return -1;
    }
    return 0;
}

void distribution2d_free(distribution2d *d)
{
    if (d->conditional)
        for (int v = 0; v < d->nv; v++)
            distribution1d_free(&d->conditional[v]);
    free(d->conditional);
    d->conditional = NULL;
    distribution1d_free(&d->marginal);
}

vec2 distribution2d_sample(const distribution2d *d, vec2 u, double *pdf)
{
    double pv, pu;
    int row;
    double y = distribution1d_sample_continuous(&d->marginal, u.y, &pv, &row);
    double x = distribution1d_sample_continuous(&d->conditional[row], u.x, &pu, NULL);
    if (pdf)
        *pdf = pv * pu;
    return v2(x, y);
}

double distribution2d_pdf(const distribution2d *d, vec2 p)
{
    double pv = distribution1d_pdf(&d->marginal, p.y);
    if (pv == 0.0)
        return 0.0;
    int row = (int)(p.y * d->nv);
    if (row >= d->nv)
        row = d->nv - 1;
    return pv * distribution1d_pdf(&d->conditional[row], p.x);
}
