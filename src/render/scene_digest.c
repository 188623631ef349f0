/* The scene's digest (scene.h, scene_digest): XXH3-64 of the description
 * tree as read (defaults and -D applied, file names resolved), the contents
 * of every file a parameter names (meshes, profiles, textures, maps), and
 * what the build made of the options that change the image (film size, spp,
 * the sampler plugin, SOR geometry). Parts of a render compare it to tell whether they rendered
 * the same scene (parts.h). */
#include <stdio.h>
#include <string.h>
#include <xxhash.h>

#include "render/scene_impl.h"

static void add(XXH3_state_t *h, const void *p, size_t n) { XXH3_64bits_update(h, p, n); }
static void add_str(XXH3_state_t *h, const char *s) { add(h, s ? s : "", s ? strlen(s) + 1 : 1); }
static void add_int(XXH3_state_t *h, long long v) { add(h, &v, sizeof v); }

/* A file's bytes; a file that cannot be read adds its name only (the scene
 * build, which reads every one, then fails anyway). */
static void add_file(XXH3_state_t *h, const char *path)
{
    FILE *f = fopen(path, "rb");
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

static void add_object(XXH3_state_t *h, const scene_obj *o)
{
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
        case SCENE_OBJECT: add_object(h, p->value.obj); break;
        }
    }
    add_int(h, o->nchildren);
    for (int i = 0; i < o->nchildren; i++)
        add_object(h, o->children[i]);
}

uint64_t scene_digest_compute(const scene_desc *desc, const struct scene *s, int mesh_segments)
{
    XXH3_state_t *h = XXH3_createState();
    if (!h)
        return 0;
    XXH3_64bits_reset(h);
    add_object(h, scene_desc_root(desc));
    const long long o[4] = {s->camera.width, s->camera.height, s->sampler.sample_count, mesh_segments};
    add(h, o, sizeof o);
    add_str(h, s->sampler.plugin);
    uint64_t d = XXH3_64bits_digest(h);
    XXH3_freeState(h);
    return d;
}
