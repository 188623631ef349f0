/* The description tree (scene_xml.h) turned into a renderable scene:
 * sensor, film size, sampler and integrator settings, shapes with their BSDFs
 * and area emitters, and the other emitters. Every defect is reported as
 * "file:line: problem" of the object it concerns. */
#include <stdlib.h>
#include <string.h>

#include "render/scene_impl.h"

#define FAIL(o, ...)                                                         \
    do {                                                                     \
        char msg_[1024];                                                      \
        snprintf(msg_, sizeof msg_, __VA_ARGS__);                            \
        snprintf(err, errlen, "%s:%d: %s", (o)->file, (o)->line, msg_);      \
        return -1;                                                           \
    } while (0)

scene_build_options scene_build_defaults(void)
{
    return (scene_build_options){0, 0, 0, -1, 0};
}

static rgb to_rgb(scene_rgb c) { return rgb_make(c.r, c.g, c.b); }

static int build_sensor(struct scene *s, scene_obj *root, const scene_build_options *opt, char *err, size_t errlen)
{
    scene_obj *sensor = scene_obj_child(root, SCENE_SENSOR);
    if (!sensor)
        FAIL(root, "the scene has no <sensor>");
    scene_obj *film = scene_obj_child(sensor, SCENE_FILM);
    int w = 768, h = 576;
    if (film) {
        w = (int)scene_obj_int(film, "width", w);
        h = (int)scene_obj_int(film, "height", h);
        /* Accepted for compatibility, no effect (docs/scene-format.md). */
        static const char *const inert[] = {"pixel_format", "component_format", "file_format", "sample_border"};
        for (size_t i = 0; i < sizeof inert / sizeof inert[0]; i++)
            scene_obj_prop(film, inert[i]);
        scene_obj *rf = scene_obj_child(film, SCENE_RFILTER);
        if (rf)
            scene_obj_prop(rf, "stddev");
    }
    if (opt->width > 0)
        w = opt->width;
    if (opt->height > 0)
        h = opt->height;
    if (w < 1 || h < 1 || w > 65536 || h > 65536)
        FAIL(film ? film : sensor, "film size %dx%d is out of range", w, h);
    scene_obj_prop(sensor, "focus_distance");
    char why[512];
    if (camera_from_sensor(&s->camera, sensor, w, h, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s", why);
        return -1;
    }
    scene_obj *sampler = scene_obj_child(sensor, SCENE_SAMPLER);
    long long spp = sampler ? scene_obj_int(sampler, "sample_count", 4) : 4;
    long long seed = sampler ? scene_obj_int(sampler, "seed", 0) : 0;
    if (opt->spp > 0)
        spp = opt->spp;
    if (opt->seed >= 0)
        seed = opt->seed;
    if (spp < 1 || spp > (1ll << 24))
        FAIL(sampler ? sampler : sensor, "sample_count %lld is out of range", spp);
    s->spp = (int)spp;
    s->seed = (uint64_t)seed;
    return 0;
}

static int build_integrator(struct scene *s, scene_obj *root, char *err, size_t errlen)
{
    scene_obj *in = scene_obj_child(root, SCENE_INTEGRATOR);
    s->max_depth = -1, s->rr_depth = 5, s->hide_emitters = false;
    if (!in)
        return 0;
    long long md = scene_obj_int(in, "max_depth", -1), rr = scene_obj_int(in, "rr_depth", 5);
    if (md < -1 || md > 1000000 || rr < 1 || rr > 1000000)
        FAIL(in, "max_depth must be -1 or >= 0 and rr_depth >= 1");
    s->max_depth = (int)md;
    s->rr_depth = (int)rr;
    s->hide_emitters = scene_obj_bool(in, "hide_emitters", false);
    return 0;
}

/* Object-to-world of Mitsuba's parametrised analytic shapes. */
static int analytic_placement(scene_obj *o, const transform4 *to_world, transform4 *out, char *err, size_t errlen)
{
    transform4 local = transform_identity();
    if (!strcmp(o->type, "sphere")) {
        double r = scene_obj_float(o, "radius", 1.0);
        if (!(r > 0.0))
            FAIL(o, "sphere radius must be > 0");
        transform4 t = transform_translate(scene_obj_point(o, "center", v3(0, 0, 0)));
        transform4 sc = transform_scale(v3(r, r, r));
        local = transform_compose(&t, &sc);
    } else if (!strcmp(o->type, "cylinder")) {
        vec3 p0 = scene_obj_point(o, "p0", v3(0, 0, 0)), p1 = scene_obj_point(o, "p1", v3(0, 0, 1));
        double r = scene_obj_float(o, "radius", 1.0), len = v3_len(v3_sub(p1, p0));
        if (!(r > 0.0) || !(len > 0.0))
            FAIL(o, "cylinder needs radius > 0 and p0 != p1");
        frame3 f = frame3_from_normal(v3_scale(v3_sub(p1, p0), 1.0 / len));
        const double rows[16] = {r * f.s.x, r * f.t.x, len * f.n.x, p0.x, r * f.s.y, r * f.t.y, len * f.n.y, p0.y,
                                 r * f.s.z, r * f.t.z, len * f.n.z, p0.z, 0, 0, 0, 1};
        if (transform_from_rows(rows, &local) != 0)
            FAIL(o, "degenerate cylinder");
    }
    *out = transform_compose(to_world, &local);
    return 0;
}

static double det3(const transform4 *t)
{
    const double(*m)[4] = t->m;
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* The geometry of one shape; sh->mesh or sh->ops/data filled. */
static int build_geometry(scene_obj *o, shape_t *sh, const scene_build_options *opt, char *err, size_t errlen)
{
    transform4 to_world = scene_obj_transform(o, "to_world");
    char why[600] = "";
    int rc = 0;
    sh->is_mesh = true;
    if (!strcmp(o->type, "obj") || !strcmp(o->type, "ply")) {
        const char *file = scene_obj_string(o, "filename", NULL);
        bool face_normals = scene_obj_bool(o, "face_normals", false);
        rc = o->type[0] == 'o' ? shape_obj_read(file, scene_obj_bool(o, "flip_tex_coords", true), &sh->mesh, why,
                                                sizeof why)
                               : shape_ply_read(file, &sh->mesh, why, sizeof why);
        if (rc == 0 && face_normals) {
            free(sh->mesh.nrm);
            sh->mesh.nrm = NULL;
        } else if (rc == 0 && !sh->mesh.nrm && shape_mesh_smooth_normals(&sh->mesh) != 0) {
            rc = -1, snprintf(why, sizeof why, "out of memory");
        }
    } else if (!strcmp(o->type, "rectangle") || !strcmp(o->type, "cube")) {
        rc = o->type[0] == 'r' ? shape_rectangle_mesh(&sh->mesh) : shape_cube_mesh(&sh->mesh);
        if (rc != 0)
            snprintf(why, sizeof why, "out of memory");
    } else if (!strcmp(o->type, "sor")) {
        const char *file = scene_obj_string(o, "filename", NULL);
        double height = scene_obj_float(o, "height", 1.0);
        bool caps = scene_obj_bool(o, "caps", true);
        if (!(height > 0.0))
            FAIL(o, "sor height must be > 0");
        if (opt->mesh_segments > 0) {
            rc = shape_sor_mesh(file, height, caps, opt->mesh_segments, &sh->mesh, why, sizeof why);
        } else {
            sh->is_mesh = false;
            sh->ops = &shape_sor_ops;
            sh->data = shape_sor_create(file, height, caps, why, sizeof why);
            rc = sh->data ? 0 : -1;
        }
    } else {
        sh->is_mesh = false;
        sh->ops = !strcmp(o->type, "sphere") ? &shape_sphere_ops
                  : !strcmp(o->type, "disk") ? &shape_disk_ops
                  : !strcmp(o->type, "cylinder") ? &shape_cylinder_ops
                                                 : NULL;
        if (!sh->ops)
            FAIL(o, "unsupported shape '%s'", o->type);
        if (analytic_placement(o, &to_world, &to_world, err, errlen) != 0)
            return -1;
    }
    if (rc != 0)
        FAIL(o, "<shape type=\"%s\">: %s", o->type, why);
    if (sh->is_mesh) {
        shape_mesh_transform(&sh->mesh, &to_world);
    } else {
        sh->to_world = to_world;
        sh->det = fabs(det3(&to_world));
    }
    return 0;
}

static int add_emitter(struct scene *s, emitter_t e)
{
    emitter_t *a = realloc(s->emitters, sizeof *a * (size_t)(s->nemitters + 1));
    if (!a)
        return -1;
    s->emitters = a;
    a[s->nemitters++] = e;
    return 0;
}

static int build_shape(struct scene *s, scene_obj *o, const scene_build_options *opt, char *err, size_t errlen)
{
    shape_t *sh = &s->shapes[s->nshapes];
    memset(sh, 0, sizeof *sh);
    sh->emitter = -1;
    sh->file = o->file;
    sh->line = o->line;
    sh->flip_normals = scene_obj_bool(o, "flip_normals", false);
    if (build_geometry(o, sh, opt, err, errlen) != 0) {
        shape_free(sh);
        return -1;
    }
    s->nshapes++;
    scene_obj *bo = scene_obj_child(o, SCENE_BSDF);
    sh->bsdf = bo ? bsdf_set_get(&s->bsdfs, bo, err, errlen) : bsdf_set_default(&s->bsdfs, o, err, errlen);
    if (!sh->bsdf)
        return -1;
    scene_obj *eo = scene_obj_child(o, SCENE_EMITTER);
    if (eo) {
        if (strcmp(eo->type, "area") != 0)
            FAIL(eo, "only an area emitter can be attached to a shape");
        emitter_t e = {.kind = EMITTER_AREA, .shape = s->nshapes - 1};
        scene_obj *tex = scene_obj_texture(eo, "radiance");
        if (tex && !(e.texture = texture_set_get(&s->textures, tex, err, errlen)))
            return -1;
        e.value = to_rgb(scene_obj_rgb(eo, "radiance", (scene_rgb){1, 1, 1}));
        if (shape_prepare_sampling(sh) != 0)
            FAIL(o, "an emitting shape must have a nonzero area");
        sh->emitter = s->nemitters;
        if (add_emitter(s, e) != 0)
            FAIL(eo, "out of memory");
    }
    return 0;
}

static int build_emitter(struct scene *s, scene_obj *o, char *err, size_t errlen)
{
    emitter_t e = {.shape = -1};
    if (!strcmp(o->type, "constant") || !strcmp(o->type, "envmap")) {
        if (s->env >= 0)
            FAIL(o, "only one environment emitter (constant or envmap) is supported");
        if (o->type[0] == 'c') {
            e.kind = EMITTER_CONSTANT;
            if (scene_obj_texture(o, "radiance"))
                FAIL(o, "a textured constant emitter is not supported (use envmap)");
            e.value = to_rgb(scene_obj_rgb(o, "radiance", (scene_rgb){1, 1, 1}));
        } else {
            e.kind = EMITTER_ENVMAP;
            e.env = calloc(1, sizeof *e.env);
            if (!e.env)
                FAIL(o, "out of memory");
            e.env->scale = scene_obj_float(o, "scale", 1.0);
            e.env->to_world = scene_obj_transform(o, "to_world");
            e.env->to_local = transform_inverse(&e.env->to_world);
            char why[600];
            if (emitter_envmap_load(e.env, scene_obj_string(o, "filename", NULL), why, sizeof why) != 0) {
                emitter_free(&e);
                FAIL(o, "%s", why);
            }
        }
        s->env = s->nemitters;
    } else if (!strcmp(o->type, "point")) {
        e.kind = EMITTER_POINT;
        e.value = to_rgb(scene_obj_rgb(o, "intensity", (scene_rgb){1, 1, 1}));
        transform4 t = scene_obj_transform(o, "to_world");
        e.position = scene_obj_point(o, "position", transform_point(&t, v3(0, 0, 0)));
    } else if (!strcmp(o->type, "directional")) {
        e.kind = EMITTER_DIRECTIONAL;
        e.value = to_rgb(scene_obj_rgb(o, "irradiance", (scene_rgb){1, 1, 1}));
        transform4 t = scene_obj_transform(o, "to_world");
        e.direction = v3_norm(scene_obj_vector(o, "direction", transform_vector(&t, v3(0, 0, 1))));
        if (!(v3_len(e.direction) > 0.0))
            FAIL(o, "directional emitter needs a nonzero direction");
    } else {
        FAIL(o, "emitter '%s' must be attached to a shape or is not supported here", o->type);
    }
    if (add_emitter(s, e) != 0) {
        emitter_free(&e);
        FAIL(o, "out of memory");
    }
    return 0;
}

static int build_all(struct scene *s, scene_desc *desc, const scene_build_options *opt, char *err, size_t errlen)
{
    scene_obj *root = scene_desc_root(desc);
    if (build_integrator(s, root, err, errlen) != 0 || build_sensor(s, root, opt, err, errlen) != 0)
        return -1;
    /* Top-level BSDFs and textures are built even when unreferenced, so
     * their parameters are checked as Mitsuba would. */
    int n = scene_obj_children(root, SCENE_TEXTURE, NULL, 0);
    scene_obj **objs = malloc(sizeof *objs * (size_t)(n + 1));
    if (!objs)
        FAIL(root, "out of memory");
    scene_obj_children(root, SCENE_TEXTURE, objs, n);
    for (int i = 0; i < n; i++)
        if (!texture_set_get(&s->textures, objs[i], err, errlen)) {
            free(objs);
            return -1;
        }
    free(objs);
    n = scene_obj_children(root, SCENE_BSDF, NULL, 0);
    objs = malloc(sizeof *objs * (size_t)(n + 1));
    if (!objs)
        FAIL(root, "out of memory");
    scene_obj_children(root, SCENE_BSDF, objs, n);
    for (int i = 0; i < n; i++)
        if (!bsdf_set_get(&s->bsdfs, objs[i], err, errlen)) {
            free(objs);
            return -1;
        }
    free(objs);

    n = scene_obj_children(root, SCENE_SHAPE, NULL, 0);
    s->shapes = calloc((size_t)n + 1, sizeof *s->shapes);
    objs = malloc(sizeof *objs * (size_t)(n + 1));
    if (!s->shapes || !objs) {
        free(objs);
        FAIL(root, "out of memory");
    }
    scene_obj_children(root, SCENE_SHAPE, objs, n);
    for (int i = 0; i < n; i++)
        if (build_shape(s, objs[i], opt, err, errlen) != 0) {
            free(objs);
            return -1;
        }
    free(objs);

    n = scene_obj_children(root, SCENE_EMITTER, NULL, 0);
    objs = malloc(sizeof *objs * (size_t)(n + 1));
    if (!objs)
        FAIL(root, "out of memory");
    scene_obj_children(root, SCENE_EMITTER, objs, n);
    for (int i = 0; i < n; i++)
        if (build_emitter(s, objs[i], err, errlen) != 0) {
            free(objs);
            return -1;
        }
    free(objs);

    char msg[600];
    if (scene_obj_unconsumed(root, msg, sizeof msg)) {
        snprintf(err, errlen, "%s", msg);
        return -1;
    }
    return scene_trace_build(s, err, errlen);
}

scene_t *scene_build(scene_desc *desc, const scene_build_options *opt, char *err, size_t errlen)
{
    scene_build_options defaults = scene_build_defaults();
    if (!opt)
        opt = &defaults;
    struct scene *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    s->env = -1;
    s->bsdfs.textures = &s->textures;
    if (opt->mesh_segments != 0 && opt->mesh_segments < 3) {
        snprintf(err, errlen, "mesh segments must be >= 3");
        free(s);
        return NULL;
    }
    if (build_all(s, desc, opt, err, errlen) != 0) {
        scene_free(s);
        return NULL;
    }
    return s;
}

scene_t *scene_load(const char *path, const scene_define *defs, int ndefs, const scene_build_options *opt,
                    char *err, size_t errlen)
{
    scene_desc *d = scene_desc_create_from_file(path, defs, ndefs, scene_plugin_find, err, errlen);
    if (!d)
        return NULL;
    scene_t *s = scene_build(d, opt, err, errlen);
    scene_desc_destroy(d);
    return s;
}

void scene_free(scene_t *s)
{
    if (!s)
        return;
    scene_trace_free(s);
    for (int i = 0; i < s->nshapes; i++)
        shape_free(&s->shapes[i]);
    free(s->shapes);
    for (int i = 0; i < s->nemitters; i++)
        emitter_free(&s->emitters[i]);
    free(s->emitters);
    /* BSDFs borrow textures: free them first. */
    bsdf_set_free(&s->bsdfs);
    texture_set_free(&s->textures);
    free(s);
}

const camera_t *scene_camera(const scene_t *s) { return &s->camera; }
int scene_spp(const scene_t *s) { return s->spp; }
uint64_t scene_seed(const scene_t *s) { return s->seed; }
int scene_shape_count(const scene_t *s) { return s->nshapes; }
int scene_emitter_count(const scene_t *s) { return s->nemitters; }

long long scene_triangle_count(const scene_t *s)
{
    long long n = 0;
    for (int i = 0; i < s->nshapes; i++)
        n += s->shapes[i].is_mesh ? s->shapes[i].mesh.n_tris : 0;
    return n;
}
