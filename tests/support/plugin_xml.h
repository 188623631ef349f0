/* Plugins built from XML snippets the way a scene builds them: the snippet
 * is parsed as the body of a <scene> and its objects built through their
 * kind's set, so a test reaches a plugin by its Mitsuba name and parameters
 * only (docs/plugins.md). */
#ifndef CELADON_TEST_PLUGIN_XML_H
#define CELADON_TEST_PLUGIN_XML_H

#include <stddef.h>

#include "bsdfs/bsdfs.h"
#include "emitters/emitters.h"
#include "textures/textures.h"

enum { PLUGIN_XML_MAX_DOCS = 64 };

typedef struct {
    scene_desc *docs[PLUGIN_XML_MAX_DOCS]; /* kept while what was built from them lives */
    int ndocs;
    texture_set textures;
    bsdf_set bsdfs;
    emitter_list emitters;
} plugin_xml;

void plugin_xml_open(plugin_xml *f);
/* Destroys everything built, then the documents. */
void plugin_xml_close(plugin_xml *f);

/* The objects of class cls at the top level of the snippet, in document
 * order: up to max of them into out; returns how many there are, or -1
 * with the reader's message in err when the snippet does not load. */
int plugin_xml_objects(plugin_xml *f, const char *xml, scene_class cls, scene_obj **out, int max, char *err,
                       size_t errlen);

/* The BSDF or texture of the snippet's first top-level <bsdf> or <texture>,
 * or NULL with a message in err (a load or a build error). */
const bsdf_t *plugin_xml_bsdf(plugin_xml *f, const char *xml, char *err, size_t errlen);
const texture_t *plugin_xml_texture(plugin_xml *f, const char *xml, char *err, size_t errlen);
/* The same for a top-level <emitter> (not one nested in a shape). */
const emitter_t *plugin_xml_emitter(plugin_xml *f, const char *xml, char *err, size_t errlen);

#endif
