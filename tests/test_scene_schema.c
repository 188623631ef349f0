/* Table-driven: every parameter of every supported plugin, in every type the
 * table allows, is written into a scene, parsed back and compared; and every
 * parameter given a type the table does not allow is refused at its line. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/scene.h"
#include "scene_xml/scene_xml_internal.h"

/* The XML for one property of type t named name, and the value it carries. */
static void property_xml(scene_prop_type t, const char *name, const scene_param_decl *par, char *buf, size_t len)
{
    switch (t) {
    case SCENE_FLOAT: snprintf(buf, len, "<float name=\"%s\" value=\"0.375\"/>", name); break;
    case SCENE_INTEGER: snprintf(buf, len, "<integer name=\"%s\" value=\"17\"/>", name); break;
    case SCENE_BOOLEAN: snprintf(buf, len, "<boolean name=\"%s\" value=\"true\"/>", name); break;
    case SCENE_STRING: {
        char word[64] = "a word";
        if (par && par->choices) /* the last allowed choice */
            snprintf(word, sizeof word, "%s", strrchr(par->choices, '|') ? strrchr(par->choices, '|') + 1 : par->choices);
        else if (par && (par->flags & PARAM_FILE))
            snprintf(word, sizeof word, "exists.dat");
        snprintf(buf, len, "<string name=\"%s\" value=\"%s\"/>", name, word);
        break;
    }
    case SCENE_RGB: snprintf(buf, len, "<rgb name=\"%s\" value=\"0.1, 0.2, 0.3\"/>", name); break;
    case SCENE_SPECTRUM: snprintf(buf, len, "<spectrum name=\"%s\" value=\"0.625\"/>", name); break;
    case SCENE_POINT: snprintf(buf, len, "<point name=\"%s\" value=\"1 2 3\"/>", name); break;
    case SCENE_VECTOR: snprintf(buf, len, "<vector name=\"%s\" x=\"4\" y=\"5\" z=\"6\"/>", name); break;
    case SCENE_TRANSFORM:
        snprintf(buf, len, "<transform name=\"%s\"><translate value=\"1 2 3\"/></transform>", name);
        break;
    case SCENE_OBJECT: snprintf(buf, len, "<texture type=\"checkerboard\" name=\"%s\"/>", name); break;
    }
}

static void check_value(scene_prop *p, scene_prop_type t, const scene_param_decl *par, scene_class cls)
{
    cr_assert_eq(p->type, t, "%s: type %d, want %d", par->name, p->type, t);
    switch (t) {
    case SCENE_FLOAT: cr_assert_eq(p->value.f, 0.375); break;
    case SCENE_INTEGER: cr_assert_eq(p->value.i, 17); break;
    case SCENE_BOOLEAN: cr_assert(p->value.b); break;
    case SCENE_STRING:
        if (par->flags & PARAM_FILE)
            cr_assert_not_null(strstr(p->value.s, "/exists.dat"), "%s", p->value.s);
        else if (par->choices)
            cr_assert(schema_choice_ok(par->choices, p->value.s), "%s", p->value.s);
        else
            cr_assert_str_eq(p->value.s, "a word");
        break;
    case SCENE_RGB: cr_assert(p->value.rgb.r == 0.1 && p->value.rgb.g == 0.2 && p->value.rgb.b == 0.3); break;
    case SCENE_SPECTRUM: /* flat emission is the sRGB of X = Y = Z, slightly purple (docs/scene-format.md) */
        if (cls == SCENE_EMITTER)
            cr_assert_float_eq(p->value.rgb.r, 0.625 * (3.240479 - 1.537150 - 0.498535), 1e-12);
        else
            cr_assert(p->value.rgb.r == 0.625 && p->value.rgb.b == 0.625);
        break;
    case SCENE_POINT: cr_assert(p->value.v.x == 1 && p->value.v.y == 2 && p->value.v.z == 3); break;
    case SCENE_VECTOR: cr_assert(p->value.v.x == 4 && p->value.v.y == 5 && p->value.v.z == 6); break;
    case SCENE_TRANSFORM: {
        vec3 o = transform_point(&p->value.xf, v3(0, 0, 0));
        cr_assert(o.x == 1 && o.y == 2 && o.z == 3);
        break;
    }
    case SCENE_OBJECT: cr_assert_str_eq(p->value.obj->type, "checkerboard"); break;
    }
}

/* Wraps the plugin's element in the context it needs; the property sits
 * alone on line 3 of the document. Returns the object found after parsing
 * via *depth (how many first-children to descend from the root). */
static void document(const scene_plugin_decl *pl, const char *prop, char *buf, size_t len, int *depth)
{
    char extra[256] = "";
    for (const scene_param_decl *q = pl->params; q && q->name; q++) {
        char given[80]; /* the property under test is this required one */
        snprintf(given, sizeof given, "name=\"%s\"", q->name);
        if ((q->flags & PARAM_REQUIRED) && !strstr(prop, given)) {
            char more[128];
            property_xml(q->types & PARAM_STRING ? SCENE_STRING : SCENE_FLOAT, q->name, q, more, sizeof more);
            strncat(extra, more, sizeof extra - strlen(extra) - 1);
        }
    }
    /* The nested objects the plugin needs: that many of a plain plugin of each class. */
    for (const scene_child_decl *c = pl->children; c && c->max > 0; c++)
        for (int k = 0; k < c->min; k++) {
            const char *child = c->cls == SCENE_INTEGRATOR ? "<integrator type=\"path\"/>"
                                : c->cls == SCENE_TEXTURE  ? "<texture type=\"checkerboard\"/>"
                                : c->cls == SCENE_BSDF     ? "<bsdf type=\"diffuse\"/>"
                                : c->only_type && !strcmp(c->only_type, "shapegroup")
                                    ? "<shape type=\"shapegroup\"><shape type=\"sphere\"/></shape>"
                                    : "<shape type=\"sphere\"/>";
            strncat(extra, child, sizeof extra - strlen(extra) - 1);
        }
    const char *cls = scene_class_name(pl->cls);
    const char *open = "", *close = "";
    *depth = 1;
    switch (pl->cls) {
    case SCENE_FILM: case SCENE_SAMPLER:
        open = "<sensor type=\"perspective\">"; close = "</sensor>"; *depth = 2; break;
    case SCENE_RFILTER:
        open = "<sensor type=\"perspective\"><film type=\"hdrfilm\">"; close = "</film></sensor>"; *depth = 3; break;
    case SCENE_TEXTURE:
        open = "<bsdf type=\"diffuse\">"; close = "</bsdf>"; *depth = 2; break;
    case SCENE_MEDIUM: /* a shape's interior */
        open = "<shape type=\"sphere\">"; close = "</shape>"; *depth = 2; break;
    case SCENE_PHASE:
        open = "<shape type=\"sphere\"><medium type=\"homogeneous\" name=\"interior\">";
        close = "</medium></shape>"; *depth = 3; break;
    case SCENE_VOLUME:
        open = "<shape type=\"sphere\"><medium type=\"heterogeneous\" name=\"interior\">";
        close = "</medium></shape>"; *depth = 3; break;
    case SCENE_EMITTER:
        if (strcmp(pl->type, "area") == 0) {
            open = "<shape type=\"sphere\">"; close = "</shape>"; *depth = 2;
        }
        break;
    default: break;
    }
    snprintf(buf, len,
             "<scene version=\"3.0.0\">\n%s<%s type=\"%s\"%s>%s\n%s\n</%s>%s\n</scene>\n", open, cls, pl->type,
             pl->cls == SCENE_TEXTURE  ? " name=\"reflectance\""
             : pl->cls == SCENE_MEDIUM ? " name=\"interior\""
             : pl->cls == SCENE_VOLUME ? " name=\"sigma_t\""
                                       : "",
             extra, prop, cls, close);
}

static scene_obj *descend(scene_desc *d, int depth)
{
    scene_obj *o = scene_desc_root(d);
    for (int i = 0; i < depth; i++) {
        if (o->nchildren > 0)
            o = o->children[0];
        else /* a texture is a property of its bsdf */
            o = o->props[0].value.obj;
    }
    return o;
}

Test(scene_schema, every_parameter_round_trips_and_wrong_types_fail)
{
    char dir[] = "/tmp/celadon-schema-XXXXXX", path[128], err[1024];
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/exists.dat", dir);
    FILE *f = fopen(path, "w");
    fclose(f);
    snprintf(path, sizeof path, "%s/s.xml", dir);
    int checked = 0, refused = 0;
    for (int i = 0; scene_plugin_at(i); i++) {
        const scene_plugin_decl *pl = scene_plugin_at(i);
        if (pl->cls == SCENE_SCENE)
            continue;
        for (const scene_param_decl *q = pl->params; q && q->name; q++)
            for (int t = SCENE_FLOAT; t <= SCENE_OBJECT; t++) {
                char prop[256], xml[2048];
                int depth;
                property_xml((scene_prop_type)t, q->name, q, prop, sizeof prop);
                document(pl, prop, xml, sizeof xml, &depth);
                scene_desc *d =
                    scene_desc_create_from_text(xml, strlen(xml), path, NULL, 0, scene_plugin_find, err, sizeof err);
                if (q->types & (1u << t)) {
                    cr_assert_not_null(d, "%s %s as %s: %s\n%s", pl->type, q->name, schema_type_tag(t), err, xml);
                    scene_obj *o = descend(d, depth);
                    cr_assert_str_eq(o->type, pl->type);
                    check_value(scene_obj_prop(o, q->name), (scene_prop_type)t, q, pl->cls);
                    checked++;
                } else {
                    cr_assert_null(d, "%s %s as %s accepted", pl->type, q->name, schema_type_tag(t));
                    char want[200];
                    snprintf(want, sizeof want, "%s:3: ", path);
                    cr_assert(strncmp(err, want, strlen(want)) == 0, "%s", err);
                    cr_assert(strstr(err, "must be") || strstr(err, "inside"), "%s", err);
                    refused++;
                }
                scene_desc_destroy(d);
            }
    }
    cr_assert_gt(checked, 90, "checked %d", checked);
    cr_assert_gt(refused, 500, "refused %d", refused);
    remove(path);
    snprintf(path, sizeof path, "%s/exists.dat", dir);
    remove(path);
    remove(dir);
}

/* The row of docs/scene-format.md's plugin tables whose first cell names
 * plugin `type`, or NULL. */
static const char *doc_row(const char *doc, const char *type)
{
    char name[80];
    snprintf(name, sizeof name, "`%s`", type);
    for (const char *line = doc; line && *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
        const char *end = strchr(line, '\n'), *cell_end = line[0] == '|' ? strchr(line + 1, '|') : NULL;
        if (!cell_end || (end && cell_end > end))
            continue;
        const char *hit = strstr(line, name);
        if (hit && hit < cell_end)
            return line;
    }
    return NULL;
}

/* The documentation lists what the registration tables declare: every
 * plugin has a row in docs/scene-format.md, and its row names every
 * parameter. */
Test(scene_schema, docs_list_every_plugin_and_parameter)
{
    FILE *f = fopen("docs/scene-format.md", "r");
    cr_assert_not_null(f, "run from the repository's top folder");
    static char doc[1 << 18];
    size_t n = fread(doc, 1, sizeof doc - 1, f);
    fclose(f);
    doc[n] = '\0';
    int plugins = 0;
    for (int i = 0; scene_plugin_at(i); i++) {
        const scene_plugin_decl *pl = scene_plugin_at(i);
        if (pl->cls == SCENE_SCENE)
            continue;
        const char *row = doc_row(doc, pl->type);
        cr_assert_not_null(row, "docs/scene-format.md has no row for <%s type=\"%s\">", scene_class_name(pl->cls),
                           pl->type);
        size_t len = strcspn(row, "\n");
        for (const scene_param_decl *q = pl->params; q && q->name; q++) {
            char name[80];
            snprintf(name, sizeof name, "`%s`", q->name);
            const char *hit = strstr(row, name);
            cr_assert(hit && (size_t)(hit - row) < len, "docs/scene-format.md: the row of %s does not name `%s`",
                      pl->type, q->name);
        }
        plugins++;
    }
    cr_assert_geq(plugins, 31, "%d plugins", plugins);
}
