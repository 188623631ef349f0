/* What the public API lets a caller read of a built scene (scene.h): its
 * render settings, and probes of its camera and geometry. */
#include <math.h>
#include <string.h>

#include "render/scene_impl.h"

void scene_film_size(const scene_t *s, int *width, int *height)
{
    *width = s->film.crop_w;
    *height = s->film.crop_h;
}

int scene_spp(const scene_t *s) { return (int)s->sampler.sample_count; }
uint64_t scene_seed(const scene_t *s) { return s->sampler.seed; }
uint64_t scene_digest(const scene_t *s) { return s->digest; }

long long scene_triangle_count(const scene_t *s)
{
    long long n = 0;
    for (int i = 0; i < s->shapes.count; i++)
        n += s->shapes.items[i].is_mesh ? s->shapes.items[i].mesh.n_tris : 0;
    return n;
}

int scene_shapes_of_type(const scene_t *s, const char *type)
{
    int n = 0;
    for (int i = 0; i < s->shapes.count; i++)
        n += strcmp(s->shapes.items[i].type, type) == 0;
    return n;
}

ray3 scene_camera_ray(const scene_t *s, int px, int py, double sx, double sy, double *tmin, double *tmax)
{
    camera_ray_t cr = camera_ray(&s->camera, px, py, sx, sy);
    *tmin = cr.tmin;
    *tmax = cr.tmax;
    return cr.ray;
}

bool scene_first_hit(const scene_t *s, const ray3 *r, double tmin, double tmax, scene_hit *hit)
{
    surface_hit h;
    if (!shape_list_intersect(&s->shapes, r, tmin, tmax, &h))
        return false;
    hit->t = h.t;
    hit->n = h.sh.n;
    hit->eps = h.eps;
    hit->shape = (int)(h.shape - s->shapes.items);
    hit->shape_type = h.shape->type;
    hit->sheet = (bsdf_flags(h.shape->bsdf) & BSDF_STRAIGHT_TRANSMISSION) != 0;
    return true;
}

rgb scene_radiance(const scene_t *s, const ray3 *r, double tmin, double tmax, uint32_t px, uint32_t py,
                   double *variance)
{
    integrator_scene sc = {&s->shapes, &s->emitters, s->camera_medium};
    rgb sum = {0, 0, 0};
    double sum_y2 = 0;
    long long n = s->sampler.sample_count;
    for (long long k = 0; k < n; k++) {
        sampler_stream smp;
        sampler_start(&s->sampler, &smp, px, py, (uint32_t)k);
        rgb L = integrator_li(s->integrator, &sc, r, tmin, tmax, &smp, NULL);
        sum.r += L.r, sum.g += L.g, sum.b += L.b;
        sum_y2 += rgb_luminance(L) * rgb_luminance(L);
    }
    rgb mean = {sum.r / (double)n, sum.g / (double)n, sum.b / (double)n};
    if (variance) {
        double y = rgb_luminance(mean);
        *variance = n > 1 ? fmax(sum_y2 / (double)n - y * y, 0.0) / (double)(n - 1) : 0.0;
    }
    return mean;
}
