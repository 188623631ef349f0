/* Parser state and declaration helpers shared by the scene_xml*.c files. */
#ifndef CELADON_SCENE_XML_INTERNAL_H
#define CELADON_SCENE_XML_INTERNAL_H

#include <libxml/hash.h>
#include <libxml/tree.h>

#include "celadon/scene_xml.h"

#define SCENE_MAX_INCLUDE_DEPTH 32
/* The deepest chain of nested or referenced objects a scene may have (real
 * scenes nest a handful: shape, twosided, blend, texture). */
#define SCENE_MAX_NESTING 100

struct scene_desc {
    scene_obj *root;
    scene_obj **objs; /* every object, owned */
    int nobjs, capobjs;
    xmlHashTablePtr ids; /* id -> object, for every object with an id */
    char **files;     /* interned file names the objects point to */
    int nfiles;
};

typedef struct {
    char *name, *value;
    int from_cli; /* given as -D (wins over <default>) */
    int used;     /* substituted somewhere */
    int declared; /* named by a <default> */
    int fallback; /* a fallback define, until a <default> replaces it */
} scene_param;

typedef struct {
    scene_obj *parent;
    char *id, *name;
    const char *file;
    int line;
} scene_pending_ref;

typedef struct {
    scene_desc *d;
    scene_plugin_lookup plugins;
    scene_param *params;
    int nparams;
    scene_pending_ref *refs;
    int nrefs;
    char *stack[SCENE_MAX_INCLUDE_DEPTH]; /* canonical paths of the files being read */
    int depth;
    const char *file; /* the file being read (interned) */
    char *scene_dir;  /* the folder of the scene file itself */
    char **paths;     /* the folders <path> added, latest first */
    int npaths;
    const char *const *extra_dirs; /* the caller's folders (render -a), tried last, in order */
    int nextra;
    int line_hint;    /* the line of the element being read, for messages about its parts */
    char *err;
    size_t errlen;
    int failed;
} scene_ctx;

/* Records "file:line: message" (line <= 0: "file: message") unless an error
 * is already recorded; returns -1. */
int scene_fail(scene_ctx *c, int line, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
int scene_line(const xmlNode *n);

/* The attribute with $name parameters substituted, malloc'd, in *out; NULL
 * when absent. Returns 0 or -1 (undefined parameter). */
int scene_attr(scene_ctx *c, const xmlNode *n, const char *name, char **out);
/* Like scene_attr but absence is an error. */
int scene_attr_req(scene_ctx *c, const xmlNode *n, const char *name, char **out);
/* Fails on an attribute not in the '|'-separated list. */
int scene_check_attrs(scene_ctx *c, const xmlNode *n, const char *allowed);

/* Strict numbers: the whole text must parse, finite. */
int scene_parse_double(const char *s, double *out);
/* Up to max numbers separated by commas and/or white space; returns the
 * count, or -1 on a bad token or more than max. */
int scene_parse_list(const char *s, double *out, int max);

/* Parses a property element (<float>, <rgb>, <transform>, ...) of an object
 * of class owner into p (name, type, value, file, line). Returns 0 or -1. */
int scene_parse_property(scene_ctx *c, const xmlNode *n, scene_class owner, scene_prop *p);
/* A <spectrum> element of an object of class owner into p, as an RGB
 * (scene_xml_spectrum.c). Returns 0 or -1. */
int scene_parse_spectrum(scene_ctx *c, const xmlNode *n, scene_class owner, scene_prop *p);

/* Where a file name is looked for (docs/scene-format.md, "Paths"): the
 * folder of from_file (the file that names it), the scene file's folder,
 * each <path> folder, the latest first, then the caller's extra folders. Returns the first candidate
 * that exists, or the first candidate when none does (the caller's open or
 * stat then reports it); malloc'd. */
char *scene_resolve_path(scene_ctx *c, const char *from_file, const char *name);
/* Whether tag names a property element. */
int scene_is_property_tag(const char *tag);
void scene_prop_clear(scene_prop *p);

/* ------------------------------------------------------- older scenes */
/* Upgrades the document under root, of a Mitsuba before 2.0, in place
 * (scene_xml_upgrade.c). */
void scene_upgrade_v1(xmlNode *root);
/* in as snake_case the way Mitsuba 3 converts camelCase: an upper-case run
 * after a lower-case letter becomes "_" and the run in lower case. */
void scene_snake_case(const char *in, char *out, size_t outlen);
/* Whether parameter name of class cls is one Mitsuba 3 ignores and the
 * reader drops. */
int scene_param_obsolete(scene_class cls, const char *name);
/* Why a Mitsuba plugin celadon does not have is refused, when it is one of
 * those refused by name (polarized, spectral-only, dropped by Mitsuba 3),
 * or NULL. */
const char *scene_plugin_refusal(scene_class cls, const char *type);

/* ------------------------------------------------ reading the declarations */
const scene_param_decl *schema_param_find(const scene_plugin_decl *p, const char *name);
const scene_child_decl *schema_child_find(const scene_plugin_decl *p, scene_class cls);
/* Whether word is one of the '|'-separated choices. */
int schema_choice_ok(const char *choices, const char *word);
/* "float, rgb or texture": the allowed types as words. */
void schema_types_text(unsigned types, char *buf, size_t len);
/* The XML tag of a property type: "float", "rgb", ...; "texture" for OBJECT. */
const char *schema_type_tag(scene_prop_type t);

#endif
