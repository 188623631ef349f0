/* Scenes of older Mitsubas, and Mitsuba's plugins that celadon refuses by
 * name (docs/scene-format.md, "Older scenes" and "Refused plugins").
 *
 * A document with version below 2.0 (Mitsuba 0.5, 0.6) is upgraded on
 * reading as Mitsuba 3 upgrades it: camelCase names become snake_case
 * (toWorld -> to_world, intIOR -> int_ior), <lookAt> becomes <lookat>,
 * diffuse's diffuse_reflectance becomes reflectance, and a texture's
 * uoffset/voffset/uscale/vscale become its to_uv transform. celadon adds what
 * the published 0.6 scenes need beyond that: `ldrfilm` is read as `hdrfilm`
 * without its tone mapping (celadon encodes the output by its extension, as
 * Mitsuba 3 does), and bitmap filters ewa and trilinear are read as
 * bilinear, Mitsuba 3's only smooth filter. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_xml/scene_xml_internal.h"

/* ------------------------------------------------------------ the upgrade */
static int is(const xmlNode *n, const char *tag)
{
    return n->type == XML_ELEMENT_NODE && strcmp((const char *)n->name, tag) == 0;
}

static int attr_is(const xmlNode *n, const char *attr, const char *value)
{
    xmlChar *v = xmlGetProp(n, (const xmlChar *)attr);
    int r = v && strcmp((const char *)v, value) == 0;
    xmlFree(v);
    return r;
}

void scene_snake_case(const char *in, char *out, size_t outlen)
{
    size_t k = 0;
    for (size_t i = 0; in[i] && k + 3 < outlen; i++) {
        if (i > 0 && islower((unsigned char)in[i - 1]) && isupper((unsigned char)in[i])) {
            out[k++] = '_'; /* a lower-case letter, then a run of upper-case ones */
            while (isupper((unsigned char)in[i]) && k + 2 < outlen)
                out[k++] = (char)tolower((unsigned char)in[i++]);
            i--;
        } else {
            out[k++] = in[i];
        }
    }
    out[k] = '\0';
}

/* Every name="..." but <default>'s in snake_case, <lookAt> as <lookat>. */
static void upgrade_names(xmlNode *n)
{
    for (; n; n = n->next) {
        if (n->type != XML_ELEMENT_NODE)
            continue;
        if (is(n, "lookAt"))
            xmlNodeSetName(n, (const xmlChar *)"lookat");
        xmlChar *name = xmlGetProp(n, (const xmlChar *)"name");
        if (name && !is(n, "default")) {
            char snake[256];
            scene_snake_case((const char *)name, snake, sizeof snake);
            xmlSetProp(n, (const xmlChar *)"name", (const xmlChar *)snake);
        }
        xmlFree(name);
        upgrade_names(n->children);
    }
}

static xmlNode *child_named(xmlNode *n, const char *tag, const char *name)
{
    for (xmlNode *ch = n->children; ch; ch = ch->next)
        if (is(ch, tag) && attr_is(ch, "name", name))
            return ch;
    return NULL;
}

static void remove_node(xmlNode *n)
{
    xmlUnlinkNode(n);
    xmlFreeNode(n);
}

/* uoffset/voffset/uscale/vscale of n as its to_uv: scale(uscale, vscale) ·
 * translate(uoffset, voffset). */
static void upgrade_uv(xmlNode *n)
{
    static const char *names[4] = {"uoffset", "voffset", "uscale", "vscale"};
    xmlChar *v[4] = {NULL, NULL, NULL, NULL};
    int any = 0;
    for (int i = 0; i < 4; i++) {
        xmlNode *f = child_named(n, "float", names[i]);
        if (f) {
            v[i] = xmlGetProp(f, (const xmlChar *)"value");
            remove_node(f);
            any = 1;
        }
    }
    if (any) {
        xmlNode *xf = xmlNewChild(n, NULL, (const xmlChar *)"transform", NULL);
        xmlSetProp(xf, (const xmlChar *)"name", (const xmlChar *)"to_uv");
        xmlNode *t = xmlNewChild(xf, NULL, (const xmlChar *)"translate", NULL);
        xmlSetProp(t, (const xmlChar *)"x", v[0] ? v[0] : (const xmlChar *)"0");
        xmlSetProp(t, (const xmlChar *)"y", v[1] ? v[1] : (const xmlChar *)"0");
        xmlNode *s = xmlNewChild(xf, NULL, (const xmlChar *)"scale", NULL);
        xmlSetProp(s, (const xmlChar *)"x", v[2] ? v[2] : (const xmlChar *)"1");
        xmlSetProp(s, (const xmlChar *)"y", v[3] ? v[3] : (const xmlChar *)"1");
    }
    for (int i = 0; i < 4; i++)
        xmlFree(v[i]);
}

/* The parameters of 0.6's ldrfilm that hdrfilm does not have: its tone
 * mapping and its file format (celadon encodes by the output's extension). */
static const char *const ldrfilm_only[] = {"gamma", "exposure", "tonemap_method", "key", "burn",
                                           "file_format", "pixel_format", "component_format", NULL};

static void upgrade_objects(xmlNode *n)
{
    for (; n; n = n->next) {
        if (n->type != XML_ELEMENT_NODE)
            continue;
        if (is(n, "bsdf") && attr_is(n, "type", "diffuse")) {
            for (xmlNode *ch = n->children; ch; ch = ch->next)
                if (ch->type == XML_ELEMENT_NODE && attr_is(ch, "name", "diffuse_reflectance"))
                    xmlSetProp(ch, (const xmlChar *)"name", (const xmlChar *)"reflectance");
        }
        if (is(n, "film") && attr_is(n, "type", "ldrfilm")) {
            xmlSetProp(n, (const xmlChar *)"type", (const xmlChar *)"hdrfilm");
            for (xmlNode *ch = n->children, *next; ch; ch = next) {
                next = ch->next;
                xmlChar *name = ch->type == XML_ELEMENT_NODE ? xmlGetProp(ch, (const xmlChar *)"name") : NULL;
                for (int i = 0; name && ldrfilm_only[i]; i++)
                    if (strcmp((const char *)name, ldrfilm_only[i]) == 0) {
                        remove_node(ch);
                        break;
                    }
                xmlFree(name);
            }
        }
        if (is(n, "texture") && attr_is(n, "type", "bitmap")) {
            xmlNode *f = child_named(n, "string", "filter_type");
            if (f && (attr_is(f, "value", "ewa") || attr_is(f, "value", "trilinear")))
                xmlSetProp(f, (const xmlChar *)"value", (const xmlChar *)"bilinear");
        }
        upgrade_uv(n);
        upgrade_objects(n->children);
    }
}

void scene_upgrade_v1(xmlNode *root)
{
    upgrade_names(root->children);
    upgrade_objects(root->children);
}

/* ------------------------------------------------- parameters and plugins */
typedef struct {
    scene_class cls;
    const char *name;
} class_name;

/* Parameters Mitsuba 3 ignores and that change nothing in the image: read
 * and dropped (Mitsuba 3 warns about them). */
static const class_name obsolete_params[] = {
    {SCENE_FILM, "banner"},          {SCENE_FILM, "attach_log"},     {SCENE_FILM, "high_quality_edges"},
    {SCENE_INTEGRATOR, "strict_normals"}, {SCENE_SENSOR, "shutter_open"}, {SCENE_SENSOR, "shutter_close"},
    {SCENE_TEXTURE, "cache"},        {SCENE_TEXTURE, "max_anisotropy"}, {SCENE_EMITTER, "cache"},
};

int scene_param_obsolete(scene_class cls, const char *name)
{
    for (size_t i = 0; i < sizeof obsolete_params / sizeof obsolete_params[0]; i++)
        if (obsolete_params[i].cls == cls && strcmp(obsolete_params[i].name, name) == 0)
            return 1;
    return 0;
}

typedef struct {
    scene_class cls;
    const char *names; /* '|'-separated */
    const char *why;
} refused_plugins;

static const refused_plugins refused[] = {
    {SCENE_BSDF, "pplastic|polarizer|retarder|measured_polarized", "polarized; celadon renders unpolarized RGB"},
    {SCENE_INTEGRATOR, "stokes", "polarized; celadon renders unpolarized RGB"},
    {SCENE_BSDF, "measured", "spectral measurements; celadon renders RGB"},
    {SCENE_INTEGRATOR,
     "photonmapper|ppm|sppm|bdpt|pssmlt|mlt|erpt|vpl|ao|irrcache|field|multichannel|adaptive|volpath_simple",
     "Mitsuba 0.6's; Mitsuba 3 dropped it"},
    {SCENE_BSDF, "phong|ward|coating|roughcoating|mixturebsdf|difftrans|hk|irawan",
     "Mitsuba 0.6's; Mitsuba 3 dropped it"},
    {SCENE_SAMPLER, "halton|hammersley", "Mitsuba 0.6's; Mitsuba 3 dropped it"},
    {SCENE_SENSOR, "telecentric|spherical|fluencemeter|perspective_rdist", "Mitsuba 0.6's; Mitsuba 3 dropped it"},
    {SCENE_EMITTER, "sun|sky|collimated", "Mitsuba 0.6's; Mitsuba 3 dropped it"},
    {SCENE_SHAPE, "hair|heightfield", "Mitsuba 0.6's; Mitsuba 3 dropped it"},
    {SCENE_FILM, "tiledhdrfilm|mfilm", "Mitsuba 0.6's; Mitsuba 3 dropped it"},
    {SCENE_TEXTURE, "gridtexture|scale|vertexcolors|wireframe|curvature", "Mitsuba 0.6's; Mitsuba 3 dropped it"},
};

const char *scene_plugin_refusal(scene_class cls, const char *type)
{
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++)
        if (refused[i].cls == cls && schema_choice_ok(refused[i].names, type))
            return refused[i].why;
    return NULL;
}
