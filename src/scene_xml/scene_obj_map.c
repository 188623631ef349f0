/* Objects built from a scene description, found again by the tree object
 * they came from (scene_xml.h): the arrays keep the order built, a search
 * tree of libc's (tsearch) finds a key in log time. */
#include <search.h>
#include <stdlib.h>

#include "celadon/scene_xml.h"

typedef struct {
    const scene_obj *key;
    void *value;
} map_entry;

static int by_key(const void *a, const void *b)
{
    const scene_obj *x = ((const map_entry *)a)->key, *y = ((const map_entry *)b)->key;
    return x < y ? -1 : x > y;
}

void *scene_obj_map_find(const scene_obj_map *m, const scene_obj *key)
{
    map_entry probe = {key, NULL};
    map_entry *const *e = tfind(&probe, &m->index, by_key);
    return e ? (*e)->value : NULL;
}

int scene_obj_map_add(scene_obj_map *m, const scene_obj *key, void *value)
{
    if (m->count == m->cap) {
        int cap = m->cap ? 2 * m->cap : 16;
        void **v = realloc(m->values, sizeof *v * (size_t)cap);
        if (!v)
            return -1;
        m->values = v;
        const scene_obj **k = realloc(m->keys, sizeof *k * (size_t)cap);
        if (!k)
            return -1;
        m->keys = k;
        m->cap = cap;
    }
    map_entry *e = malloc(sizeof *e);
    if (!e)
        return -1;
    *e = (map_entry){key, value};
    map_entry **slot = tsearch(e, &m->index, by_key);
    if (!slot || *slot != e) { /* out of memory, or the key was there already */
        free(e);
        return -1;
    }
    m->values[m->count] = value;
    m->keys[m->count] = key;
    m->count++;
    return 0;
}

void scene_obj_map_free(scene_obj_map *m)
{
    tdestroy(m->index, free);
    free(m->values);
    free(m->keys);
    *m = (scene_obj_map){0};
}
