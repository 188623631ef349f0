/* <bsdf> and <texture> objects of the description tree mapped onto the
 * constructors of bsdf.h and texture.h, with Mitsuba's defaults. Objects
 * referenced from several places are built once. */
#include <stdlib.h>
#include <string.h>

#include "render/scene_impl.h"

#define FAIL(o, ...)                                                         \
    do {                                                                     \
        char msg_[1024];                                                      \
        snprintf(msg_, sizeof msg_, __VA_ARGS__);                            \
        snprintf(err, errlen, "%s:%d: %s", (o)->file, (o)->line, msg_);      \
        return NULL;                                                         \
    } while (0)

/* Built objects are kept with the description object they came from
 * (keys[i] for objs[i]), so a referenced one is built once. */
static void *built_find(void *const *objs, const scene_obj *const *keys, int n, const scene_obj *key)
{
    for (int i = 0; i < n; i++)
        if (keys[i] == key)
            return objs[i];
    return NULL;
}

static int built_add(void ***objs, const scene_obj ***keys, int *n, const scene_obj *key, void *value)
{
    void **a = realloc(*objs, sizeof *a * (size_t)(*n + 1));
    if (!a)
        return -1;
    *objs = a;
    const scene_obj **k = realloc(*keys, sizeof *k * (size_t)(*n + 1));
    if (!k)
        return -1;
    *keys = k;
    a[*n] = value;
    k[*n] = key;
    (*n)++;
    return 0;
}

static uv_transform to_uv_of(scene_obj *o)
{
    transform4 t = scene_obj_transform(o, "to_uv");
    uv_transform u;
    for (int i = 0; i < 2; i++)
        u.m[i][0] = t.m[i][0], u.m[i][1] = t.m[i][1], u.m[i][2] = t.m[i][3];
    return u;
}

static rgb to_rgb(scene_rgb c) { return rgb_make(c.r, c.g, c.b); }

const texture_t *scene_build_texture(struct scene *s, scene_obj *o, char *err, size_t errlen)
{
    texture_t *t = built_find((void *const *)s->textures, s->texture_keys, s->ntextures, o);
    if (t)
        return t;
    char why[512] = "";
    if (!strcmp(o->type, "bitmap")) {
        texture_bitmap_params p = texture_bitmap_defaults();
        p.filename = scene_obj_string(o, "filename", NULL);
        p.raw = scene_obj_bool(o, "raw", false);
        const char *filter = scene_obj_string(o, "filter_type", "bilinear");
        const char *wrap = scene_obj_string(o, "wrap_mode", "repeat");
        if (texture_filter_parse(filter, &p.filter_type) != 0 || texture_wrap_parse(wrap, &p.wrap_mode) != 0)
            FAIL(o, "bad filter_type or wrap_mode");
        p.to_uv = to_uv_of(o);
        t = texture_create_bitmap(&p, why, sizeof why);
    } else if (!strcmp(o->type, "checkerboard")) {
        texture_checkerboard_params p = texture_checkerboard_defaults();
        if (scene_obj_texture(o, "color0") || scene_obj_texture(o, "color1"))
            FAIL(o, "checkerboard colors must be constant colors (nested textures are not supported)");
        p.color0 = to_rgb(scene_obj_rgb(o, "color0", (scene_rgb){p.color0.r, p.color0.g, p.color0.b}));
        p.color1 = to_rgb(scene_obj_rgb(o, "color1", (scene_rgb){p.color1.r, p.color1.g, p.color1.b}));
        p.to_uv = to_uv_of(o);
        t = texture_create_checkerboard(&p);
    } else {
        FAIL(o, "unsupported texture '%s'", o->type);
    }
    if (!t)
        FAIL(o, "%s", why[0] ? why : "cannot create the texture");
    if (built_add((void ***)&s->textures, &s->texture_keys, &s->ntextures, o, t) != 0) {
        texture_free(t);
        FAIL(o, "out of memory");
    }
    return t;
}

/* A "color or texture" property: 0, or -1 with err set. */
static int spectrum_of(struct scene *s, scene_obj *o, const char *name, double def, bsdf_spectrum *out, char *err,
                       size_t errlen)
{
    scene_obj *tex = scene_obj_texture(o, name);
    if (tex) {
        const texture_t *t = scene_build_texture(s, tex, err, errlen);
        if (!t)
            return -1;
        *out = bsdf_spectrum_tex(t);
        return 0;
    }
    *out = bsdf_spectrum_const(to_rgb(scene_obj_rgb(o, name, (scene_rgb){def, def, def})));
    return 0;
}

/* A float-or-IOR-name property. */
static int ior_of(scene_obj *o, const char *name, double def, double *out)
{
    scene_prop *p = scene_obj_prop(o, name);
    if (!p) {
        *out = def;
        return 0;
    }
    if (p->type == SCENE_STRING)
        return bsdf_ior_lookup(p->value.s, out);
    *out = p->value.f;
    return 0;
}

/* Constant color property that must not be a texture. */
static int color_only(scene_obj *o, const char *name, rgb *inout)
{
    if (scene_obj_texture(o, name))
        return -1;
    *inout = to_rgb(scene_obj_rgb(o, name, (scene_rgb){inout->r, inout->g, inout->b}));
    return 0;
}

/* Roughness: alpha sets both, alpha_u / alpha_v each; textures unsupported. */
static int roughness_of(scene_obj *o, microfacet_type *dist, double *au, double *av, int *visible)
{
    if (scene_obj_texture(o, "alpha") || scene_obj_texture(o, "alpha_u") || scene_obj_texture(o, "alpha_v"))
        return -1;
    if (microfacet_type_parse(scene_obj_string(o, "distribution", "beckmann"), dist) != 0)
        return -1;
    double a = scene_obj_float(o, "alpha", *au);
    *au = scene_obj_float(o, "alpha_u", a);
    *av = scene_obj_float(o, "alpha_v", a);
    *visible = scene_obj_bool(o, "sample_visible", *visible != 0);
    return 0;
}

static bsdf_t *build_conductor(struct scene *s, scene_obj *o, bool rough, char *why, size_t wl, char *err,
                               size_t errlen)
{
    rgb eta, k;
    bsdf_conductor_preset("none", &eta, &k);
    const char *material = scene_obj_string(o, "material", NULL);
    if (material && bsdf_conductor_preset(material, &eta, &k) != 0)
        FAIL(o, "unknown conductor material '%s'", material);
    if (color_only(o, "eta", &eta) != 0 || color_only(o, "k", &k) != 0)
        FAIL(o, "textured eta or k is not supported");
    bsdf_spectrum spec;
    if (spectrum_of(s, o, "specular_reflectance", 1.0, &spec, err, errlen) != 0)
        return NULL;
    if (!rough) {
        bsdf_conductor_params p = bsdf_conductor_defaults();
        p.eta = eta, p.k = k, p.specular_reflectance = spec;
        return bsdf_create_conductor(&p, why, wl);
    }
    bsdf_roughconductor_params p = bsdf_roughconductor_defaults();
    p.eta = eta, p.k = k, p.specular_reflectance = spec;
    if (roughness_of(o, &p.distribution, &p.alpha_u, &p.alpha_v, &p.sample_visible) != 0)
        FAIL(o, "textured roughness is not supported");
    return bsdf_create_roughconductor(&p, why, wl);
}

static bsdf_t *build_dielectric(struct scene *s, scene_obj *o, char *why, size_t wl, char *err, size_t errlen)
{
    bsdf_dielectric_params d = bsdf_dielectric_defaults();
    if (ior_of(o, "int_ior", d.int_ior, &d.int_ior) != 0 || ior_of(o, "ext_ior", d.ext_ior, &d.ext_ior) != 0)
        FAIL(o, "unknown index of refraction name");
    if (spectrum_of(s, o, "specular_reflectance", 1.0, &d.specular_reflectance, err, errlen) != 0 ||
        spectrum_of(s, o, "specular_transmittance", 1.0, &d.specular_transmittance, err, errlen) != 0)
        return NULL;
    if (!strcmp(o->type, "dielectric"))
        return bsdf_create_dielectric(&d, why, wl);
    if (!strcmp(o->type, "thindielectric"))
        return bsdf_create_thindielectric(&d, why, wl);
    bsdf_roughdielectric_params p = bsdf_roughdielectric_defaults();
    p.int_ior = d.int_ior, p.ext_ior = d.ext_ior;
    p.specular_reflectance = d.specular_reflectance, p.specular_transmittance = d.specular_transmittance;
    if (roughness_of(o, &p.distribution, &p.alpha_u, &p.alpha_v, &p.sample_visible) != 0)
        FAIL(o, "textured roughness is not supported");
    return bsdf_create_roughdielectric(&p, why, wl);
}

static bsdf_t *build_plastic(struct scene *s, scene_obj *o, char *why, size_t wl, char *err, size_t errlen)
{
    bsdf_plastic_params d = bsdf_plastic_defaults();
    if (ior_of(o, "int_ior", d.int_ior, &d.int_ior) != 0 || ior_of(o, "ext_ior", d.ext_ior, &d.ext_ior) != 0)
        FAIL(o, "unknown index of refraction name");
    if (spectrum_of(s, o, "diffuse_reflectance", 0.5, &d.diffuse_reflectance, err, errlen) != 0 ||
        spectrum_of(s, o, "specular_reflectance", 1.0, &d.specular_reflectance, err, errlen) != 0)
        return NULL;
    d.nonlinear = scene_obj_bool(o, "nonlinear", false);
    if (!strcmp(o->type, "plastic"))
        return bsdf_create_plastic(&d, why, wl);
    bsdf_roughplastic_params p = bsdf_roughplastic_defaults();
    p.diffuse_reflectance = d.diffuse_reflectance, p.specular_reflectance = d.specular_reflectance;
    p.int_ior = d.int_ior, p.ext_ior = d.ext_ior, p.nonlinear = d.nonlinear;
    if (microfacet_type_parse(scene_obj_string(o, "distribution", "beckmann"), &p.distribution) != 0)
        FAIL(o, "unknown distribution");
    p.alpha = scene_obj_float(o, "alpha", p.alpha);
    p.sample_visible = scene_obj_bool(o, "sample_visible", p.sample_visible != 0);
    return bsdf_create_roughplastic(&p, why, wl);
}

bsdf_t *scene_build_bsdf(struct scene *s, scene_obj *o, char *err, size_t errlen)
{
    bsdf_t *b = built_find((void *const *)s->bsdfs, s->bsdf_keys, s->nbsdfs, o);
    if (b)
        return b;
    char why[512] = "";
    err[0] = '\0';
    if (!strcmp(o->type, "diffuse")) {
        bsdf_diffuse_params p = bsdf_diffuse_defaults();
        if (spectrum_of(s, o, "reflectance", 0.5, &p.reflectance, err, errlen) != 0)
            return NULL;
        b = bsdf_create_diffuse(&p, why, sizeof why);
    } else if (!strcmp(o->type, "conductor") || !strcmp(o->type, "roughconductor")) {
        b = build_conductor(s, o, o->type[0] == 'r', why, sizeof why, err, errlen);
    } else if (strstr(o->type, "dielectric")) {
        b = build_dielectric(s, o, why, sizeof why, err, errlen);
    } else if (strstr(o->type, "plastic")) {
        b = build_plastic(s, o, why, sizeof why, err, errlen);
    } else if (!strcmp(o->type, "twosided")) {
        scene_obj *kids[2];
        int n = scene_obj_children(o, SCENE_BSDF, kids, 2);
        const bsdf_t *front = n >= 1 ? scene_build_bsdf(s, kids[0], err, errlen) : NULL;
        const bsdf_t *back = n >= 2 ? scene_build_bsdf(s, kids[1], err, errlen) : NULL;
        if (!front || (n >= 2 && !back))
            return NULL;
        b = bsdf_create_twosided(front, back, why, sizeof why);
    } else {
        FAIL(o, "unsupported BSDF '%s'", o->type);
    }
    if (!b) {
        if (err[0])
            return NULL;
        FAIL(o, "<bsdf type='%s'>: %s", o->type, why[0] ? why : "cannot create the BSDF");
    }
    if (built_add((void ***)&s->bsdfs, &s->bsdf_keys, &s->nbsdfs, o, b) != 0) {
        bsdf_free(b);
        FAIL(o, "out of memory");
    }
    return b;
}
