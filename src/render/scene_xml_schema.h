/* The supported subset of Mitsuba 3: for each object class and plugin type,
 * the properties it accepts (name, allowed types, flags) and the child
 * objects it may hold. Internal to the scene parser. */
#ifndef CELADON_SCENE_XML_SCHEMA_H
#define CELADON_SCENE_XML_SCHEMA_H

#include <stddef.h>

#include "celadon/scene_xml.h"

/* Allowed property types, one bit per scene_prop_type. */
#define PT(t) (1u << (t))
#define PT_FLOAT PT(SCENE_FLOAT)
#define PT_INT PT(SCENE_INTEGER)
#define PT_BOOL PT(SCENE_BOOLEAN)
#define PT_STRING PT(SCENE_STRING)
#define PT_POINT PT(SCENE_POINT)
#define PT_VECTOR PT(SCENE_VECTOR)
#define PT_TRANSFORM PT(SCENE_TRANSFORM)
#define PT_TEXTURE PT(SCENE_OBJECT)
/* Mitsuba's "spectrum": <rgb>, <spectrum> or a gray <float>. */
#define PT_COLOR (PT(SCENE_RGB) | PT(SCENE_SPECTRUM) | PT_FLOAT)

enum {
    PF_REQUIRED = 1, /* must be given */
    PF_FILE = 2,     /* a string naming a file relative to the scene file; must exist */
};

typedef struct {
    const char *name;
    unsigned types;
    unsigned flags;
    const char *choices; /* for string values: allowed words separated by '|', or NULL */
} schema_param;

typedef struct {
    scene_class cls;
    int min, max;
} schema_child;

typedef struct {
    scene_class cls;
    const char *type;
    const schema_param *params;   /* terminated by a NULL name */
    const schema_child *children; /* terminated by max == 0 */
    const char *exclusive[2];     /* two properties that may not both be given, or NULLs */
} schema_plugin;

/* The plugin entry, or NULL when the subset has no such plugin. The scene
 * root is looked up as (SCENE_SCENE, "scene"). */
const schema_plugin *schema_find(scene_class cls, const char *type);
/* The i-th plugin of the table, or NULL past its end. */
const schema_plugin *schema_plugin_at(int i);
const schema_param *schema_param_find(const schema_plugin *p, const char *name);
const schema_child *schema_child_find(const schema_plugin *p, scene_class cls);
/* Whether word is one of the '|'-separated choices. */
int schema_choice_ok(const char *choices, const char *word);
/* "float, rgb or texture": the allowed types as words. */
void schema_types_text(unsigned types, char *buf, size_t len);
/* The XML tag of a property type: "float", "rgb", ...; "texture" for OBJECT. */
const char *schema_type_tag(scene_prop_type t);

#endif
