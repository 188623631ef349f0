/* Typed access to a loaded scene description, with consumption tracking,
 * and messages about its objects. */
#include <search.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "celadon/scene_xml.h"

static scene_prop *lookup(const scene_obj *o, const char *name)
{
    for (int i = 0; i < o->nprops; i++)
        if (strcmp(o->props[i].name, name) == 0)
            return &o->props[i];
    return NULL;
}

bool scene_obj_has(const scene_obj *o, const char *name) { return lookup(o, name) != NULL; }

scene_prop *scene_obj_prop(scene_obj *o, const char *name)
{
    scene_prop *p = lookup(o, name);
    if (p)
        p->consumed = true;
    return p;
}

/* The property if present with type t (consumed), else NULL. */
static scene_prop *typed(scene_obj *o, const char *name, scene_prop_type t)
{
    scene_prop *p = lookup(o, name);
    if (!p || p->type != t)
        return NULL;
    p->consumed = true;
    return p;
}

double scene_obj_float(scene_obj *o, const char *name, double def)
{
    scene_prop *p = typed(o, name, SCENE_FLOAT);
    return p ? p->value.f : def;
}

long long scene_obj_int(scene_obj *o, const char *name, long long def)
{
    scene_prop *p = typed(o, name, SCENE_INTEGER);
    return p ? p->value.i : def;
}

bool scene_obj_bool(scene_obj *o, const char *name, bool def)
{
    scene_prop *p = typed(o, name, SCENE_BOOLEAN);
    return p ? p->value.b : def;
}

const char *scene_obj_string(scene_obj *o, const char *name, const char *def)
{
    scene_prop *p = typed(o, name, SCENE_STRING);
    return p ? p->value.s : def;
}

vec3 scene_obj_point(scene_obj *o, const char *name, vec3 def)
{
    scene_prop *p = typed(o, name, SCENE_POINT);
    return p ? p->value.v : def;
}

vec3 scene_obj_vector(scene_obj *o, const char *name, vec3 def)
{
    scene_prop *p = typed(o, name, SCENE_VECTOR);
    return p ? p->value.v : def;
}

transform4 scene_obj_transform(scene_obj *o, const char *name)
{
    scene_prop *p = typed(o, name, SCENE_TRANSFORM);
    return p ? p->value.xf : transform_identity();
}

scene_rgb scene_obj_rgb(scene_obj *o, const char *name, scene_rgb def)
{
    scene_prop *p = lookup(o, name);
    if (!p)
        return def;
    switch (p->type) {
    case SCENE_RGB:
    case SCENE_SPECTRUM:
        p->consumed = true;
        return p->value.rgb;
    case SCENE_FLOAT:
        p->consumed = true;
        return (scene_rgb){p->value.f, p->value.f, p->value.f};
    default:
        return def;
    }
}

scene_obj *scene_obj_texture(scene_obj *o, const char *name)
{
    scene_prop *p = typed(o, name, SCENE_OBJECT);
    return p ? p->value.obj : NULL;
}

int scene_obj_children(const scene_obj *o, scene_class cls, scene_obj **out, int max)
{
    int n = 0;
    for (int i = 0; i < o->nchildren; i++)
        if (o->children[i]->cls == cls) {
            if (n < max)
                out[n] = o->children[i];
            n++;
        }
    return n;
}

scene_obj *scene_obj_child(const scene_obj *o, scene_class cls)
{
    scene_obj *c = NULL;
    scene_obj_children(o, cls, &c, 1);
    return c;
}

static int by_address(const void *a, const void *b) { return a < b ? -1 : a > b; }

/* The set of seen objects owns none of them. */
static void keep(void *o) { (void)o; }

/* scene_obj_unconsumed over the objects not seen yet: a shared object is
 * reached by every path to it, and a chain of them doubling at each step
 * would be walked exponentially often. */
static int unconsumed_in(const scene_obj *o, void **seen, char *msg, size_t msglen)
{
    if (tfind(o, seen, by_address))
        return 0;
    if (!tsearch(o, seen, by_address)) {
        snprintf(msg, msglen, "out of memory");
        return 1;
    }
    for (int i = 0; i < o->nprops; i++) {
        const scene_prop *p = &o->props[i];
        if (!p->consumed) {
            if (o->cls == SCENE_SCENE)
                snprintf(msg, msglen, "%s:%d: <scene> property '%s' was not used", p->file, p->line, p->name);
            else
                snprintf(msg, msglen, "%s:%d: <%s type=\"%s\"> property '%s' was not used", p->file, p->line,
                         scene_class_name(o->cls), o->type, p->name);
            return 1;
        }
        if (p->type == SCENE_OBJECT && unconsumed_in(p->value.obj, seen, msg, msglen))
            return 1;
    }
    for (int i = 0; i < o->nchildren; i++)
        if (unconsumed_in(o->children[i], seen, msg, msglen))
            return 1;
    return 0;
}

int scene_obj_unconsumed(const scene_obj *o, char *msg, size_t msglen)
{
    void *seen = NULL;
    int rc = unconsumed_in(o, &seen, msg, msglen);
    tdestroy(seen, keep);
    return rc;
}

int scene_obj_error(const scene_obj *o, char *err, size_t errlen, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(err, errlen, "%s:%d: %s", o->file, o->line, msg);
    return -1;
}
