/* Objects built from a scene description, found again by the tree object
 * they came from (scene_xml.h). */
#include <stdlib.h>

#include "celadon/scene_xml.h"

void *scene_obj_map_find(const scene_obj_map *m, const scene_obj *key)
{
    for (int i = 0; i < m->count; i++)
        if (m->keys[i] == key)
            return m->values[i];
    return NULL;
}

int scene_obj_map_add(scene_obj_map *m, const scene_obj *key, void *value)
{
    void **v = realloc(m->values, sizeof *v * (size_t)(m->count + 1));
    if (!v)
        return -1;
    m->values = v;
    const scene_obj **k = realloc(m->keys, sizeof *k * (size_t)(m->count + 1));
    if (!k)
        return -1;
    m->keys = k;
    v[m->count] = value;
    k[m->count] = key;
    m->count++;
    return 0;
}

void scene_obj_map_free(scene_obj_map *m)
{
    free(m->values);
    free(m->keys);
    *m = (scene_obj_map){0};
}
