/* Reading and checking the parameters several BSDF plugins take: colors or
 * textures, indices of refraction, conductor presets, roughness. */
#include <stdarg.h>
#include <stdio.h>

#include "bsdfs/bsdf_impl.h"

int bsdf_refuse(const scene_obj *o, char *err, size_t errlen, const char *fmt, ...)
{
    char why[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    return scene_obj_error(o, err, errlen, "<bsdf type='%s'>: %s", o->type, why);
}

int bsdf_spectrum_param(bsdf_set *set, scene_obj *o, const char *name, double def, bsdf_spectrum *out, char *err,
                        size_t errlen)
{
    scene_obj *tex = scene_obj_texture(o, name);
    if (tex) {
        const texture_t *t = texture_set_get(set->textures, tex, err, errlen);
        if (!t)
            return -1;
        *out = (bsdf_spectrum){rgb_gray(0.0), t};
        return 0;
    }
    scene_rgb c = scene_obj_rgb(o, name, (scene_rgb){def, def, def});
    *out = (bsdf_spectrum){rgb_make(c.r, c.g, c.b), NULL};
    return 0;
}

int bsdf_ior_param(scene_obj *o, const char *name, double def, double *out, char *err, size_t errlen)
{
    scene_prop *p = scene_obj_prop(o, name);
    if (!p) {
        *out = def;
        return 0;
    }
    if (p->type != SCENE_STRING) {
        *out = p->value.f;
        return 0;
    }
    if (bsdf_ior_lookup(p->value.s, out) != 0)
        return scene_obj_error(o, err, errlen, "unknown index of refraction name");
    return 0;
}

int bsdf_ior_pair_param(scene_obj *o, const char *inside, double *int_ior, double *ext_ior, char *err,
                        size_t errlen)
{
    double in, air;
    bsdf_ior_lookup(inside, &in);
    bsdf_ior_lookup("air", &air);
    if (bsdf_ior_param(o, "int_ior", in, int_ior, err, errlen) != 0 ||
        bsdf_ior_param(o, "ext_ior", air, ext_ior, err, errlen) != 0)
        return -1;
    return 0;
}

int bsdf_dielectric_param(bsdf_set *set, scene_obj *o, double *int_ior, double *ext_ior, bsdf_spectrum *reflectance,
                          bsdf_spectrum *transmittance, char *err, size_t errlen)
{
    if (bsdf_ior_pair_param(o, "bk7", int_ior, ext_ior, err, errlen) != 0 ||
        bsdf_spectrum_param(set, o, "specular_reflectance", 1.0, reflectance, err, errlen) != 0 ||
        bsdf_spectrum_param(set, o, "specular_transmittance", 1.0, transmittance, err, errlen) != 0)
        return -1;
    return 0;
}

int bsdf_smooth_dielectric_param(bsdf_set *set, scene_obj *o, double *eta, bsdf_spectrum *reflectance,
                                 bsdf_spectrum *transmittance, char *err, size_t errlen)
{
    double int_ior, ext_ior;
    if (bsdf_dielectric_param(set, o, &int_ior, &ext_ior, reflectance, transmittance, err, errlen) != 0 ||
        bsdf_check_ior(o, int_ior, ext_ior, err, errlen) ||
        bsdf_check_spectrum(o, "specular_reflectance", reflectance, err, errlen) ||
        bsdf_check_spectrum(o, "specular_transmittance", transmittance, err, errlen))
        return -1;
    *eta = int_ior / ext_ior;
    return 0;
}

int bsdf_plastic_param(bsdf_set *set, scene_obj *o, double *int_ior, double *ext_ior, bsdf_spectrum *diffuse,
                       bsdf_spectrum *specular, int *nonlinear, char *err, size_t errlen)
{
    if (bsdf_ior_pair_param(o, "polypropylene", int_ior, ext_ior, err, errlen) != 0 ||
        bsdf_spectrum_param(set, o, "diffuse_reflectance", 0.5, diffuse, err, errlen) != 0 ||
        bsdf_spectrum_param(set, o, "specular_reflectance", 1.0, specular, err, errlen) != 0)
        return -1;
    *nonlinear = scene_obj_bool(o, "nonlinear", false);
    return 0;
}

double bsdf_specular_sampling_weight(const bsdf_spectrum *diffuse, const bsdf_spectrum *specular)
{
    double dm = spectrum_mean(diffuse), sm = spectrum_mean(specular);
    return dm + sm > 0.0 ? sm / (dm + sm) : 0.5;
}

/* A constant color parameter that must not be a texture. */
static int color_only(scene_obj *o, const char *name, rgb *inout)
{
    if (scene_obj_texture(o, name))
        return -1;
    scene_rgb c = scene_obj_rgb(o, name, (scene_rgb){inout->r, inout->g, inout->b});
    *inout = rgb_make(c.r, c.g, c.b);
    return 0;
}

int bsdf_conductor_param(scene_obj *o, rgb *eta, rgb *k, char *err, size_t errlen)
{
    bsdf_conductor_preset("none", eta, k);
    const char *material = scene_obj_string(o, "material", NULL);
    if (material && bsdf_conductor_preset(material, eta, k) != 0)
        return scene_obj_error(o, err, errlen, "unknown conductor material '%s'", material);
    if (color_only(o, "eta", eta) != 0 || color_only(o, "k", k) != 0)
        return scene_obj_error(o, err, errlen, "textured eta or k is not supported");
    return 0;
}

int bsdf_scalar_param(bsdf_set *set, scene_obj *o, const char *name, double def, bsdf_scalar *out, char *err,
                      size_t errlen)
{
    bsdf_spectrum s;
    if (bsdf_spectrum_param(set, o, name, def, &s, err, errlen) != 0)
        return -1;
    /* A color (where the declaration allows one) is read as its luminance. */
    rgb c = s.value;
    *out = (bsdf_scalar){c.r == c.g && c.g == c.b ? c.r : rgb_luminance(c), s.texture};
    return 0;
}

int bsdf_roughness_param(bsdf_set *set, scene_obj *o, bsdf_roughness *out, char *err, size_t errlen)
{
    out->type = MICROFACET_BECKMANN;
    microfacet_type_parse(scene_obj_string(o, "distribution", "beckmann"), &out->type);
    bsdf_scalar a;
    if (bsdf_scalar_param(set, o, "alpha", 0.1, &a, err, errlen) != 0)
        return -1;
    if (scene_obj_has(o, "alpha_u") != scene_obj_has(o, "alpha_v"))
        return bsdf_refuse(o, err, errlen, "give both alpha_u and alpha_v (or alpha)");
    out->alpha_u = out->alpha_v = a;
    if ((scene_obj_has(o, "alpha_u") && bsdf_scalar_param(set, o, "alpha_u", 0.1, &out->alpha_u, err, errlen) != 0) ||
        (scene_obj_has(o, "alpha_v") && bsdf_scalar_param(set, o, "alpha_v", 0.1, &out->alpha_v, err, errlen) != 0))
        return -1;
    out->sample_visible = scene_obj_bool(o, "sample_visible", true);
    if ((!out->alpha_u.texture && bsdf_check_alpha(o, "alpha_u", out->alpha_u.value, err, errlen) != 0) ||
        (!out->alpha_v.texture && bsdf_check_alpha(o, "alpha_v", out->alpha_v.value, err, errlen) != 0))
        return -1;
    return 0;
}

int bsdf_check_ior(const scene_obj *o, double int_ior, double ext_ior, char *err, size_t errlen)
{
    if (!(int_ior > 0.0) || !isfinite(int_ior))
        return bsdf_refuse(o, err, errlen, "int_ior must be a positive number, got %g", int_ior);
    if (!(ext_ior > 0.0) || !isfinite(ext_ior))
        return bsdf_refuse(o, err, errlen, "ext_ior must be a positive number, got %g", ext_ior);
    return 0;
}

int bsdf_check_alpha(const scene_obj *o, const char *name, double alpha, char *err, size_t errlen)
{
    if (!(alpha >= 0.0) || !isfinite(alpha))
        return bsdf_refuse(o, err, errlen, "%s must be a non-negative number, got %g", name, alpha);
    return 0;
}

int bsdf_check_spectrum(const scene_obj *o, const char *name, const bsdf_spectrum *s, char *err, size_t errlen)
{
    if (s->texture)
        return 0;
    rgb v = s->value;
    if (!(v.r >= 0.0 && v.g >= 0.0 && v.b >= 0.0) || !isfinite(v.r + v.g + v.b))
        return bsdf_refuse(o, err, errlen, "%s must be non-negative, got (%g, %g, %g)", name, v.r, v.g, v.b);
    return 0;
}
