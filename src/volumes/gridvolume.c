/* The `gridvolume` volume: a voxel grid read from Mitsuba's binary .vol
 * file (`filename`, vol_file.c), its values not negative. The grid fills
 * the unit cube, placed by `to_world`; with `use_grid_bbox` (false) the
 * file's box is placed by it instead. `filter_type` trilinear (default) or nearest,
 * `wrap_mode` clamp (default), repeat or mirror; `raw` is accepted and
 * changes nothing in RGB. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "volumes/volume_impl.h"

/* The values of g, which must not be negative, into v; g's values move
 * to v. 0, or -1 with the problem in why. */
static int take_grid(vol_grid *g, volume_t *v, char *why, size_t whylen)
{
    size_t count = (size_t)g->nx * (size_t)g->ny * (size_t)g->nz * (size_t)g->channels;
    v->max = 0.0;
    for (size_t i = 0; i < count; i++) {
        if (!(g->values[i] >= 0.0f)) {
            snprintf(why, whylen, "value %zu is %g: values must not be negative", i, (double)g->values[i]);
            return -1;
        }
        v->max = fmax(v->max, g->values[i]);
    }
    v->grid = g->values;
    v->nx = g->nx, v->ny = g->ny, v->nz = g->nz, v->channels = g->channels;
    g->values = NULL;
    return 0;
}

static volume_t *gridvolume_create(scene_obj *o, char *err, size_t errlen)
{
    const char *path = scene_obj_string(o, "filename", "");
    const char *wrap = scene_obj_string(o, "wrap_mode", "clamp");
    bool nearest = strcmp(scene_obj_string(o, "filter_type", "trilinear"), "nearest") == 0;
    bool grid_box = scene_obj_bool(o, "use_grid_bbox", false);
    (void)scene_obj_bool(o, "raw", false);
    transform4 to_world = scene_obj_transform(o, "to_world");
    volume_t *v = volume_alloc(o, err, errlen);
    if (!v)
        return NULL;
    v->nearest = nearest;
    v->wrap = strcmp(wrap, "repeat") == 0 ? VOLUME_REPEAT : strcmp(wrap, "mirror") == 0 ? VOLUME_MIRROR : VOLUME_CLAMP;
    char why[256];
    vol_grid g;
    if (vol_grid_read(path, &g, why, sizeof why) != 0 || take_grid(&g, v, why, sizeof why) != 0) {
        scene_obj_error(o, err, errlen, "%s: %s", path, why);
        vol_grid_free(&g);
        volume_destroy(v);
        return NULL;
    }
    vec3 lo = g.lo, hi = g.hi;
    if (grid_box) {
        vec3 size = v3_sub(hi, lo);
        if (!(size.x > 0.0 && size.y > 0.0 && size.z > 0.0)) {
            scene_obj_error(o, err, errlen, "%s: the file's bounding box is empty (use_grid_bbox)", path);
            volume_destroy(v);
            return NULL;
        }
        transform4 t = transform_translate(lo), s = transform_scale(size), box = transform_compose(&t, &s);
        to_world = transform_compose(&to_world, &box);
    }
    v->bounded = true;
    v->to_local = transform_inverse(&to_world);
    return v;
}

static const scene_param_decl gridvolume_params[] = {
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    {"use_grid_bbox", PARAM_BOOL, 0, NULL},
    {"filter_type", PARAM_STRING, 0, "trilinear|nearest"},
    {"wrap_mode", PARAM_STRING, 0, "clamp|repeat|mirror"},
    {"raw", PARAM_BOOL, 0, NULL},
    {NULL, 0, 0, NULL},
};

const volume_plugin volume_gridvolume = {
    .decl = {.cls = SCENE_VOLUME, .type = "gridvolume", .params = gridvolume_params},
    .create = gridvolume_create,
};
