/* Mitsuba's `envmap`: a latitude-longitude image at infinity (`filename`,
 * linear when EXR/HDR/PFM, sRGB-decoded otherwise), times `scale`, turned by
 * `to_world`, with Mitsuba's orientation: local direction
 * (sin t sin p, cos t, -sin t cos p) for image coordinates
 * (u, v) = (p / 2pi, t / pi), so the top row looks along +y.
 * Lookups interpolate bilinearly on Mitsuba's grid: column i sits at
 * u = (i + 0.5) / width and wraps around (the last column blends into the
 * first), row j at v = j / (height - 1), so the top row is the +y pole itself
 * and the bottom row the -y pole. Importance sampling draws texels from a 2D piecewise-constant distribution of
 * max(0, luminance - its mean over the sphere) x sin(theta), which makes
 * sample and density agree exactly. Subtracting the mean is MIS
 * compensation (Karlik et al. 2019, as pbrt-v4 does): BSDF sampling, weighed
 * in by MIS, already covers the map's uniform part well, so emitter samples
 * go where the map is brighter than that; the density is zero elsewhere,
 * where MIS then gives BSDF samples their full weight. A uniform map is
 * never picked for next-event estimation at all (phi 0, like `constant`). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "celadon/image.h"
#include "emitters/emitter_impl.h"

typedef struct {
    int width, height;
    rgb *pixels;            /* linear, row 0 = the top (+y, theta = 0) */
    double excess;          /* the mean over the sphere of max(0, luminance - its mean) */
    distribution2d dist;    /* over (u, v) cells, luminance x sin(theta) */
    transform4 to_world, to_local;
    double scale;
} envmap_data;

/* The map's radiance at (u, v) before `scale`: bilinear on Mitsuba's grid. */
static rgb envmap_interp(const envmap_data *env, vec2 uv)
{
    int w = env->width, h = env->height;
    double x = uv.x - 0.5 / w;
    x = (x - floor(x)) * w;
    double y = fmin(fmax(uv.y, 0.0), 1.0) * (h > 1 ? h - 1 : 0);
    int ix = (int)x, iy = (int)y;
    ix = ix < w - 1 ? ix : w - 1;
    iy = iy < h - 2 ? iy : (h > 1 ? h - 2 : 0);
    double fx = x - ix, fy = h > 1 ? y - iy : 0.0;
    int ix1 = (ix + 1) % w, iy1 = h > 1 ? iy + 1 : iy;
    const rgb *row0 = env->pixels + (size_t)iy * w, *row1 = env->pixels + (size_t)iy1 * w;
    rgb top = rgb_add(rgb_scale(row0[ix], 1.0 - fx), rgb_scale(row0[ix1], fx));
    rgb bottom = rgb_add(rgb_scale(row1[ix], 1.0 - fx), rgb_scale(row1[ix1], fx));
    return rgb_add(rgb_scale(top, 1.0 - fy), rgb_scale(bottom, fy));
}

static rgb envmap_lookup(const envmap_data *env, vec2 uv) { return rgb_scale(envmap_interp(env, uv), env->scale); }

static int envmap_load(envmap_data *env, const char *path, char *err, size_t errlen)
{
    image_t img;
    char why[512];
    if (image_read_quiet(path, &img, why, sizeof why) != 0) {
        snprintf(err, errlen, "cannot read '%s': %s", path, why);
        return -1;
    }
    const char *dot = strrchr(path, '.');
    int linear = dot && (!strcasecmp(dot, ".exr") || !strcasecmp(dot, ".hdr") || !strcasecmp(dot, ".pfm"));
    int w = img.width, h = img.height, nc = img.channels - (img.has_alpha ? 1 : 0);
    env->width = w, env->height = h;
    env->pixels = malloc(sizeof *env->pixels * (size_t)w * (size_t)h);
    double *f = malloc(sizeof *f * (size_t)w * (size_t)h);
    if (!env->pixels || !f || nc < 1) {
        free(f);
        image_free(&img);
        snprintf(err, errlen, "cannot load '%s' as an environment map", path);
        return -1;
    }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const float *px = &img.data[((size_t)y * w + x) * img.channels];
            rgb c = nc >= 3 ? rgb_make(px[0], px[1], px[2]) : rgb_gray(px[0]);
            if (!linear)
                c = rgb_srgb_to_linear(c);
            env->pixels[(size_t)y * w + x] = rgb_make(fmax(c.r, 0.0), fmax(c.g, 0.0), fmax(c.b, 0.0));
        }
    image_free(&img);
    /* The sampled cells are the w x h cells of (u, v); each weighs the
     * interpolated radiance at its centre. */
    double mean = 0.0, weight = 0.0;
    for (int y = 0; y < h; y++) {
        double sin_t = sin(M_PI * (y + 0.5) / h);
        for (int x = 0; x < w; x++) {
            double l = rgb_luminance(envmap_interp(env, v2((x + 0.5) / w, (y + 0.5) / h)));
            f[(size_t)y * w + x] = l;
            mean += l * sin_t, weight += sin_t;
        }
    }
    mean = weight > 0.0 ? mean / weight : 0.0;
    env->excess = 0.0;
    for (int y = 0; y < h; y++) {
        double sin_t = sin(M_PI * (y + 0.5) / h);
        for (int x = 0; x < w; x++) {
            double e = fmax(0.0, f[(size_t)y * w + x] - mean);
            f[(size_t)y * w + x] = e * sin_t;
            env->excess += e * sin_t / weight;
        }
    }
    int rc = distribution2d_init(&env->dist, f, w, h);
    free(f);
    if (rc != 0) {
        snprintf(err, errlen, "out of memory for '%s'", path);
        return -1;
    }
    return 0;
}

/* Image coordinates of a world direction; *sin_t receives sin(theta). */
static vec2 dir_to_uv(const envmap_data *env, vec3 dir, double *sin_t)
{
    vec3 v = v3_norm(transform_vector(&env->to_local, dir));
    double phi = atan2(v.x, -v.z);
    phi = phi < 0.0 ? phi + 2.0 * M_PI : phi;
    double theta = acos(fmax(-1.0, fmin(1.0, v.y)));
    *sin_t = sin(theta);
    return v2(fmin(phi / (2.0 * M_PI), 1.0 - 1e-12), fmin(theta / M_PI, 1.0 - 1e-12));
}

static rgb envmap_eval_env(const emitter_t *e, vec3 dir)
{
    const envmap_data *env = e->data;
    double sin_t;
    return envmap_lookup(env, dir_to_uv(env, dir, &sin_t));
}

static double envmap_pdf_env(const emitter_t *e, vec3 dir)
{
    const envmap_data *env = e->data;
    double sin_t;
    vec2 uv = dir_to_uv(env, dir, &sin_t);
    return sin_t > 0.0 ? distribution2d_pdf(&env->dist, uv) / (2.0 * M_PI * M_PI * sin_t) : 0.0;
}

static int envmap_sample(const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out)
{
    (void)ref;
    const envmap_data *env = e->data;
    double pdf_uv;
    vec2 uv = distribution2d_sample(&env->dist, v2(u.x, u.y), &pdf_uv);
    double theta = M_PI * uv.y, phi = 2.0 * M_PI * uv.x, st = sin(theta);
    if (!(pdf_uv > 0.0) || st <= 0.0)
        return 0;
    vec3 local = v3(st * sin(phi), cos(theta), -st * cos(phi));
    out->wi = v3_norm(transform_vector(&env->to_world, local));
    out->pdf = pdf_uv / (2.0 * M_PI * M_PI * st);
    out->value = envmap_lookup(env, uv);
    return 1;
}

static void envmap_release(void *data)
{
    envmap_data *env = data;
    free(env->pixels);
    if (env->dist.conditional)
        distribution2d_free(&env->dist);
}

/* What a surface facing the map receives beyond its uniform part: pi times
 * the mean excess (0 for a uniform map). */
static void envmap_bounds(const emitter_t *e, light_bounds *out)
{
    const envmap_data *env = e->data;
    emitter_bounds_infinite(M_PI * env->scale * env->excess, out);
}

static const emitter_ops envmap_ops = {envmap_sample, NULL,           NULL,         envmap_eval_env,
                                       envmap_pdf_env, envmap_release, envmap_bounds, false};

static emitter_t *envmap_create(scene_obj *o, shape_t *shape, texture_set *textures, char *err, size_t errlen)
{
    (void)shape, (void)textures;
    envmap_data env = {0};
    env.scale = scene_obj_float(o, "scale", 1.0);
    env.to_world = scene_obj_transform(o, "to_world");
    env.to_local = transform_inverse(&env.to_world);
    char why[600];
    if (envmap_load(&env, scene_obj_string(o, "filename", NULL), why, sizeof why) != 0) {
        envmap_release(&env);
        scene_obj_error(o, err, errlen, "%s", why);
        return NULL;
    }
    emitter_t *e = emitter_alloc(o, &envmap_ops, &env, sizeof env, err, errlen);
    if (!e)
        envmap_release(&env);
    return e;
}

static const scene_param_decl envmap_params[] = {
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"scale", PARAM_FLOAT, 0, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    {NULL, 0, 0, NULL},
};

const emitter_plugin emitter_envmap = {
    .decl = {.cls = SCENE_EMITTER, .type = "envmap", .params = envmap_params},
    .flags = EMITTER_ENVIRONMENT,
    .create = envmap_create,
};
