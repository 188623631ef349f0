/* The description tree (scene_xml.h) turned into a renderable scene through
 * the kinds' registration tables: integrator, sensor with its film and
 * sampler, textures and BSDFs, shapes with their area emitters, and the
 * other emitters. Every defect is reported as "file:line: problem" of the
 * object it concerns. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/film.h"
#include "render/scene_impl.h"

scene_options scene_options_default(void)
{
    return (scene_options){0, 0, 0, -1, 0, NULL, NULL, 0, 0, 0, 0, 0};
}

/* An object of class cls and plugin type with no parameters, located at at:
 * what the scene gets where it names none (Mitsuba's defaults). */
static scene_obj implicit_object(scene_class cls, const char *type, const scene_obj *at)
{
    return (scene_obj){.cls = cls, .type = (char *)type, .file = at->file, .line = at->line};
}

static int build_integrator(struct scene *s, scene_obj *root, char *err, size_t errlen)
{
    scene_obj implicit = implicit_object(SCENE_INTEGRATOR, "path", root);
    scene_obj *o = scene_obj_child(root, SCENE_INTEGRATOR);
    if (!o)
        o = &implicit;
    s->integrator = integrator_plugin_find(o->type)->create(o, err, errlen);
    return s->integrator ? 0 : -1;
}

/* The film's size, overridden by the options, within limits. */
static int build_film(scene_obj *sensor, const scene_options *opt, film_settings *fs, char *err, size_t errlen)
{
    scene_obj implicit = implicit_object(SCENE_FILM, "hdrfilm", sensor);
    scene_obj *film = scene_obj_child(sensor, SCENE_FILM);
    if (!film)
        film = &implicit;
    if (film_plugin_find(film->type)->create(film, fs, err, errlen) != 0)
        return -1;
    if (opt->width > 0)
        fs->width = opt->width;
    if (opt->height > 0)
        fs->height = opt->height;
    if (fs->width < 1 || fs->height < 1 || fs->width > FILM_MAX_SIDE || fs->height > FILM_MAX_SIDE ||
        (double)fs->width * fs->height > FILM_MAX_PIXELS)
        return scene_obj_error(film, err, errlen, "film size %dx%d is out of range (at most %d on a side, %.0e pixels)",
                               fs->width, fs->height, FILM_MAX_SIDE, FILM_MAX_PIXELS);
    if (opt->crop_w > 0)
        fs->crop_x = opt->crop_x, fs->crop_y = opt->crop_y, fs->crop_w = opt->crop_w, fs->crop_h = opt->crop_h;
    if (fs->crop_w == 0)
        fs->crop_w = fs->width - fs->crop_x;
    if (fs->crop_h == 0)
        fs->crop_h = fs->height - fs->crop_y;
    if (fs->crop_x < 0 || fs->crop_y < 0 || fs->crop_w < 1 || fs->crop_h < 1 ||
        (long long)fs->crop_x + fs->crop_w > fs->width || (long long)fs->crop_y + fs->crop_h > fs->height)
        return scene_obj_error(film, err, errlen, "crop window %d,%d %dx%d is not inside the %dx%d film", fs->crop_x,
                               fs->crop_y, fs->crop_w, fs->crop_h, fs->width, fs->height);
    return 0;
}

/* The sampler (the options may name another plugin, which then keeps the
 * scene's sample count and seed), its sample count and seed overridden by
 * the options and rounded by the plugin for a film of fs. */
static int build_sampler(struct scene *s, scene_obj *sensor, const scene_options *opt, const film_settings *fs,
                         char *err, size_t errlen)
{
    scene_obj implicit = implicit_object(SCENE_SAMPLER, "independent", sensor);
    scene_obj *o = scene_obj_child(sensor, SCENE_SAMPLER);
    if (!o)
        o = &implicit;
    if (sampler_plugin_find(o->type)->create(o, &s->sampler, err, errlen) != 0)
        return -1;
    const char *type = sampler_plugin_find(o->type)->decl.type; /* static: o is freed after the build */
    if (opt->sampler && strcmp(opt->sampler, o->type) != 0) {
        const sampler_plugin *named = sampler_plugin_find(opt->sampler);
        if (!named)
            return scene_obj_error(o, err, errlen, "unknown sampler '%s'", opt->sampler);
        scene_obj other = implicit_object(SCENE_SAMPLER, named->decl.type, o);
        sampler_t scene_own = s->sampler;
        if (named->create(&other, &s->sampler, err, errlen) != 0)
            return -1;
        s->sampler.sample_count = scene_own.sample_count;
        s->sampler.seed = scene_own.seed;
        type = named->decl.type;
    }
    s->sampler.plugin = type;
    if (opt->spp > 0)
        s->sampler.sample_count = opt->spp;
    if (opt->seed >= 0)
        s->sampler.seed = (uint64_t)opt->seed;
    const long long max_count = 1ll << 24;
    if (s->sampler.sample_count < 1 || s->sampler.sample_count > max_count)
        return scene_obj_error(o, err, errlen, "sample_count %lld is out of range", s->sampler.sample_count);
    sampler_prepare(&s->sampler, fs->width, fs->height);
    if (s->sampler.sample_count > max_count)
        return scene_obj_error(o, err, errlen, "sample_count rounds up to %lld for the %s sampler: out of range",
                               s->sampler.sample_count, type);
    return 0;
}

static int build_sensor(struct scene *s, scene_obj *root, const scene_options *opt, char *err, size_t errlen)
{
    scene_obj *sensor = scene_obj_child(root, SCENE_SENSOR);
    if (!sensor)
        return scene_obj_error(root, err, errlen, "the scene has no <sensor>");
    film_settings *fs = &s->film;
    if (build_film(sensor, opt, fs, err, errlen) != 0 ||
        sensor_plugin_find(sensor->type)->create(sensor, fs->width, fs->height, &s->camera, err, errlen) != 0)
        return -1;
    scene_obj *medium = scene_obj_child(sensor, SCENE_MEDIUM);
    if (medium && medium_set_get(&s->media, medium, &s->camera_medium, err, errlen) != 0)
        return -1;
    return build_sampler(s, sensor, opt, fs, err, errlen);
}

/* Textures and BSDFs at the top level are built even when unreferenced, so
 * their parameters are checked as Mitsuba would. */
static int build_shared(struct scene *s, scene_obj *root, char *err, size_t errlen)
{
    for (int i = 0; i < root->nchildren; i++) {
        scene_obj *o = root->children[i];
        if (o->cls == SCENE_TEXTURE && !texture_set_get(&s->textures, o, err, errlen))
            return -1;
    }
    for (int i = 0; i < root->nchildren; i++) {
        scene_obj *o = root->children[i];
        if (o->cls == SCENE_BSDF && !bsdf_set_get(&s->bsdfs, o, err, errlen))
            return -1;
    }
    return 0;
}

static int add_emitter(struct scene *s, scene_obj *o, emitter_t *e, char *err, size_t errlen)
{
    if (emitter_list_add(&s->emitters, e) != 0) {
        emitter_destroy(e);
        return scene_obj_error(o, err, errlen, "out of memory");
    }
    return 0;
}

/* Whether shape sh carries the mesh attribute name. */
static bool has_attribute(const shape_t *sh, const char *name)
{
    for (int i = 0; sh->is_mesh && i < sh->mesh.attrs.count; i++)
        if (strcmp(sh->mesh.attrs.items[i].name, name) == 0)
            return true;
    return false;
}

/* The first `mesh_attribute` texture in o or the objects it holds (its
 * textures, nested and referenced BSDFs) whose attribute shape sh lacks, or
 * NULL; *name is then that attribute. Each object is looked at once
 * (seen), however often it is referenced. Mitsuba refuses such a scene. */
static const scene_obj *missing_attribute(const scene_obj *o, const shape_t *sh, const char **name,
                                          scene_obj_map *seen)
{
    if (scene_obj_map_find(seen, o) || scene_obj_map_add(seen, o, (void *)o) != 0)
        return NULL; /* looked at already (or out of memory: not looked at) */
    if (o->cls == SCENE_TEXTURE && strcmp(o->type, "mesh_attribute") == 0)
        for (int i = 0; i < o->nprops; i++)
            if (o->props[i].type == SCENE_STRING && strcmp(o->props[i].name, "name") == 0 &&
                !has_attribute(sh, o->props[i].value.s)) {
                *name = o->props[i].value.s;
                return o;
            }
    const scene_obj *found = NULL;
    for (int i = 0; !found && i < o->nprops; i++)
        if (o->props[i].type == SCENE_OBJECT)
            found = missing_attribute(o->props[i].value.obj, sh, name, seen);
    for (int i = 0; !found && i < o->nchildren; i++)
        found = missing_attribute(o->children[i], sh, name, seen);
    return found;
}

/* Refuses a shape whose BSDF or emitter reads a mesh attribute it lacks. */
static int check_attributes(const scene_obj *o, const shape_t *sh, char *err, size_t errlen)
{
    const scene_obj *parts[2] = {scene_obj_child(o, SCENE_BSDF), scene_obj_child(o, SCENE_EMITTER)};
    for (int k = 0; k < 2; k++) {
        const char *name = NULL;
        scene_obj_map seen = {0};
        const scene_obj *t = parts[k] ? missing_attribute(parts[k], sh, &name, &seen) : NULL;
        scene_obj_map_free(&seen);
        if (!t)
            continue;
        char at[512]; /* the shape's line, and its file when the texture is in another */
        if (strcmp(t->file, o->file) == 0)
            snprintf(at, sizeof at, "line %d", o->line);
        else
            snprintf(at, sizeof at, "%s:%d", o->file, o->line);
        return scene_obj_error(t, err, errlen,
                               "<texture type=\"mesh_attribute\">: the <shape type=\"%s\"> at %s has no mesh "
                               "attribute '%s' (Mitsuba refuses it too)",
                               o->type, at, name);
    }
    return 0;
}

/* The shape of a leaf, its BSDF (Mitsuba's default when it names none) and
 * its area emitter. */
static int build_shape(struct scene *s, const shape_leaf *leaf, const scene_options *opt, char *err, size_t errlen)
{
    scene_obj *o = leaf->obj;
    shape_t *sh = &s->shapes.items[s->shapes.count];
    shape_options so = {opt->mesh_segments};
    if (shape_create(o, leaf->placed ? &leaf->outer : NULL, &so, sh, err, errlen) != 0)
        return -1;
    s->shapes.count++;
    if (check_attributes(o, sh, err, errlen) != 0)
        return -1;
    scene_obj *bo = scene_obj_child(o, SCENE_BSDF);
    sh->bsdf = bo ? bsdf_set_get(&s->bsdfs, bo, err, errlen) : bsdf_set_default(&s->bsdfs, o, err, errlen);
    if (!sh->bsdf || medium_set_param(&s->media, o, "interior", &sh->interior, err, errlen) != 0 ||
        medium_set_param(&s->media, o, "exterior", &sh->exterior, err, errlen) != 0)
        return -1;
    scene_obj *eo = scene_obj_child(o, SCENE_EMITTER);
    if (!eo)
        return 0;
    emitter_t *e = emitter_plugin_find(eo->type)->create(eo, sh, &s->textures, err, errlen);
    if (!e || add_emitter(s, eo, e, err, errlen) != 0)
        return -1;
    sh->emitter = e;
    return 0;
}

/* Every shape of the scene, instances expanded into their groups' shapes. */
static int build_shapes(struct scene *s, scene_obj *root, const scene_options *opt, char *err, size_t errlen)
{
    int n = 0, cap = 0;
    shape_leaf *leaves = NULL;
    for (int i = 0; i < root->nchildren; i++) {
        scene_obj *o = root->children[i];
        int k = o->cls == SCENE_SHAPE ? shape_leaves(o, NULL, 0, err, errlen) : 0;
        if (k < 0 || (k > 0 && n + k > cap && !(leaves = realloc(leaves, sizeof *leaves * (size_t)(cap = 2 * (n + k)))))) {
            free(leaves);
            return k < 0 ? -1 : scene_obj_error(root, err, errlen, "out of memory");
        }
        if (k > 0)
            n += shape_leaves(o, leaves + n, k, err, errlen);
    }
    s->shapes.items = calloc((size_t)n + 1, sizeof *s->shapes.items);
    int rc = s->shapes.items ? 0 : scene_obj_error(root, err, errlen, "out of memory");
    for (int i = 0; i < n && rc == 0; i++)
        rc = build_shape(s, &leaves[i], opt, err, errlen);
    free(leaves);
    return rc;
}

/* An emitter outside any shape; at most one environment. */
static int build_emitter(struct scene *s, scene_obj *o, char *err, size_t errlen)
{
    const emitter_plugin *plugin = emitter_plugin_find(o->type);
    bool env = (plugin->flags & EMITTER_ENVIRONMENT) != 0;
    if (env && s->emitters.env)
        return scene_obj_error(o, err, errlen, "only one environment emitter (constant or envmap) is supported");
    emitter_t *e = plugin->create(o, NULL, &s->textures, err, errlen);
    if (!e || add_emitter(s, o, e, err, errlen) != 0)
        return -1;
    if (env)
        s->emitters.env = e;
    return 0;
}

static int build_all(struct scene *s, scene_desc *desc, const scene_options *opt, char *err, size_t errlen)
{
    scene_obj *root = scene_desc_root(desc);
    if (build_integrator(s, root, err, errlen) != 0 || build_sensor(s, root, opt, err, errlen) != 0 ||
        build_shared(s, root, err, errlen) != 0)
        return -1;
    if (build_shapes(s, root, opt, err, errlen) != 0)
        return -1;
    for (int i = 0; i < root->nchildren; i++)
        if (root->children[i]->cls == SCENE_EMITTER && build_emitter(s, root->children[i], err, errlen) != 0)
            return -1;
    char msg[600];
    if (scene_obj_unconsumed(root, msg, sizeof msg)) {
        snprintf(err, errlen, "%s", msg);
        return -1;
    }
    if (emitter_list_commit(&s->emitters) != 0)
        return scene_obj_error(root, err, errlen, "out of memory");
    return shape_list_commit(&s->shapes, err, errlen);
}

scene_t *scene_create(scene_desc *desc, const scene_options *opt, char *err, size_t errlen)
{
    scene_options defaults = scene_options_default();
    if (!opt)
        opt = &defaults;
    if (opt->mesh_segments != 0 && opt->mesh_segments < 3) {
        snprintf(err, errlen, "mesh segments must be >= 3");
        return NULL;
    }
    struct scene *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    s->bsdfs.textures = &s->textures;
    if (build_all(s, desc, opt, err, errlen) != 0) {
        scene_destroy(s);
        return NULL;
    }
    s->digest = scene_digest_compute(desc, s, opt->mesh_segments);
    return s;
}

scene_t *scene_create_from_file(const char *path, const scene_define *defs, int ndefs, const scene_options *opt,
                                char *err, size_t errlen)
{
    scene_desc *d = opt ? scene_desc_create_from_file_in(path, opt->search_dirs, opt->n_search_dirs, defs, ndefs,
                                                         scene_plugin_find, err, errlen)
                        : scene_desc_create_from_file(path, defs, ndefs, scene_plugin_find, err, errlen);
    if (!d)
        return NULL;
    scene_t *s = scene_create(d, opt, err, errlen);
    scene_desc_destroy(d);
    return s;
}

void scene_destroy(scene_t *s)
{
    if (!s)
        return;
    shape_list_free(&s->shapes);
    emitter_list_free(&s->emitters);
    /* BSDFs borrow textures: free them first. */
    bsdf_set_free(&s->bsdfs);
    texture_set_free(&s->textures);
    medium_set_free(&s->media);
    integrator_destroy(s->integrator);
    free(s);
}
