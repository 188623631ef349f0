/* Mitsuba's reconstruction filters `box`, `gaussian` (`stddev`; Mitsuba's
 * film default) and `tent`: accepted, and today none changes the film,
 * which counts each sample in the pixel it falls in (a one-pixel box;
 * docs/scene-format.md, "Differences"). A filter that does change it gets
 * a file of its own. */
#include "sensors/sensors.h"

/* The parameters are read (and so count as used); the film stays as it is. */
static int accept_only(scene_obj *o, film_settings *out, char *err, size_t errlen)
{
    (void)out, (void)err, (void)errlen;
    for (const scene_param_decl *p = rfilter_plugin_find(o->type)->decl.params; p && p->name; p++)
        scene_obj_prop(o, p->name);
    return 0;
}

static const scene_param_decl gaussian_params[] = {{"stddev", PARAM_FLOAT, 0, NULL}, {NULL, 0, 0, NULL}};

const rfilter_plugin rfilter_box = {
    .decl = {.cls = SCENE_RFILTER, .type = "box"},
    .create = accept_only,
};

const rfilter_plugin rfilter_gaussian = {
    .decl = {.cls = SCENE_RFILTER, .type = "gaussian", .params = gaussian_params},
    .create = accept_only,
};

const rfilter_plugin rfilter_tent = {
    .decl = {.cls = SCENE_RFILTER, .type = "tent"},
    .create = accept_only,
};
