/* Reading plugin declarations (scene_plugin_decl): finding a plugin in a
 * table, a parameter or a child rule in a plugin, and the words the
 * reader's messages use for them. */
#include <stdio.h>
#include <string.h>

#include "scene_xml/scene_xml_internal.h"

const scene_plugin_decl *scene_plugin_table_find(const scene_plugin_decl *const *table, const char *type)
{
    for (int i = 0; table[i]; i++)
        if (strcmp(table[i]->type, type) == 0)
            return table[i];
    return NULL;
}

const scene_param_decl *schema_param_find(const scene_plugin_decl *p, const char *name)
{
    for (const scene_param_decl *q = p->params; q && q->name; q++)
        if (strcmp(q->name, name) == 0)
            return q;
    return NULL;
}

const scene_child_decl *schema_child_find(const scene_plugin_decl *p, scene_class cls)
{
    for (const scene_child_decl *c = p->children; c && c->max > 0; c++)
        if (c->cls == cls)
            return c;
    return NULL;
}

int schema_choice_ok(const char *choices, const char *word)
{
    size_t n = strlen(word);
    for (const char *s = choices; *s;) {
        const char *bar = strchr(s, '|');
        size_t len = bar ? (size_t)(bar - s) : strlen(s);
        if (len == n && strncmp(s, word, n) == 0)
            return 1;
        if (!bar)
            break;
        s = bar + 1;
    }
    return 0;
}

const char *schema_type_tag(scene_prop_type t)
{
    static const char *tags[] = {"float", "integer", "boolean", "string", "rgb",
                                 "spectrum", "point", "vector", "transform", "texture"};
    return tags[t];
}

void schema_types_text(unsigned types, char *buf, size_t len)
{
    int k = 0, total = 0;
    for (int t = SCENE_FLOAT; t <= SCENE_OBJECT; t++)
        total += (types >> t) & 1u;
    buf[0] = '\0';
    for (int t = SCENE_FLOAT; t <= SCENE_OBJECT; t++) {
        if (!((types >> t) & 1u))
            continue;
        size_t used = strlen(buf);
        const char *sep = k == 0 ? "" : (k == total - 1 ? " or " : ", ");
        snprintf(buf + used, len - used, "%s<%s>", sep, schema_type_tag((scene_prop_type)t));
        k++;
    }
}
