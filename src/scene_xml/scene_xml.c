/* The scene reader: documents, includes, defaults, objects, references and
 * validation against the plugin declarations the caller's lookup gives. */
#include <ctype.h>
#include <errno.h>
#include <libgen.h>
#include <libxml/SAX2.h>
#include <libxml/parser.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/core.h"
#include "scene_xml/scene_xml_internal.h"

static const char *class_tags[SCENE_CLASS_COUNT] = {
    "scene", "sensor", "film", "sampler", "rfilter", "integrator", "shape", "bsdf", "texture", "emitter",
    "medium", "phase", "volume"};

const char *scene_class_name(scene_class c) { return c >= 0 && c < SCENE_CLASS_COUNT ? class_tags[c] : "?"; }

static int class_of_tag(const char *tag)
{
    for (int i = 1; i < SCENE_CLASS_COUNT; i++)
        if (strcmp(tag, class_tags[i]) == 0)
            return i;
    return -1;
}

static void *xrealloc(void *p, size_t n)
{
    p = realloc(p, n);
    if (!p)
        abort();
    return p;
}

static char *xstrdup(const char *s)
{
    char *r = strdup(s);
    if (!r)
        abort();
    return r;
}

/* -------------------------------------------------------------- ownership */
static const char *intern_file(scene_desc *d, const char *path)
{
    for (int i = 0; i < d->nfiles; i++)
        if (strcmp(d->files[i], path) == 0)
            return d->files[i];
    d->files = xrealloc(d->files, sizeof(char *) * (size_t)(d->nfiles + 1));
    return d->files[d->nfiles++] = xstrdup(path);
}

static scene_obj *new_obj(scene_ctx *c, scene_class cls, const char *type, int line)
{
    scene_desc *d = c->d;
    if (d->nobjs == d->capobjs) {
        d->capobjs = d->capobjs ? 2 * d->capobjs : 16;
        d->objs = xrealloc(d->objs, sizeof(scene_obj *) * (size_t)d->capobjs);
    }
    scene_obj *o = calloc(1, sizeof *o);
    if (!o)
        abort();
    o->cls = cls;
    o->type = xstrdup(type);
    o->file = c->file;
    o->line = line;
    d->objs[d->nobjs++] = o;
    return o;
}

static void free_obj(scene_obj *o)
{
    for (int i = 0; i < o->nprops; i++)
        scene_prop_clear(&o->props[i]);
    free(o->props);
    free(o->children);
    free(o->type);
    free(o->id);
    free(o->name);
    free(o);
}

void scene_desc_destroy(scene_desc *d)
{
    if (!d)
        return;
    for (int i = 0; i < d->nobjs; i++)
        free_obj(d->objs[i]);
    for (int i = 0; i < d->nfiles; i++)
        free(d->files[i]);
    free(d->objs);
    free(d->files);
    xmlHashFree(d->ids, NULL);
    free(d);
}

scene_obj *scene_desc_root(const scene_desc *d) { return d->root; }

/* ------------------------------------------------------------ validation */
static void describe(const scene_obj *o, char *buf, size_t len)
{
    if (o->cls == SCENE_SCENE)
        snprintf(buf, len, "<scene>");
    else
        snprintf(buf, len, "<%s type=\"%s\">", scene_class_name(o->cls), o->type);
}

static scene_prop *find_prop(const scene_obj *o, const char *name)
{
    for (int i = 0; i < o->nprops; i++)
        if (strcmp(o->props[i].name, name) == 0)
            return &o->props[i];
    return NULL;
}

/* name in the folder dir; "." stays implicit. */
static char *join_path(const char *dir, const char *name)
{
    if (name[0] == '/' || strcmp(dir, ".") == 0)
        return xstrdup(name);
    size_t n = strlen(dir) + strlen(name) + 2;
    char *r = xrealloc(NULL, n);
    snprintf(r, n, "%s/%s", dir, name);
    return r;
}

static char *folder_of(const char *file)
{
    char *tmp = xstrdup(file);
    char *dir = xstrdup(dirname(tmp));
    free(tmp);
    return dir;
}

char *scene_resolve_path(scene_ctx *c, const char *from_file, const char *name)
{
    char *first = folder_of(from_file), *r = join_path(first, name);
    free(first);
    struct stat st;
    if (name[0] == '/' || stat(r, &st) == 0)
        return r;
    for (int i = -1; i < c->npaths + c->nextra; i++) {
        char *alt = join_path(i < 0 ? c->scene_dir : i < c->npaths ? c->paths[i] : c->extra_dirs[i - c->npaths], name);
        if (stat(alt, &st) == 0) {
            free(r);
            return alt;
        }
        free(alt);
    }
    return r;
}

static int check_file(scene_ctx *c, int line, const char *shown, const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return scene_fail(c, line, "file '%s' not found (%s: %s)", shown, path, strerror(errno));
    char why[256];
    if (input_check(path, INPUT_MAX_DATA_BYTES, NULL, why, sizeof why) != 0)
        return scene_fail(c, line, "'%s' (%s): %s", shown, path, why);
    return 0;
}

/* Adds p to o after checking it against o's plugin table; takes ownership of
 * p's contents (also on failure). */
static int add_prop(scene_ctx *c, scene_obj *o, scene_prop *p)
{
    char what[160], allowed[160];
    describe(o, what, sizeof what);
    const scene_plugin_decl *sp = c->plugins(o->cls, o->type);
    const scene_param_decl *par = schema_param_find(sp, p->name);
    if (!par && scene_param_obsolete(o->cls, p->name)) {
        scene_prop_clear(p);
        return 0;
    }
    int rc = 0;
    const scene_prop *dup = find_prop(o, p->name);
    if (!par) {
        rc = scene_fail(c, p->line, "unknown parameter '%s' for %s", p->name, what);
    } else if (!(par->types & (1u << p->type))) {
        schema_types_text(par->types, allowed, sizeof allowed);
        rc = scene_fail(c, p->line, "parameter '%s' of %s must be %s, not <%s>", p->name, what, allowed,
                        schema_type_tag(p->type));
    } else if (dup) {
        rc = scene_fail(c, p->line, "parameter '%s' of %s given twice (first at %s:%d)", p->name, what, dup->file,
                        dup->line);
    } else if (p->type == SCENE_STRING && par->choices && !schema_choice_ok(par->choices, p->value.s)) {
        rc = scene_fail(c, p->line, "bad value '%s' for '%s' of %s (one of: %s)", p->value.s, p->name, what,
                        par->choices);
    } else if (p->type == SCENE_STRING && (par->flags & PARAM_FILE)) {
        char *path = scene_resolve_path(c, p->file, p->value.s);
        rc = check_file(c, p->line, p->value.s, path);
        free(p->value.s);
        p->value.s = path;
    }
    if (rc != 0) {
        scene_prop_clear(p);
        return -1;
    }
    o->props = xrealloc(o->props, sizeof(scene_prop) * (size_t)(o->nprops + 1));
    o->props[o->nprops++] = *p;
    return 0;
}

/* Puts child under parent: a texture, medium or volume below an object sets
 * the property its name says (unless, for a texture, the object takes nested
 * textures whatever their name, as bumpmap does, and the name is none of its
 * parameters, or, for a medium, the object takes one as a child); anything else
 * joins the children, within the table's limits. */
static int attach(scene_ctx *c, scene_obj *parent, scene_obj *child, const char *name, int line)
{
    char pw[160], cw[160];
    describe(parent, pw, sizeof pw);
    describe(child, cw, sizeof cw);
    const scene_plugin_decl *pd = c->plugins(parent->cls, parent->type);
    bool any_name = schema_child_find(pd, SCENE_TEXTURE) && !(name && schema_param_find(pd, name));
    /* a medium sets a named parameter (a shape's interior), unless the
     * object takes one whatever its name (a sensor's, as Mitsuba's endpoints) */
    bool medium_by_name = child->cls == SCENE_MEDIUM && !schema_child_find(pd, SCENE_MEDIUM);
    bool by_name = (child->cls == SCENE_TEXTURE && !any_name) || medium_by_name || child->cls == SCENE_VOLUME;
    if (by_name && parent->cls != SCENE_SCENE) {
        if (!name)
            return scene_fail(c, line, "%s inside %s needs a name (the parameter it sets)", cw, pw);
        scene_prop p = {0};
        p.name = xstrdup(name);
        p.type = SCENE_OBJECT;
        p.file = c->file;
        p.line = line;
        p.value.obj = child;
        return add_prop(c, parent, &p);
    }
    const scene_child_decl *rule = schema_child_find(c->plugins(parent->cls, parent->type), child->cls);
    if (!rule)
        return scene_fail(c, line, "%s cannot contain a <%s>", pw, scene_class_name(child->cls));
    if (rule->only_type && strcmp(child->type, rule->only_type) != 0)
        return scene_fail(c, line, "%s: only an '%s' %s can be attached to a %s", pw, rule->only_type,
                          scene_class_name(child->cls), scene_class_name(parent->cls));
    scene_class host = c->plugins(child->cls, child->type)->host;
    if (host != SCENE_SCENE && parent->cls != host)
        return scene_fail(c, line, "%s must be nested in a <%s>", cw, scene_class_name(host));
    /* Counted only when the limit is within reach: linear in the children. */
    if (parent->nchildren >= rule->max && scene_obj_children(parent, child->cls, NULL, 0) >= rule->max)
        return scene_fail(c, line, "%s takes at most %d <%s>", pw, rule->max, scene_class_name(child->cls));
    parent->children = xrealloc(parent->children, sizeof(scene_obj *) * (size_t)(parent->nchildren + 1));
    parent->children[parent->nchildren++] = child;
    return 0;
}

static scene_obj *find_id(const scene_desc *d, const char *id)
{
    return xmlHashLookup(d->ids, BAD_CAST id);
}

/* Required parameters, minimum child counts, exclusive pairs. */
static int validate_obj(scene_ctx *c, const scene_obj *o)
{
    char what[160];
    describe(o, what, sizeof what);
    const scene_plugin_decl *sp = c->plugins(o->cls, o->type);
    const char *saved = c->file;
    c->file = o->file;
    int rc = 0;
    for (const scene_param_decl *q = sp->params; q && q->name && rc == 0; q++)
        if ((q->flags & PARAM_REQUIRED) && !find_prop(o, q->name))
            rc = scene_fail(c, o->line, "%s needs the parameter '%s'", what, q->name);
    for (const scene_child_decl *r = sp->children; r && r->max > 0 && rc == 0; r++)
        if (scene_obj_children(o, r->cls, NULL, 0) < r->min)
            rc = scene_fail(c, o->line, "%s needs at least %d nested <%s>", what, r->min, scene_class_name(r->cls));
    if (rc == 0 && sp->exclusive[0] && find_prop(o, sp->exclusive[0]) && find_prop(o, sp->exclusive[1]))
        rc = scene_fail(c, find_prop(o, sp->exclusive[1])->line, "%s takes '%s' or '%s', not both", what,
                        sp->exclusive[0], sp->exclusive[1]);
    if (rc == 0)
        c->file = saved;
    return rc;
}

/* Objects sorted by address, to find an object's slot in the DFS state. */
static int cmp_ptr(const void *a, const void *b)
{
    const scene_obj *x = *(scene_obj *const *)a, *y = *(scene_obj *const *)b;
    return x < y ? -1 : x > y;
}

typedef struct {
    scene_obj **sorted; /* the objects by address */
    int *height;        /* per sorted slot: 0 new, -1 on the path, else the longest chain from it */
    int n;
} dfs_t;

/* Depth-first search for a cycle made by references, and for a chain of
 * objects (nested or referenced) longer than SCENE_MAX_NESTING, which every
 * later walk of the tree would follow as deep. depth: the objects above o on
 * the way down. Returns the object's height, or -1. */
static int find_cycle(scene_ctx *c, dfs_t *g, scene_obj *o, int depth)
{
    scene_obj **slot = bsearch(&o, g->sorted, (size_t)g->n, sizeof(scene_obj *), cmp_ptr);
    int *h = &g->height[slot - g->sorted];
    if (*h > 0)
        return *h;
    char what[160];
    describe(o, what, sizeof what);
    c->file = o->file;
    if (*h < 0)
        return scene_fail(c, o->line, "reference cycle: %s (id '%s') contains itself", what, o->id ? o->id : "");
    if (depth > SCENE_MAX_NESTING) /* the way down is as long: stop before the stack runs out */
        return scene_fail(c, o->line, "%s lies in a chain of nested or referenced objects more than %d deep", what,
                          SCENE_MAX_NESTING);
    *h = -1;
    int below = 0;
    for (int i = 0; i < o->nchildren + o->nprops && below >= 0; i++) {
        scene_obj *next = i < o->nchildren ? o->children[i]
                          : o->props[i - o->nchildren].type == SCENE_OBJECT ? o->props[i - o->nchildren].value.obj
                                                                             : NULL;
        int hn = next ? find_cycle(c, g, next, depth + 1) : 0;
        below = hn < 0 ? -1 : below > hn ? below : hn;
    }
    if (below < 0)
        return -1;
    if (below + 1 > SCENE_MAX_NESTING) {
        c->file = o->file;
        return scene_fail(c, o->line, "%s holds a chain of nested or referenced objects more than %d deep", what,
                          SCENE_MAX_NESTING);
    }
    return *h = below + 1;
}

/* --------------------------------------------------------------- parsing */
static int parse_document(scene_ctx *c, const char *xml, size_t len, const char *path, scene_obj *parent);

static int parse_include(scene_ctx *c, const xmlNode *n, scene_obj *parent)
{
    int line = scene_line(n);
    char *name;
    if (scene_check_attrs(c, n, "filename") != 0 || scene_attr_req(c, n, "filename", &name) != 0)
        return -1;
    char *path = scene_resolve_path(c, c->file, name);
    char canon[PATH_MAX], why[256];
    char *buf = NULL;
    size_t len = 0;
    int rc = 0;
    if (!realpath(path, canon))
        rc = scene_fail(c, line, "cannot read included file '%s' (%s: %s)", name, path, strerror(errno));
    else if (input_read_all(path, INPUT_MAX_TEXT_BYTES, &buf, &len, why, sizeof why) != 0)
        rc = scene_fail(c, line, "cannot read included file '%s' (%s: %s)", name, path, why);
    for (int i = 0; i < c->depth && rc == 0; i++)
        if (strcmp(c->stack[i], canon) == 0)
            rc = scene_fail(c, line, "include cycle: '%s' is already being included", name);
    if (rc == 0 && c->depth == SCENE_MAX_INCLUDE_DEPTH)
        rc = scene_fail(c, line, "includes nested deeper than %d", SCENE_MAX_INCLUDE_DEPTH);
    if (rc == 0) {
        c->stack[c->depth++] = xstrdup(canon);
        const char *saved = c->file;
        rc = parse_document(c, buf, len, path, parent);
        if (rc == 0)
            c->file = saved;
        free(c->stack[--c->depth]);
    }
    free(buf);
    free(path);
    free(name);
    return rc;
}

/* <path value="folder"/>: one more folder to look for files in, relative
 * to the file that names it (or found as a file name is); it must exist. */
static int parse_path(scene_ctx *c, const xmlNode *n)
{
    char *value;
    if (scene_check_attrs(c, n, "value") != 0 || scene_attr_req(c, n, "value", &value) != 0)
        return -1;
    char *path = scene_resolve_path(c, c->file, value);
    struct stat st;
    int rc = 0;
    if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode)) {
        rc = scene_fail(c, scene_line(n), "<path>: folder '%s' not found (%s)", value, path);
        free(path);
    } else {
        c->paths = xrealloc(c->paths, sizeof(char *) * (size_t)(c->npaths + 1));
        memmove(c->paths + 1, c->paths, sizeof(char *) * (size_t)c->npaths);
        c->paths[0] = path;
        c->npaths++;
    }
    free(value);
    return rc;
}

static int parse_default(scene_ctx *c, const xmlNode *n)
{
    char *name = NULL, *value = NULL;
    int rc = 0;
    if (scene_check_attrs(c, n, "name|value") != 0 || scene_attr_req(c, n, "name", &name) != 0 ||
        scene_attr_req(c, n, "value", &value) != 0) {
        rc = -1;
    } else {
        scene_param *p = NULL;
        for (int i = 0; i < c->nparams; i++)
            if (strcmp(c->params[i].name, name) == 0)
                p = &c->params[i];
        if (!p) { /* an earlier -D or <default> wins over this one, which wins over a fallback */
            c->params = xrealloc(c->params, sizeof(scene_param) * (size_t)(c->nparams + 1));
            p = &c->params[c->nparams++];
            *p = (scene_param){xstrdup(name), xstrdup(value), 0, 0, 0, 0};
        } else if (p->fallback) {
            free(p->value);
            p->value = xstrdup(value);
            p->fallback = 0;
        }
        p->declared = 1;
    }
    free(name);
    free(value);
    return rc;
}

static int parse_ref(scene_ctx *c, const xmlNode *n, scene_obj *parent)
{
    char *id = NULL, *name = NULL;
    if (scene_check_attrs(c, n, "id|name") != 0 || scene_attr_req(c, n, "id", &id) != 0 ||
        scene_attr(c, n, "name", &name) != 0) {
        free(id);
        return -1;
    }
    c->refs = xrealloc(c->refs, sizeof(scene_pending_ref) * (size_t)(c->nrefs + 1));
    c->refs[c->nrefs++] = (scene_pending_ref){parent, id, name, c->file, scene_line(n)};
    return 0;
}

static int parse_children(scene_ctx *c, const xmlNode *n, scene_obj *o, int file_scene_level);

/* An object with an id at the top level that the scene itself cannot hold
 * (a sampler, a film, an area emitter, ...) is only declared there, for
 * <ref>s to place it, as in Mitsuba; unreferenced, it is not used. */
static int declared_only(scene_ctx *c, const scene_obj *parent, const scene_obj *o)
{
    if (parent->cls != SCENE_SCENE || !o->id)
        return 0;
    return !schema_child_find(c->plugins(SCENE_SCENE, "scene"), o->cls) || c->plugins(o->cls, o->type)->host != SCENE_SCENE;
}

/* Mitsuba 3 loads a plugin from the file plugins/<type>.so (.dylib, .dll),
 * so on the case-insensitive file systems of macOS and Windows `Rectangle`
 * loads `rectangle` (some of Mitsuba's own scenes say so): a type that names
 * no plugin becomes its lower-case spelling when that one does. */
static void fold_plugin_case(scene_ctx *c, scene_class cls, char *type)
{
    char *lower = xstrdup(type);
    for (char *s = lower; *s; s++)
        *s = (char)tolower((unsigned char)*s);
    if (c->plugins(cls, lower))
        memcpy(type, lower, strlen(lower));
    free(lower);
}

static int parse_object(scene_ctx *c, const xmlNode *n, scene_class cls, scene_obj *parent)
{
    int line = scene_line(n);
    char *type = NULL, *id = NULL, *name = NULL;
    int rc = -1;
    if (scene_check_attrs(c, n, "type|id|name") != 0 || scene_attr_req(c, n, "type", &type) != 0 ||
        scene_attr(c, n, "id", &id) != 0 || scene_attr(c, n, "name", &name) != 0)
        goto done;
    if (!c->plugins(cls, type))
        fold_plugin_case(c, cls, type);
    if (!c->plugins(cls, type)) {
        const char *why = scene_plugin_refusal(cls, type);
        scene_fail(c, line, "unknown plugin '%s' for <%s>%s%s%s", type, scene_class_name(cls), why ? " (" : "",
                   why ? why : "", why ? ")" : "");
        goto done;
    }
    if (id) {
        const scene_obj *prev = find_id(c->d, id);
        if (prev) {
            scene_fail(c, line, "duplicate id '%s' (first used at %s:%d)", id, prev->file, prev->line);
            goto done;
        }
    }
    scene_obj *o = new_obj(c, cls, type, line);
    if (id && xmlHashAddEntry(c->d->ids, BAD_CAST id, o) != 0)
        abort(); /* out of memory: a duplicate was refused above */
    o->id = id;
    o->name = name;
    id = name = NULL;
    if (parse_children(c, n, o, 0) != 0 || (!declared_only(c, parent, o) && attach(c, parent, o, o->name, line) != 0))
        goto done;
    rc = 0;
done:
    free(type);
    free(id);
    free(name);
    return rc;
}

static int parse_element(scene_ctx *c, const xmlNode *n, scene_obj *o, int file_scene_level)
{
    const char *tag = (const char *)n->name;
    int cls = class_of_tag(tag);
    if (strcmp(tag, "default") == 0) {
        if (!file_scene_level)
            return scene_fail(c, scene_line(n), "<default> must be a direct child of <scene>");
        return parse_default(c, n);
    }
    if (strcmp(tag, "path") == 0) {
        if (!file_scene_level)
            return scene_fail(c, scene_line(n), "<path> must be a direct child of <scene>");
        return parse_path(c, n);
    }
    if (strcmp(tag, "include") == 0)
        return parse_include(c, n, o);
    if (strcmp(tag, "ref") == 0)
        return parse_ref(c, n, o);
    if (cls >= 0)
        return parse_object(c, n, (scene_class)cls, o);
    if (scene_is_property_tag(tag)) {
        scene_prop p;
        if (scene_parse_property(c, n, o->cls, &p) != 0) {
            scene_prop_clear(&p);
            return -1;
        }
        return add_prop(c, o, &p);
    }
    if (strcmp(tag, "scene") == 0)
        return scene_fail(c, scene_line(n), "<scene> can only be the root element");
    return scene_fail(c, scene_line(n), "unknown tag <%s>", tag);
}

static int parse_children(scene_ctx *c, const xmlNode *n, scene_obj *o, int file_scene_level)
{
    for (const xmlNode *ch = n->children; ch; ch = ch->next) {
        if (ch->type == XML_ELEMENT_NODE) {
            if (parse_element(c, ch, o, file_scene_level) != 0)
                return -1;
        } else if (ch->type == XML_TEXT_NODE || ch->type == XML_CDATA_SECTION_NODE) {
            if (!xmlIsBlankNode(ch))
                return scene_fail(c, scene_line(ch), "unexpected text inside <%s>", (const char *)n->name);
        } else if (ch->type != XML_COMMENT_NODE && ch->type != XML_PI_NODE) {
            return scene_fail(c, scene_line(ch), "unexpected content inside <%s>", (const char *)n->name);
        }
    }
    return 0;
}

/* "major.minor.patch"; a scene before Mitsuba 2 is upgraded in place. */
static int check_version(scene_ctx *c, xmlNode *root)
{
    char *v;
    if (scene_check_attrs(c, root, "version") != 0 || scene_attr_req(c, root, "version", &v) != 0)
        return -1;
    int major, minor, patch, end = 0;
    int ok = sscanf(v, "%d.%d.%d%n", &major, &minor, &patch, &end) == 3 && v[end] == '\0';
    int rc = 0;
    if (!ok || major < 0 || minor < 0 || patch < 0)
        rc = scene_fail(c, scene_line(root), "bad scene version '%s' (expected e.g. \"3.0.0\")", v);
    else if (major > 3)
        rc = scene_fail(c, scene_line(root), "scene version '%s' is not supported (Mitsuba 0.5 to 3 scenes)", v);
    else if (major < 2)
        scene_upgrade_v1(root);
    free(v);
    return rc;
}

/* The first entity a document declares (its line; 0: none). */
typedef struct {
    int line;
    char name[64];
} entity_seen;

/* libxml2's SAX hook for <!ENTITY ...>: the parse stops there. Mitsuba
 * scenes need no entities (Mitsuba's own reader expands none), and
 * expanding them is where a small file becomes gigabytes or hours
 * (billion laughs; one 50 KB entity named 20,000 times in an attribute). */
static void stop_at_entity(void *ctx, const xmlChar *name, int type, const xmlChar *public_id,
                           const xmlChar *system_id, xmlChar *content)
{
    (void)type, (void)public_id, (void)system_id, (void)content;
    xmlParserCtxtPtr px = ctx;
    entity_seen *seen = px->_private;
    if (!seen->line) {
        seen->line = xmlSAX2GetLineNumber(ctx);
        snprintf(seen->name, sizeof seen->name, "%s", (const char *)name);
    }
    xmlStopParser(px);
}

static int parse_document(scene_ctx *c, const char *xml, size_t len, const char *path, scene_obj *parent)
{
    c->file = intern_file(c->d, path);
    if (len > INT_MAX)
        return scene_fail(c, 0, "file too large");
    xmlParserCtxtPtr px = xmlNewParserCtxt();
    if (!px)
        abort();
    entity_seen seen = {0};
    px->_private = &seen;
    px->sax->entityDecl = stop_at_entity;
    int opts = XML_PARSE_NONET | XML_PARSE_BIG_LINES | XML_PARSE_NOERROR | XML_PARSE_NOWARNING;
    xmlDocPtr doc = xmlCtxtReadMemory(px, xml, (int)len, path, NULL, opts);
    int rc = 0;
    if (seen.line) {
        rc = scene_fail(c, seen.line, "the document declares an entity ('%s'): scene files may not (Mitsuba "
                        "scenes need none)", seen.name);
        xmlFreeDoc(doc);
    } else if (!doc) {
        const xmlError *e = xmlCtxtGetLastError(px);
        char msg[512];
        snprintf(msg, sizeof msg, "%s", e && e->message ? e->message : "unreadable document");
        msg[strcspn(msg, "\n")] = '\0';
        rc = scene_fail(c, e ? e->line : 0, "malformed XML: %s", msg);
    } else {
        xmlNode *root = xmlDocGetRootElement(doc);
        if (!root)
            rc = scene_fail(c, 0, "empty document");
        else if (strcmp((const char *)root->name, "scene") != 0)
            rc = scene_fail(c, scene_line(root), "the root element must be <scene>, not <%s>",
                            (const char *)root->name);
        else if (check_version(c, root) != 0)
            rc = -1;
        else {
            if (!parent)
                parent = c->d->root = new_obj(c, SCENE_SCENE, "scene", scene_line(root));
            rc = parse_children(c, root, parent, 1);
        }
        xmlFreeDoc(doc);
    }
    xmlFreeParserCtxt(px);
    return rc;
}

/* Resolves references, then validates every object and looks for cycles. */
static int finish(scene_ctx *c)
{
    for (int i = 0; i < c->nrefs; i++) {
        scene_pending_ref *r = &c->refs[i];
        c->file = r->file;
        scene_obj *target = find_id(c->d, r->id);
        if (!target)
            return scene_fail(c, r->line, "<ref id=\"%s\">: no object has this id", r->id);
        if (target->cls == SCENE_SHAPE && strcmp(target->type, "shapegroup") != 0)
            return scene_fail(c, r->line, "<ref id=\"%s\">: only a shapegroup can be referenced (by an instance)",
                              r->id);
        if (attach(c, r->parent, target, r->name, r->line) != 0)
            return -1;
    }
    for (int i = 0; i < c->d->nobjs; i++)
        if (validate_obj(c, c->d->objs[i]) != 0)
            return -1;
    dfs_t g = {xrealloc(NULL, sizeof(scene_obj *) * (size_t)c->d->nobjs),
               calloc((size_t)c->d->nobjs, sizeof(int)), c->d->nobjs};
    if (!g.height)
        abort();
    memcpy(g.sorted, c->d->objs, sizeof(scene_obj *) * (size_t)g.n);
    qsort(g.sorted, (size_t)g.n, sizeof(scene_obj *), cmp_ptr);
    int rc = find_cycle(c, &g, c->d->root, 0) < 0 ? -1 : 0;
    free(g.sorted);
    free(g.height);
    return rc;
}

static scene_desc *load(const char *xml, size_t len, const char *path, const char *const *dirs, int ndirs,
                        const scene_define *defs, int ndefs, scene_plugin_lookup plugins, char *err, size_t errlen)
{
    xmlInitParser();
    scene_ctx c = {0};
    c.plugins = plugins;
    c.d = calloc(1, sizeof *c.d);
    if (!c.d || !(c.d->ids = xmlHashCreate(0)))
        abort();
    c.err = err;
    c.errlen = errlen;
    c.file = intern_file(c.d, path);
    c.extra_dirs = dirs;
    c.nextra = ndirs;
    int rc = 0;
    for (int i = 0; i < ndirs && rc == 0; i++) {
        struct stat st;
        if (stat(dirs[i], &st) != 0 || !S_ISDIR(st.st_mode))
            rc = scene_fail(&c, 0, "-a %s: no such folder", dirs[i]);
    }
    for (int i = 0; i < ndefs && rc == 0; i++) {
        for (int j = 0; j < c.nparams; j++)
            if (strcmp(c.params[j].name, defs[i].name) == 0)
                rc = scene_fail(&c, 0, "-D %s given twice", defs[i].name);
        c.params = xrealloc(c.params, sizeof(scene_param) * (size_t)(c.nparams + 1));
        c.params[c.nparams++] = (scene_param){xstrdup(defs[i].name), xstrdup(defs[i].value), !defs[i].fallback, 0, 0,
                                              defs[i].fallback};
    }
    char canon[PATH_MAX];
    c.stack[c.depth++] = xstrdup(realpath(path, canon) ? canon : path);
    c.scene_dir = folder_of(path);
    if (rc == 0)
        rc = parse_document(&c, xml, len, path, NULL);
    if (rc == 0)
        rc = finish(&c);
    for (int i = 0; i < c.nparams && rc == 0; i++)
        if (c.params[i].from_cli && !c.params[i].used && !c.params[i].declared) {
            c.file = path;
            rc = scene_fail(&c, 0, "-D %s=%s: the scene has no parameter '$%s'", c.params[i].name,
                            c.params[i].value, c.params[i].name);
        }
    for (int i = 0; i < c.nparams; i++) {
        free(c.params[i].name);
        free(c.params[i].value);
    }
    for (int i = 0; i < c.nrefs; i++) {
        free(c.refs[i].id);
        free(c.refs[i].name);
    }
    while (c.depth > 0)
        free(c.stack[--c.depth]);
    for (int i = 0; i < c.npaths; i++)
        free(c.paths[i]);
    free(c.paths);
    free(c.scene_dir);
    free(c.params);
    free(c.refs);
    if (rc != 0) {
        scene_desc_destroy(c.d);
        return NULL;
    }
    return c.d;
}

scene_desc *scene_desc_create_from_text(const char *xml, size_t len, const char *path, const scene_define *defs,
                                        int ndefs, scene_plugin_lookup plugins, char *err, size_t errlen)
{
    return load(xml, len, path, NULL, 0, defs, ndefs, plugins, err, errlen);
}

scene_desc *scene_desc_create_from_file(const char *path, const scene_define *defs, int ndefs,
                                        scene_plugin_lookup plugins, char *err, size_t errlen)
{
    return scene_desc_create_from_file_in(path, NULL, 0, defs, ndefs, plugins, err, errlen);
}

scene_desc *scene_desc_create_from_file_in(const char *path, const char *const *dirs, int ndirs,
                                           const scene_define *defs, int ndefs, scene_plugin_lookup plugins, char *err,
                                           size_t errlen)
{
    char *buf, why[256];
    size_t len;
    if (input_read_all(path, INPUT_MAX_TEXT_BYTES, &buf, &len, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s: %s", path, why);
        return NULL;
    }
    scene_desc *d = load(buf, len, path, dirs, ndirs, defs, ndefs, plugins, err, errlen);
    free(buf);
    return d;
}
