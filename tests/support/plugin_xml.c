#include "plugin_xml.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/scene.h"

void plugin_xml_open(plugin_xml *f)
{
    memset(f, 0, sizeof *f);
    f->bsdfs.textures = &f->textures;
}

void plugin_xml_close(plugin_xml *f)
{
    emitter_list_free(&f->emitters);
    bsdf_set_free(&f->bsdfs);
    texture_set_free(&f->textures);
    for (int i = 0; i < f->ndocs; i++)
        scene_desc_destroy(f->docs[i]);
    f->ndocs = 0;
}

int plugin_xml_objects(plugin_xml *f, const char *xml, scene_class cls, scene_obj **out, int max, char *err,
                       size_t errlen)
{
    if (f->ndocs == PLUGIN_XML_MAX_DOCS) {
        snprintf(err, errlen, "plugin_xml: too many snippets");
        return -1;
    }
    size_t len = strlen(xml) + 64;
    char *doc = malloc(len);
    if (!doc) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    snprintf(doc, len, "<scene version=\"3.0.0\">%s</scene>", xml);
    scene_desc *d =
        scene_desc_create_from_text(doc, strlen(doc), "snippet.xml", NULL, 0, scene_plugin_find, err, errlen);
    free(doc);
    if (!d)
        return -1;
    f->docs[f->ndocs++] = d;
    return scene_obj_children(scene_desc_root(d), cls, out, max);
}

/* The first top-level object of class cls of the snippet, or NULL with err. */
static scene_obj *first_object(plugin_xml *f, const char *xml, scene_class cls, char *err, size_t errlen)
{
    scene_obj *o;
    int n = plugin_xml_objects(f, xml, cls, &o, 1, err, errlen);
    if (n == 0)
        snprintf(err, errlen, "plugin_xml: no <%s> in the snippet", scene_class_name(cls));
    return n > 0 ? o : NULL;
}

const bsdf_t *plugin_xml_bsdf(plugin_xml *f, const char *xml, char *err, size_t errlen)
{
    scene_obj *o = first_object(f, xml, SCENE_BSDF, err, errlen);
    return o ? bsdf_set_get(&f->bsdfs, o, err, errlen) : NULL;
}

const texture_t *plugin_xml_texture(plugin_xml *f, const char *xml, char *err, size_t errlen)
{
    scene_obj *o = first_object(f, xml, SCENE_TEXTURE, err, errlen);
    return o ? texture_set_get(&f->textures, o, err, errlen) : NULL;
}

const emitter_t *plugin_xml_emitter(plugin_xml *f, const char *xml, char *err, size_t errlen)
{
    scene_obj *o = first_object(f, xml, SCENE_EMITTER, err, errlen);
    emitter_t *e = o ? emitter_plugin_find(o->type)->create(o, NULL, &f->textures, err, errlen) : NULL;
    if (e && emitter_list_add(&f->emitters, e) != 0) {
        emitter_destroy(e);
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    return e;
}
