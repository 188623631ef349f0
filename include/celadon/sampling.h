/* Sample warps (unit square -> domain) with their densities, piecewise-constant
 * 1D/2D distributions (environment-map importance sampling), and the MIS power
 * heuristic. Directions are in a local frame with z up; densities are per unit
 * solid angle (sphere/hemisphere/cone) or per unit area (disk, square). */
#ifndef CELADON_SAMPLING_H
#define CELADON_SAMPLING_H

#include "celadon/vecmath.h"

/* Shirley-Chiu concentric map onto the unit disk (area-preserving up to 1/pi). */
vec2 warp_square_to_concentric_disk(vec2 u);
double warp_concentric_disk_pdf(vec2 p);

vec3 warp_square_to_cosine_hemisphere(vec2 u);
double warp_cosine_hemisphere_pdf(vec3 w);

vec3 warp_square_to_uniform_hemisphere(vec2 u);
double warp_uniform_hemisphere_pdf(vec3 w);

vec3 warp_square_to_uniform_sphere(vec2 u);
double warp_uniform_sphere_pdf(void);

/* Uniform directions in the cone of half-angle acos(cos_max) around +z. */
vec3 warp_square_to_uniform_cone(vec2 u, double cos_max);
double warp_uniform_cone_pdf(vec3 w, double cos_max);

/* Uniform barycentrics (b1, b2) on a triangle; b0 = 1 - b1 - b2. Density 2 on
 * the reference triangle (divide by the triangle's area for an area density). */
vec2 warp_square_to_uniform_triangle(vec2 u);

/* Uniform sampling of the solid angle a rectangle subtends from a point
 * (Urena, Fajardo & King 2013, "An area-preserving parametrization for
 * spherical rectangles"): the rectangle corner + a edge_u + b edge_v,
 * (a, b) in [0,1]^2, edge_u and edge_v orthogonal. */
typedef struct {
    vec3 o, x, y, z;              /* the reference point and the rectangle's frame (z away from o) */
    double x0, x1, y0, y1, z0;    /* the rectangle in that frame, seen from o */
    double b0, b1, b0_comp;       /* the parametrization's constants (b0_comp = 1 - b0^2) */
    double cos_k, sin_k;          /* and its k, as cosine and sine */
    double solid_angle;
} spherical_rect;

/* Sets r up for the rectangle seen from o; returns its solid angle (0 when
 * o lies in its plane). */
double spherical_rect_init(spherical_rect *r, vec3 o, vec3 corner, vec3 edge_u, vec3 edge_v);
/* The point of the rectangle whose direction from o is u's image under the
 * area-preserving map: uniform in solid angle (density 1 / solid_angle). */
vec3 spherical_rect_sample(const spherical_rect *r, vec2 u);

/* Veach's power heuristic (beta = 2): weight of a sample from strategy f. */
double mis_power_heuristic(double pdf_f, double pdf_g);

/* Piecewise-constant density on [0,1) with n equal cells. */
typedef struct {
    int n;
    double *func;    /* n cell values, as given (negatives clamped to 0) */
    double *cdf;     /* n + 1 entries, cdf[0] = 0, cdf[n] = 1 */
    double integral; /* sum(func) / n; 0 means all-zero input (sampled uniformly) */
} distribution1d;

/* Returns 0, or -1 when n < 1 or out of memory. */
int distribution1d_init(distribution1d *d, const double *func, int n);
void distribution1d_free(distribution1d *d);
/* Continuous sample x in [0,1); *pdf = density at x; *cell = its cell. */
double distribution1d_sample_continuous(const distribution1d *d, double u, double *pdf, int *cell);
/* Discrete cell with probability func/sum; *pmf its probability; *u_reuse the
 * rescaled remainder of u, uniform in [0,1) again. Pointers may be NULL. */
int distribution1d_sample_discrete(const distribution1d *d, double u, double *pmf, double *u_reuse);
double distribution1d_pdf(const distribution1d *d, double x);
double distribution1d_pmf(const distribution1d *d, int cell);

/* Piecewise-constant density on [0,1)^2 from nu x nv cells, f row-major with
 * f[v * nu + u]: a marginal over rows and one conditional per row. */
typedef struct {
    int nu, nv;
    distribution1d *conditional; /* nv rows */
    distribution1d marginal;     /* over v */
} distribution2d;

int distribution2d_init(distribution2d *d, const double *f, int nu, int nv);
void distribution2d_free(distribution2d *d);
/* Point p in [0,1)^2 with density *pdf (per unit square area). */
vec2 distribution2d_sample(const distribution2d *d, vec2 u, double *pdf);
double distribution2d_pdf(const distribution2d *d, vec2 p);

#endif
