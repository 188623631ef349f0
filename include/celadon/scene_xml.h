/* Scene description: Mitsuba 3's XML scene format read with libxml2 into a
 * plain property tree (docs/scene-format.md). The reader knows no plugin: it
 * checks every object against the declarations a lookup gives it
 * (scene_plugin_decl: the parameters with their types, the nested objects),
 * which the plugins themselves provide (src/render's scene_plugin_find
 * gathers every kind's registration table).
 *
 * Every object has a class (its XML tag), a plugin type, an optional id and
 * the file and line it came from; it holds typed properties and child
 * objects (nested or referenced with <ref>). Everything the declarations do
 * not allow is a load error naming file, line and feature: "scene.xml:12:
 * unknown plugin 'hair' for <bsdf>". Once loaded, a consumer reads
 * properties through the typed getters below, which mark them consumed; the
 * reader already guaranteed each property's name and type against the
 * declarations, so a getter falls back to its default only when the property
 * is absent or has another of its allowed types (int_ior as a float or an
 * IOR name, a color or a texture): check scene_obj_prop(o, name)->type for
 * those. */
#ifndef CELADON_SCENE_XML_H
#define CELADON_SCENE_XML_H

#include <stdbool.h>
#include <stddef.h>

#include "celadon/transform.h"
#include "celadon/vecmath.h"

typedef enum {
    SCENE_SCENE,
    SCENE_SENSOR,
    SCENE_FILM,
    SCENE_SAMPLER,
    SCENE_RFILTER,
    SCENE_INTEGRATOR,
    SCENE_SHAPE,
    SCENE_BSDF,
    SCENE_TEXTURE,
    SCENE_EMITTER,
    SCENE_MEDIUM,
    SCENE_PHASE,
    SCENE_VOLUME,
    SCENE_CLASS_COUNT
} scene_class;

typedef enum {
    SCENE_FLOAT,
    SCENE_INTEGER,
    SCENE_BOOLEAN,
    SCENE_STRING,
    SCENE_RGB,
    SCENE_SPECTRUM,  /* a constant spectrum, stored as gray RGB */
    SCENE_POINT,
    SCENE_VECTOR,
    SCENE_TRANSFORM,
    SCENE_OBJECT     /* a nested or referenced texture, medium or volume given by name */
} scene_prop_type;

typedef struct { double r, g, b; } scene_rgb;

typedef struct scene_obj scene_obj;

typedef struct {
    char *name;
    scene_prop_type type;
    const char *file;
    int line;
    bool consumed;
    union {
        double f;
        long long i;
        bool b;
        char *s;          /* STRING; a `filename` is resolved against its file's folder */
        scene_rgb rgb;    /* RGB, SPECTRUM */
        vec3 v;           /* POINT, VECTOR */
        transform4 xf;    /* TRANSFORM */
        scene_obj *obj;   /* OBJECT */
    } value;
} scene_prop;

struct scene_obj {
    scene_class cls;
    char *type;            /* plugin name, e.g. "perspective"; "scene" for the root */
    char *id;              /* NULL when none */
    char *name;            /* the name attribute of a nested object, or NULL */
    const char *file;
    int line;
    scene_prop *props;
    int nprops;
    scene_obj **children;  /* unnamed nested and referenced objects, document order */
    int nchildren;
};

typedef struct scene_desc scene_desc;

/* ------------------------------------------------------ plugin declarations */
/* What a plugin accepts, as its registration declares it once beside its
 * code. A parameter's allowed property types are bits (1 << scene_prop_type): */
#define PARAM_FLOAT (1u << SCENE_FLOAT)
#define PARAM_INT (1u << SCENE_INTEGER)
#define PARAM_BOOL (1u << SCENE_BOOLEAN)
#define PARAM_STRING (1u << SCENE_STRING)
#define PARAM_POINT (1u << SCENE_POINT)
#define PARAM_VECTOR (1u << SCENE_VECTOR)
#define PARAM_TRANSFORM (1u << SCENE_TRANSFORM)
#define PARAM_TEXTURE (1u << SCENE_OBJECT)
/* A named <medium> or <volume>: an object property like a texture, whose
 * class its consumer checks. */
#define PARAM_OBJECT PARAM_TEXTURE
/* Mitsuba's "spectrum": <rgb>, <spectrum> or a gray <float>. */
#define PARAM_COLOR ((1u << SCENE_RGB) | (1u << SCENE_SPECTRUM) | PARAM_FLOAT)

enum {
    PARAM_REQUIRED = 1, /* must be given */
    PARAM_FILE = 2,     /* a string naming a file relative to the scene file; must exist */
};

typedef struct {
    const char *name;
    unsigned types;      /* PARAM_FLOAT, ...: the property types allowed */
    unsigned flags;      /* PARAM_REQUIRED, PARAM_FILE */
    const char *choices; /* for string values: the allowed words separated by '|', or NULL */
} scene_param_decl;

/* Objects of class cls nested (or referenced) in the plugin's object. */
typedef struct {
    scene_class cls;
    int min, max;
    const char *only_type; /* NULL, or the one plugin of cls allowed here */
} scene_child_decl;

typedef struct {
    scene_class cls;
    const char *type;                 /* the plugin name, e.g. "diffuse" */
    const scene_param_decl *params;   /* terminated by a NULL name; NULL: none */
    const scene_child_decl *children; /* terminated by max == 0; NULL: none */
    const char *exclusive[2];         /* two parameters that may not both be given, or NULLs */
    scene_class host; /* SCENE_SCENE: wherever its class may be; otherwise only nested in an object of this class */
} scene_plugin_decl;

/* The declaration of plugin type of class cls, or NULL for an unknown one.
 * The scene root is looked up as (SCENE_SCENE, "scene"). */
typedef const scene_plugin_decl *(*scene_plugin_lookup)(scene_class cls, const char *type);

/* The entry named type in a NULL-terminated table of declarations, or NULL. */
const scene_plugin_decl *scene_plugin_table_find(const scene_plugin_decl *const *table, const char *type);

/* A kind's registration table from LIST, an X-macro of X(kind, name) lines:
 * each plugin is `const kind_plugin kind_name` (a struct whose first member
 * is its scene_plugin_decl), defined in its own file. Defines
 * `const scene_plugin_decl *const kind_plugins[]` (NULL-terminated) and
 * `const kind_plugin *kind_plugin_find(const char *name)`. */
#define SCENE_PLUGIN_EXTERN_(kind, name) extern const kind##_plugin kind##_##name;
#define SCENE_PLUGIN_ENTRY_(kind, name) &kind##_##name.decl,
#define SCENE_PLUGIN_TABLE(kind, LIST)                                                                             \
    LIST(SCENE_PLUGIN_EXTERN_)                                                                                     \
    const scene_plugin_decl *const kind##_plugins[] = {LIST(SCENE_PLUGIN_ENTRY_) NULL};                           \
    const kind##_plugin *kind##_plugin_find(const char *name)                                                      \
    {                                                                                                              \
        return (const kind##_plugin *)scene_plugin_table_find(kind##_plugins, name);                               \
    }

/* ------------------------------------------------------------- reading */
/* A -D name=value override; it takes precedence over <default>. A fallback
 * is the other way round: the value of $name only where the scene declares
 * no <default> for it, and no error when the scene does not use it
 * (`celadon render --spp N` is the fallback for $spp, which Mitsuba's own
 * scenes leave to the command line). */
typedef struct {
    const char *name, *value;
    bool fallback;
} scene_define;

/* Reads a scene file, checking it against the declarations plugins gives.
 * Returns NULL on error with one line "file:line: what" in err. An override
 * that the scene neither declares nor uses is an error. */
scene_desc *scene_desc_create_from_file(const char *path, const scene_define *defs, int ndefs,
                                        scene_plugin_lookup plugins, char *err, size_t errlen);
/* The same with extra folders where files are looked for, as Mitsuba's
 * `-a`: tried in order after every folder the scene itself gives
 * (docs/scene-format.md, "Paths"); each must be an existing folder. */
scene_desc *scene_desc_create_from_file_in(const char *path, const char *const *dirs, int ndirs,
                                           const scene_define *defs, int ndefs, scene_plugin_lookup plugins, char *err,
                                           size_t errlen);
/* The same from text in memory; path names it in messages and anchors
 * relative file names (it need not exist). */
scene_desc *scene_desc_create_from_text(const char *xml, size_t len, const char *path, const scene_define *defs,
                                        int ndefs, scene_plugin_lookup plugins, char *err, size_t errlen);
void scene_desc_destroy(scene_desc *d);

/* The root object (class SCENE). */
scene_obj *scene_desc_root(const scene_desc *d);

const char *scene_class_name(scene_class c); /* the XML tag: "bsdf" */

/* ------------------------------------------------------------- getters */
/* The named property (marked consumed), or NULL. */
scene_prop *scene_obj_prop(scene_obj *o, const char *name);
bool scene_obj_has(const scene_obj *o, const char *name);
double scene_obj_float(scene_obj *o, const char *name, double def);
long long scene_obj_int(scene_obj *o, const char *name, long long def);
bool scene_obj_bool(scene_obj *o, const char *name, bool def);
const char *scene_obj_string(scene_obj *o, const char *name, const char *def);
vec3 scene_obj_point(scene_obj *o, const char *name, vec3 def);
vec3 scene_obj_vector(scene_obj *o, const char *name, vec3 def);
/* Identity when absent. */
transform4 scene_obj_transform(scene_obj *o, const char *name);
/* A constant color from <rgb>, <spectrum> or <float> (gray); def when the
 * property is absent or is a texture (see scene_obj_texture). */
scene_rgb scene_obj_rgb(scene_obj *o, const char *name, scene_rgb def);
/* The texture given for a "spectrum or texture" property, or NULL. */
scene_obj *scene_obj_texture(scene_obj *o, const char *name);

/* Children of class cls in document order: writes up to max of them to out
 * (out may be NULL when max is 0) and returns how many there are. */
int scene_obj_children(const scene_obj *o, scene_class cls, scene_obj **out, int max);
/* The first child of class cls, or NULL. */
scene_obj *scene_obj_child(const scene_obj *o, scene_class cls);

/* Reports the first property nobody consumed in o and its descendants:
 * returns 1 and "file:line: <bsdf type='diffuse'> property 'x' was not used"
 * in msg, or 0 when all were consumed. */
int scene_obj_unconsumed(const scene_obj *o, char *msg, size_t msglen);

/* Writes "file:line: message" about o into err; returns -1. */
int scene_obj_error(const scene_obj *o, char *err, size_t errlen, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* ------------------------------------------------------ built objects */
/* What was built from the tree's objects, each object built once however
 * often it is referenced (a shared BSDF, a texture), in the order built. The
 * map owns its arrays and its index, not the values. Zero-initialise it. */
typedef struct {
    void **values;
    const scene_obj **keys;
    int count, cap;
    void *index; /* the keys in a search tree (tsearch): finding one takes log time */
} scene_obj_map;

/* The value built for key, or NULL. */
void *scene_obj_map_find(const scene_obj_map *m, const scene_obj *key);
/* Appends (key, value) for a key not in the map yet; returns 0, or -1 when
 * out of memory (or the key is there already). */
int scene_obj_map_add(scene_obj_map *m, const scene_obj *key, void *value);
void scene_obj_map_free(scene_obj_map *m);

#endif
