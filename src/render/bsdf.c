/* BSDF dispatch, allocation, parameter validation and the plugin parameter table. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/bsdf_impl.h"

bsdf_t *bsdf_alloc(const char *plugin, const bsdf_ops *ops, unsigned flags, size_t data_size, char *err,
                   size_t errlen)
{
    /* Round the header up so the data that follows is suitably aligned. */
    size_t head = (sizeof(bsdf_t) + 15u) & ~(size_t)15u;
    bsdf_t *b = calloc(1, head + data_size);
    if (!b) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    b->plugin = plugin;
    b->ops = ops;
    b->flags = flags;
    b->data = (char *)b + head;
    return b;
}

int bsdf_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    memset(out, 0, sizeof *out);
    return b->ops->sample(b, q, u1, u2, out);
}

rgb bsdf_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    return b->ops->eval(b, q, wo);
}

double bsdf_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    return b->ops->pdf(b, q, wo);
}

unsigned bsdf_flags(const bsdf_t *b)
{
    return b->flags;
}

rgb bsdf_albedo(const bsdf_t *b, vec2 uv)
{
    return b->ops->albedo(b, uv);
}

rgb bsdf_straight_transmittance(const bsdf_t *b, const bsdf_query *q)
{
    return b->flags & BSDF_STRAIGHT_TRANSMISSION ? b->ops->straight(b, q) : rgb_gray(0.0);
}

const char *bsdf_plugin_name(const bsdf_t *b)
{
    return b->plugin;
}

void bsdf_free(bsdf_t *b)
{
    free(b);
}

rgb bsdf_eval_delta_only(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    (void)b;
    (void)q;
    (void)wo;
    return rgb_gray(0.0);
}

double bsdf_pdf_delta_only(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    (void)b;
    (void)q;
    (void)wo;
    return 0.0;
}

int bsdf_finish_sample(const bsdf_t *b, const bsdf_query *q, bsdf_sample_rec *out)
{
    double pdf = b->ops->pdf(b, q, out->wo);
    if (!(pdf > 0.0) || !isfinite(pdf))
        return 0;
    rgb f = b->ops->eval(b, q, out->wo);
    out->pdf = pdf;
    out->weight = rgb_scale(f, 1.0 / pdf);
    return 1;
}

int bsdf_check_ior(double int_ior, double ext_ior, char *err, size_t errlen)
{
    if (!(int_ior > 0.0) || !isfinite(int_ior)) {
        snprintf(err, errlen, "int_ior must be a positive number, got %g", int_ior);
        return -1;
    }
    if (!(ext_ior > 0.0) || !isfinite(ext_ior)) {
        snprintf(err, errlen, "ext_ior must be a positive number, got %g", ext_ior);
        return -1;
    }
    return 0;
}

int bsdf_check_alpha(const char *name, double alpha, char *err, size_t errlen)
{
    if (!(alpha >= 0.0) || !isfinite(alpha)) {
        snprintf(err, errlen, "%s must be a non-negative number, got %g", name, alpha);
        return -1;
    }
    return 0;
}

int bsdf_check_spectrum(const char *name, const bsdf_spectrum *s, char *err, size_t errlen)
{
    if (s->texture)
        return 0;
    rgb v = s->value;
    if (!(v.r >= 0.0 && v.g >= 0.0 && v.b >= 0.0) || !isfinite(v.r + v.g + v.b)) {
        snprintf(err, errlen, "%s must be non-negative, got (%g, %g, %g)", name, v.r, v.g, v.b);
        return -1;
    }
    return 0;
}

const char *const *bsdf_plugin_params(const char *plugin)
{
    static const char *const diffuse[] = {"reflectance", NULL};
    static const char *const dielectric[] = {"int_ior", "ext_ior", "specular_reflectance", "specular_transmittance",
                                             NULL};
    static const char *const roughdielectric[] = {"int_ior", "ext_ior", "specular_reflectance",
                                                  "specular_transmittance", "distribution", "alpha", "alpha_u",
                                                  "alpha_v", "sample_visible", NULL};
    static const char *const conductor[] = {"material", "eta", "k", "specular_reflectance", NULL};
    static const char *const roughconductor[] = {"material", "eta", "k", "specular_reflectance", "distribution",
                                                 "alpha", "alpha_u", "alpha_v", "sample_visible", NULL};
    static const char *const plastic[] = {"diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior",
                                          "nonlinear", NULL};
    static const char *const roughplastic[] = {"diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior",
                                               "nonlinear", "distribution", "alpha", "sample_visible", NULL};
    static const char *const twosided[] = {NULL};
    static const struct {
        const char *name;
        const char *const *params;
    } table[] = {
        {"diffuse", diffuse},       {"dielectric", dielectric},         {"thindielectric", dielectric},
        {"roughdielectric", roughdielectric}, {"conductor", conductor}, {"roughconductor", roughconductor},
        {"plastic", plastic},       {"roughplastic", roughplastic},     {"twosided", twosided},
    };
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (strcmp(plugin, table[i].name) == 0)
            return table[i].params;
    return NULL;
}
