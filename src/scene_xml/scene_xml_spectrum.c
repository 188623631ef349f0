/* The <spectrum> element, read into an RGB as Mitsuba 3's RGB variants read
 * it (spectrum.h; docs/scene-format.md, "Spectra"): a constant, a list of
 * wavelength:value pairs, a spectrum file, or a spectrum plugin (blackbody,
 * uniform, regular, irregular) with its own parameters. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_xml/scene_xml_internal.h"
#include "scene_xml/spectrum.h"

enum { SPECTRUM_PLUGIN_MAX_PARAMS = 8 };

typedef struct {
    double *wl, *v;
    int n, cap;
} sample_list;

static void list_push(sample_list *s, double wl, double v)
{
    if (s->n == s->cap) {
        s->cap = s->cap ? 2 * s->cap : 64;
        s->wl = realloc(s->wl, sizeof(double) * (size_t)s->cap);
        s->v = realloc(s->v, sizeof(double) * (size_t)s->cap);
        if (!s->wl || !s->v)
            abort();
    }
    s->wl[s->n] = wl;
    s->v[s->n++] = v;
}

static void list_free(sample_list *s)
{
    free(s->wl);
    free(s->v);
}

/* At least two samples, wavelengths increasing and positive. */
static int list_check(scene_ctx *c, int line, const char *what, const sample_list *s)
{
    if (s->n < 2)
        return scene_fail(c, line, "%s: a spectrum needs at least two wavelengths", what);
    for (int i = 0; i < s->n; i++)
        if (s->wl[i] <= 0 || (i > 0 && s->wl[i] <= s->wl[i - 1]))
            return scene_fail(c, line, "%s: wavelengths must be positive and increasing (%g after %g)", what,
                              s->wl[i], i > 0 ? s->wl[i - 1] : 0.0);
    return 0;
}

/* "400:0.5, 500:0.7 ..." (commas and/or white space between the pairs). */
static int parse_pairs(scene_ctx *c, int line, const char *name, const char *text, sample_list *s)
{
    const char *p = text;
    for (;;) {
        while (*p == ',' || isspace((unsigned char)*p))
            p++;
        if (!*p)
            return 0;
        char *end;
        errno = 0;
        double wl = strtod(p, &end), v = 0;
        int ok = end != p && *end == ':' && errno == 0 && isfinite(wl);
        if (ok) {
            p = end + 1;
            v = strtod(p, &end);
            ok = end != p && errno == 0 && isfinite(v) && (!*end || *end == ',' || isspace((unsigned char)*end));
        }
        if (!ok)
            return scene_fail(c, line, "bad wavelength:value pair in <spectrum name=\"%s\"> near '%.20s'", name, p);
        list_push(s, wl, v);
        p = end;
    }
}

/* A spectrum file: one "wavelength value" pair per line; '#' starts a comment. */
static int read_spectrum_file(scene_ctx *c, int line, const char *shown, const char *path, sample_list *s)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return scene_fail(c, line, "spectrum file '%s' not found (%s: %s)", shown, path, strerror(errno));
    char buf[512];
    int lineno = 0, rc = 0;
    while (rc == 0 && fgets(buf, sizeof buf, f)) {
        lineno++;
        buf[strcspn(buf, "#\r\n")] = '\0';
        double v[2];
        int k = scene_parse_list(buf, v, 2);
        if (k == 2)
            list_push(s, v[0], v[1]);
        else if (k != 0)
            rc = scene_fail(c, line, "spectrum file '%s', line %d: expected 'wavelength value'", shown, lineno);
    }
    fclose(f);
    return rc;
}

/* ------------------------------------------------------- spectrum plugins */
typedef struct {
    scene_prop p[SPECTRUM_PLUGIN_MAX_PARAMS];
    int n;
} plugin_params;

static scene_prop *param(plugin_params *pp, const char *name, scene_prop_type type)
{
    for (int i = 0; i < pp->n; i++)
        if (strcmp(pp->p[i].name, name) == 0 && pp->p[i].type == type) {
            pp->p[i].consumed = true;
            return &pp->p[i];
        }
    return NULL;
}

/* The plugin's parameters (its child elements), each a known name. */
static int read_plugin_params(scene_ctx *c, const xmlNode *n, const char *type, plugin_params *pp)
{
    for (const xmlNode *ch = n->children; ch; ch = ch->next) {
        if (ch->type == XML_COMMENT_NODE || (ch->type == XML_TEXT_NODE && xmlIsBlankNode(ch)))
            continue;
        const char *tag = (const char *)ch->name;
        if (ch->type != XML_ELEMENT_NODE || !scene_is_property_tag(tag) || strcmp(tag, "spectrum") == 0)
            return scene_fail(c, scene_line(ch), "<spectrum type=\"%s\"> takes only <float> and <string> parameters",
                              type);
        if (pp->n == SPECTRUM_PLUGIN_MAX_PARAMS)
            return scene_fail(c, scene_line(ch), "<spectrum type=\"%s\">: too many parameters", type);
        scene_prop *q = &pp->p[pp->n];
        if (scene_parse_property(c, ch, SCENE_TEXTURE, q) != 0) {
            scene_prop_clear(q);
            return -1;
        }
        pp->n++;
    }
    return 0;
}

static int plugin_float(scene_ctx *c, plugin_params *pp, const char *type, const char *name, bool required,
                        double def, double *out)
{
    scene_prop *q = param(pp, name, SCENE_FLOAT);
    *out = q ? q->value.f : def;
    if (!q && required)
        return scene_fail(c, c->line_hint, "<spectrum type=\"%s\"> needs <float name=\"%s\">", type, name);
    return 0;
}

static int plugin_numbers(scene_ctx *c, plugin_params *pp, const char *type, const char *name, double *out, int max,
                          int *count)
{
    scene_prop *q = param(pp, name, SCENE_STRING);
    if (!q)
        return scene_fail(c, c->line_hint, "<spectrum type=\"%s\"> needs <string name=\"%s\">", type, name);
    *count = scene_parse_list(q->value.s, out, max);
    if (*count < 2)
        return scene_fail(c, q->line, "<string name=\"%s\"> of <spectrum type=\"%s\"> must be 2 to %d numbers", name,
                          type, max);
    return 0;
}

enum { SPECTRUM_LIST_MAX = 4096 };

/* The plugin type's RGB from its parameters. */
static int plugin_rgb(scene_ctx *c, const char *type, plugin_params *pp, spectrum_use use, scene_rgb *out)
{
    int rc = 0;
    if (strcmp(type, "blackbody") == 0) {
        double t, wmin, wmax, xyz[3];
        rc = plugin_float(c, pp, type, "temperature", true, 0, &t) ||
             plugin_float(c, pp, type, "wavelength_min", false, CIE_MIN_NM, &wmin) ||
             plugin_float(c, pp, type, "wavelength_max", false, CIE_MAX_NM, &wmax);
        if (rc == 0 && !(t > 0 && wmin < wmax))
            rc = scene_fail(c, c->line_hint, "<spectrum type=\"blackbody\">: the temperature must be positive "
                                             "and wavelength_min below wavelength_max");
        if (rc == 0) {
            spectrum_blackbody_xyz(t, wmin, wmax, xyz);
            *out = spectrum_clamp(spectrum_xyz_to_rgb(xyz), SPECTRUM_EMITTED);
        }
    } else if (strcmp(type, "uniform") == 0) {
        double v;
        rc = plugin_float(c, pp, type, "value", true, 0, &v);
        *out = spectrum_constant_rgb(v, use);
    } else if (strcmp(type, "regular") == 0 || strcmp(type, "irregular") == 0) {
        double *wl = malloc(sizeof(double) * SPECTRUM_LIST_MAX), *v = malloc(sizeof(double) * SPECTRUM_LIST_MAX);
        if (!wl || !v)
            abort();
        int nv = 0, nw = 0;
        double wmin = 0, wmax = 0;
        rc = plugin_numbers(c, pp, type, "values", v, SPECTRUM_LIST_MAX, &nv);
        if (rc == 0 && type[0] == 'r') {
            rc = plugin_float(c, pp, type, "wavelength_min", true, 0, &wmin) ||
                 plugin_float(c, pp, type, "wavelength_max", true, 0, &wmax);
            for (int i = 0; i < nv; i++)
                wl[i] = wmin + (wmax - wmin) * i / (nv - 1);
            nw = nv;
        } else if (rc == 0) {
            rc = plugin_numbers(c, pp, type, "wavelengths", wl, SPECTRUM_LIST_MAX, &nw);
        }
        if (rc == 0 && nw != nv)
            rc = scene_fail(c, c->line_hint, "<spectrum type=\"irregular\">: %d wavelengths but %d values", nw, nv);
        sample_list s = {wl, v, nv, nv};
        if (rc == 0 && list_check(c, c->line_hint, "<spectrum>", &s) == 0)
            *out = spectrum_list_rgb(wl, v, nv, use);
        else
            rc = -1;
        free(wl);
        free(v);
    } else {
        return scene_fail(c, c->line_hint, "unknown spectrum type '%s' (blackbody, uniform, regular or irregular)",
                          type);
    }
    for (int i = 0; i < pp->n && rc == 0; i++)
        if (!pp->p[i].consumed)
            rc = scene_fail(c, pp->p[i].line, "unknown parameter '%s' for <spectrum type=\"%s\">", pp->p[i].name,
                            type);
    return rc ? -1 : 0;
}

/* ----------------------------------------------------------- the element */
static int no_content(scene_ctx *c, const xmlNode *n, const char *name)
{
    for (const xmlNode *ch = n->children; ch; ch = ch->next)
        if (ch->type != XML_COMMENT_NODE && !(ch->type == XML_TEXT_NODE && xmlIsBlankNode(ch)))
            return scene_fail(c, scene_line(n), "<spectrum name=\"%s\"> takes no content (only <spectrum type=...>)",
                              name);
    return 0;
}

int scene_parse_spectrum(scene_ctx *c, const xmlNode *n, scene_class owner, scene_prop *p)
{
    char *value = NULL, *filename = NULL, *type = NULL;
    int line = p->line, rc = -1;
    sample_list s = {0};
    plugin_params pp = {0};
    if (scene_check_attrs(c, n, "name|value|filename|type") != 0 || scene_attr_req(c, n, "name", &p->name) != 0 ||
        scene_attr(c, n, "value", &value) != 0 || scene_attr(c, n, "filename", &filename) != 0 ||
        scene_attr(c, n, "type", &type) != 0)
        goto done;
    if (!!value + !!filename + !!type != 1) {
        scene_fail(c, line, "<spectrum name=\"%s\"> needs one of 'value', 'filename' or 'type'", p->name);
        goto done;
    }
    spectrum_use use = spectrum_use_of(owner, p->name);
    c->line_hint = line;
    if (type) {
        if (read_plugin_params(c, n, type, &pp) == 0 && plugin_rgb(c, type, &pp, use, &p->value.rgb) == 0)
            rc = 0;
        goto done;
    }
    if (no_content(c, n, p->name) != 0)
        goto done;
    double constant;
    if (value && scene_parse_double(value, &constant) == 0) {
        p->value.rgb = spectrum_constant_rgb(constant, use);
        rc = 0;
        goto done;
    }
    if (value && parse_pairs(c, line, p->name, value, &s) != 0)
        goto done;
    if (filename) {
        char *path = scene_resolve_path(c, c->file, filename);
        int bad = read_spectrum_file(c, line, filename, path, &s);
        free(path);
        if (bad)
            goto done;
    }
    char what[300];
    snprintf(what, sizeof what, "<spectrum name=\"%s\">", p->name);
    if (list_check(c, line, what, &s) != 0)
        goto done;
    p->value.rgb = spectrum_list_rgb(s.wl, s.v, s.n, use);
    rc = 0;
done:
    for (int i = 0; i < pp.n; i++)
        scene_prop_clear(&pp.p[i]);
    list_free(&s);
    free(value);
    free(filename);
    free(type);
    return rc;
}
