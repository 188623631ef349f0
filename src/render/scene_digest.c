/* The scene's digest (scene.h, scene_digest): XXH3-64 of the description
 * tree as read (defaults and -D applied, file names resolved), the contents
 * of every file a parameter names (meshes, profiles, textures, maps), and
 * what the build made of the options that change the image (film size, spp,
 * the sampler plugin, SOR geometry). Parts of a render compare it to tell
 * whether they rendered the same scene (parts.h). */
#include <search.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <xxhash.h>

#include "core/core.h"
#include "render/scene_impl.h"

static void add(XXH3_state_t *h, const void *p, size_t n) { XXH3_64bits_update(h, p, n); }
static void add_str(XXH3_state_t *h, const char *s) { add(h, s ? s : "", s ? strlen(s) + 1 : 1); }
static void add_int(XXH3_state_t *h, long long v) { add(h, &v, sizeof v); }

/* A file's bytes; a file that cannot be read adds its name only (the scene
 * build, which reads every one, then fails anyway). */
static void add_file(XXH3_state_t *h, const char *path)
{
    char why[256];
    FILE *f = input_open(path, INPUT_MAX_DATA_BYTES, NULL, why, sizeof why);
    if (!f)
        return;
    unsigned char buf[1 << 16];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0)
        add(h, buf, n);
    fclose(f);
}

static int names_file(const scene_obj *o, const char *param)
{
    const scene_plugin_decl *d = scene_plugin_find(o->cls, o->type);
    for (const scene_param_decl *p = d ? d->params : NULL; p && p->name; p++)
        if (!strcmp(p->name, param))
            return (p->flags & PARAM_FILE) != 0;
    return 0;
}

/* The digest being made, and the objects in it so far: a shared object
 * (one <ref id> named by many) goes in once, then by its ordinal, so a chain
 * of objects each naming the one before twice costs linear time, not 2^n. */
typedef struct {
    XXH3_state_t *h;
    void *seen; /* seen_object by address (tsearch) */
    long long n_seen;
    int out_of_memory;
} digest;

typedef struct {
    const scene_obj *o;
    long long ordinal;
} seen_object;

static int by_object(const void *a, const void *b)
{
    const scene_obj *x = ((const seen_object *)a)->o, *y = ((const seen_object *)b)->o;
    return x < y ? -1 : x > y;
}

/* 1 when o is in the digest already (its ordinal is added instead). */
static int seen_before(digest *d, const scene_obj *o)
{
    seen_object *e = malloc(sizeof *e);
    if (e)
        *e = (seen_object){o, d->n_seen};
    seen_object **slot = e ? tsearch(e, &d->seen, by_object) : NULL;
    if (!slot) {
        free(e);
        d->out_of_memory = 1;
        return 1;
    }
    if (*slot != e) {
        free(e);
        add_int(d->h, -1 - (*slot)->ordinal);
        return 1;
    }
    d->n_seen++;
    return 0;
}

static void add_object(digest *d, const scene_obj *o)
{
    if (seen_before(d, o))
        return;
    XXH3_state_t *h = d->h;
    add_int(h, o->cls);
    add_str(h, o->type);
    add_str(h, o->id);
    add_str(h, o->name);
    add_int(h, o->nprops);
    for (int i = 0; i < o->nprops; i++) {
        const scene_prop *p = &o->props[i];
        add_str(h, p->name);
        add_int(h, p->type);
        switch (p->type) {
        case SCENE_FLOAT: add(h, &p->value.f, sizeof p->value.f); break;
        case SCENE_INTEGER: add_int(h, p->value.i); break;
        case SCENE_BOOLEAN: add_int(h, p->value.b); break;
        case SCENE_STRING:
            add_str(h, p->value.s);
            if (names_file(o, p->name))
                add_file(h, p->value.s);
            break;
        case SCENE_RGB:
        case SCENE_SPECTRUM: add(h, &p->value.rgb, sizeof p->value.rgb); break;
        case SCENE_POINT:
        case SCENE_VECTOR: add(h, &p->value.v, sizeof p->value.v); break;
        case SCENE_TRANSFORM: add(h, &p->value.xf, sizeof p->value.xf); break;
        case SCENE_OBJECT: add_object(d, p->value.obj); break;
        }
    }
    add_int(h, o->nchildren);
    for (int i = 0; i < o->nchildren; i++)
        add_object(d, o->children[i]);
}

uint64_t scene_digest_compute(const scene_desc *desc, const struct scene *s, int mesh_segments)
{
    XXH3_state_t *h = XXH3_createState();
    if (!h)
        return 0;
    XXH3_64bits_reset(h);
    digest d = {h, NULL, 0, 0};
    add_object(&d, scene_desc_root(desc));
    tdestroy(d.seen, free);
    const long long o[4] = {s->camera.width, s->camera.height, s->sampler.sample_count, mesh_segments};
    add(h, o, sizeof o);
    add_str(h, s->sampler.plugin);
    uint64_t digest_value = d.out_of_memory ? 0 : XXH3_64bits_digest(h);
    XXH3_freeState(h);
    return digest_value;
}
