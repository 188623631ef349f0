/* Property elements of the scene format: attributes with $parameter
 * substitution, strict number parsing, and the typed values (<float> ...
 * <transform>). */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "scene_xml/scene_xml_internal.h"

int scene_fail(scene_ctx *c, int line, const char *fmt, ...)
{
    if (c->failed)
        return -1;
    c->failed = 1;
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (line > 0)
        snprintf(c->err, c->errlen, "%s:%d: %s", c->file, line, msg);
    else
        snprintf(c->err, c->errlen, "%s: %s", c->file, msg);
    return -1;
}

int scene_line(const xmlNode *n)
{
    long l = xmlGetLineNo(n);
    return l > 0 && l < 0x7fffffff ? (int)l : 0;
}

/* ------------------------------------------------------------ attributes */
typedef struct {
    char *s;
    size_t len, cap;
} strbuf;

static void sb_put(strbuf *b, const char *s, size_t n)
{
    if (b->len + n + 1 > b->cap) {
        b->cap = (b->len + n + 1) * 2;
        b->s = realloc(b->s, b->cap);
        if (!b->s)
            abort();
    }
    memcpy(b->s + b->len, s, n);
    b->len += n;
    b->s[b->len] = '\0';
}

static scene_param *find_param(scene_ctx *c, const char *name, size_t n)
{
    for (int i = 0; i < c->nparams; i++)
        if (strlen(c->params[i].name) == n && strncmp(c->params[i].name, name, n) == 0)
            return &c->params[i];
    return NULL;
}

/* Replaces every $name (name = [A-Za-z0-9_]+) by its parameter value; a '$'
 * not followed by a name character stays as it is. */
static int substitute(scene_ctx *c, int line, const char *in, char **out)
{
    strbuf b = {0};
    sb_put(&b, "", 0);
    for (const char *p = in; *p;) {
        if (*p == '$' && (isalnum((unsigned char)p[1]) || p[1] == '_')) {
            const char *q = p + 1;
            while (isalnum((unsigned char)*q) || *q == '_')
                q++;
            scene_param *par = find_param(c, p + 1, (size_t)(q - p - 1));
            if (!par) {
                free(b.s);
                return scene_fail(c, line, "undefined parameter '$%.*s' (no <default> for it and no -D %.*s=...)",
                                  (int)(q - p - 1), p + 1, (int)(q - p - 1), p + 1);
            }
            par->used = 1;
            sb_put(&b, par->value, strlen(par->value));
            p = q;
        } else {
            sb_put(&b, p, 1);
            p++;
        }
    }
    *out = b.s;
    return 0;
}

int scene_attr(scene_ctx *c, const xmlNode *n, const char *name, char **out)
{
    *out = NULL;
    xmlChar *v = xmlGetProp(n, (const xmlChar *)name);
    if (!v)
        return 0;
    int rc = substitute(c, scene_line(n), (const char *)v, out);
    xmlFree(v);
    return rc;
}

int scene_attr_req(scene_ctx *c, const xmlNode *n, const char *name, char **out)
{
    if (scene_attr(c, n, name, out) != 0)
        return -1;
    if (!*out)
        return scene_fail(c, scene_line(n), "<%s> needs a '%s' attribute", (const char *)n->name, name);
    return 0;
}

int scene_check_attrs(scene_ctx *c, const xmlNode *n, const char *allowed)
{
    for (const xmlAttr *a = n->properties; a; a = a->next)
        if (!schema_choice_ok(allowed, (const char *)a->name))
            return scene_fail(c, scene_line(n), "unexpected attribute '%s' on <%s>", (const char *)a->name,
                              (const char *)n->name);
    return 0;
}

/* --------------------------------------------------------------- numbers */
int scene_parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || errno == ERANGE || !isfinite(v))
        return -1;
    while (isspace((unsigned char)*end))
        end++;
    if (*end)
        return -1;
    *out = v;
    return 0;
}

static int is_sep(char ch) { return ch == ',' || isspace((unsigned char)ch); }

int scene_parse_list(const char *s, double *out, int max)
{
    int n = 0;
    const char *p = s;
    for (;;) {
        while (is_sep(*p))
            p++;
        if (!*p)
            return n;
        if (n == max)
            return -1;
        char *end;
        errno = 0;
        double v = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(v) || (*end && !is_sep(*end)))
            return -1;
        out[n++] = v;
        p = end;
    }
}

static int parse_integer(const char *s, long long *out)
{
    char *end;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (end == s || errno == ERANGE)
        return -1;
    while (isspace((unsigned char)*end))
        end++;
    if (*end)
        return -1;
    *out = v;
    return 0;
}

/* A 3-vector from value="a, b, c" or from x/y/z attributes defaulting to
 * def; both forms at once is an error. what names the value in messages. */
static int parse_xyz(scene_ctx *c, const xmlNode *n, double def, vec3 *out)
{
    int line = scene_line(n);
    char *value, *xyz[3];
    const char *names[3] = {"x", "y", "z"};
    if (scene_attr(c, n, "value", &value) != 0)
        return -1;
    double v[3] = {def, def, def};
    int rc = 0, any = 0;
    for (int i = 0; i < 3; i++)
        xyz[i] = NULL;
    for (int i = 0; i < 3 && rc == 0; i++) {
        rc = scene_attr(c, n, names[i], &xyz[i]);
        if (rc == 0 && xyz[i]) {
            any = 1;
            if (scene_parse_double(xyz[i], &v[i]) != 0)
                rc = scene_fail(c, line, "bad number '%s' in attribute '%s' of <%s>", xyz[i], names[i],
                                (const char *)n->name);
        }
    }
    if (rc == 0 && value) {
        int k = scene_parse_list(value, v, 3);
        if (any)
            rc = scene_fail(c, line, "<%s> takes either 'value' or x/y/z attributes, not both", (const char *)n->name);
        else if (k != 3)
            rc = scene_fail(c, line, "<%s> value '%s' is not three numbers", (const char *)n->name, value);
    }
    free(value);
    for (int i = 0; i < 3; i++)
        free(xyz[i]);
    *out = v3(v[0], v[1], v[2]);
    return rc;
}

/* ------------------------------------------------------------ transforms */
static int parse_vec_attr(scene_ctx *c, const xmlNode *n, const char *name, int required, vec3 *out)
{
    char *s;
    if ((required ? scene_attr_req(c, n, name, &s) : scene_attr(c, n, name, &s)) != 0)
        return -1;
    if (!s)
        return 1;
    double v[3];
    int k = scene_parse_list(s, v, 3);
    if (k != 3) {
        scene_fail(c, scene_line(n), "attribute '%s' of <%s> is not three numbers: '%s'", name, (const char *)n->name, s);
        free(s);
        return -1;
    }
    free(s);
    *out = v3(v[0], v[1], v[2]);
    return 0;
}

static int parse_transform_op(scene_ctx *c, const xmlNode *n, transform4 *op)
{
    const char *tag = (const char *)n->name;
    int line = scene_line(n);
    if (strcmp(tag, "translate") == 0) {
        vec3 t;
        if (scene_check_attrs(c, n, "value|x|y|z") != 0 || parse_xyz(c, n, 0.0, &t) != 0)
            return -1;
        *op = transform_translate(t);
        return 0;
    }
    if (strcmp(tag, "scale") == 0) {
        vec3 s;
        char *value = NULL;
        if (scene_check_attrs(c, n, "value|x|y|z") != 0 || scene_attr(c, n, "value", &value) != 0)
            return -1;
        double u;
        int uniform = value && scene_parse_list(value, &u, 1) == 1;
        free(value);
        if (uniform && (xmlHasProp(n, (const xmlChar *)"x") || xmlHasProp(n, (const xmlChar *)"y") ||
                        xmlHasProp(n, (const xmlChar *)"z")))
            return scene_fail(c, line, "<scale> takes either 'value' or x/y/z attributes, not both");
        if (uniform)
            s = v3(u, u, u);
        else if (parse_xyz(c, n, 1.0, &s) != 0)
            return -1;
        if (s.x == 0 || s.y == 0 || s.z == 0)
            return scene_fail(c, line, "<scale> factors must be nonzero");
        *op = transform_scale(s);
        return 0;
    }
    if (strcmp(tag, "rotate") == 0) {
        vec3 axis;
        char *angle;
        double a;
        if (scene_check_attrs(c, n, "value|x|y|z|angle") != 0 || parse_xyz(c, n, 0.0, &axis) != 0 ||
            scene_attr_req(c, n, "angle", &angle) != 0)
            return -1;
        int bad = scene_parse_double(angle, &a) != 0;
        if (bad)
            scene_fail(c, line, "bad number '%s' in attribute 'angle' of <rotate>", angle);
        free(angle);
        if (bad)
            return -1;
        if (v3_len(axis) == 0)
            return scene_fail(c, line, "<rotate> needs a nonzero axis");
        *op = transform_rotate(axis, a);
        return 0;
    }
    if (strcmp(tag, "matrix") == 0) {
        char *value;
        double v[16];
        if (scene_check_attrs(c, n, "value") != 0 || scene_attr_req(c, n, "value", &value) != 0)
            return -1;
        int k = scene_parse_list(value, v, 16);
        free(value);
        if (k == 9) { /* 3x3: embed in the identity */
            double m3[9];
            memcpy(m3, v, sizeof m3);
            const double e[16] = {m3[0], m3[1], m3[2], 0, m3[3], m3[4], m3[5], 0, m3[6], m3[7], m3[8], 0, 0, 0, 0, 1};
            memcpy(v, e, sizeof v);
        } else if (k != 16) {
            return scene_fail(c, line, "<matrix> value must be 16 or 9 numbers");
        }
        if (transform_from_rows(v, op) != 0)
            return scene_fail(c, line, "<matrix> must be affine (last row 0 0 0 1) and invertible");
        return 0;
    }
    if (strcmp(tag, "lookat") == 0) {
        vec3 origin, target, up;
        if (scene_check_attrs(c, n, "origin|target|up") != 0 || parse_vec_attr(c, n, "origin", 1, &origin) != 0 ||
            parse_vec_attr(c, n, "target", 1, &target) != 0)
            return -1;
        int has_up = parse_vec_attr(c, n, "up", 0, &up);
        if (has_up < 0)
            return -1;
        if (has_up == 1) /* no up given: any direction perpendicular to the view */
            up = frame3_from_normal(v3_norm(v3_sub(target, origin))).s;
        if (transform_lookat(origin, target, up, op) != 0)
            return scene_fail(c, line, "<lookat> is degenerate (origin equals target, or up is parallel to the view)");
        return 0;
    }
    return scene_fail(c, line, "unknown transform operation <%s> (expected translate, rotate, scale, matrix or lookat)",
                      tag);
}

/* Each operation is applied after the ones before it: M <- op · M. */
static int parse_transform(scene_ctx *c, const xmlNode *n, transform4 *out)
{
    transform4 m = transform_identity();
    for (const xmlNode *ch = n->children; ch; ch = ch->next) {
        if (ch->type == XML_COMMENT_NODE)
            continue;
        if (ch->type == XML_TEXT_NODE) {
            if (xmlIsBlankNode(ch))
                continue;
            return scene_fail(c, scene_line(ch), "unexpected text inside <transform>");
        }
        if (ch->type != XML_ELEMENT_NODE)
            return scene_fail(c, scene_line(ch), "unexpected content inside <transform>");
        transform4 op;
        if (parse_transform_op(c, ch, &op) != 0)
            return -1;
        m = transform_compose(&op, &m);
    }
    *out = m;
    return 0;
}

/* ------------------------------------------------------------ properties */
static const char *property_tags[] = {"float", "integer", "boolean", "string", "rgb",
                                      "spectrum", "point", "vector", "transform"};

int scene_is_property_tag(const char *tag)
{
    for (int i = 0; i < (int)(sizeof property_tags / sizeof property_tags[0]); i++)
        if (strcmp(tag, property_tags[i]) == 0)
            return 1;
    return 0;
}

void scene_prop_clear(scene_prop *p)
{
    free(p->name);
    if (p->type == SCENE_STRING)
        free(p->value.s);
    memset(p, 0, sizeof *p);
}

static int parse_value(scene_ctx *c, const xmlNode *n, scene_prop *p, const char *value)
{
    int line = p->line;
    const char *tag = (const char *)n->name;
    switch (p->type) {
    case SCENE_FLOAT:
        if (scene_parse_double(value, &p->value.f) != 0)
            return scene_fail(c, line, "bad number '%s' for <float name=\"%s\">", value, p->name);
        return 0;
    case SCENE_INTEGER:
        if (parse_integer(value, &p->value.i) != 0)
            return scene_fail(c, line, "bad integer '%s' for <integer name=\"%s\">", value, p->name);
        return 0;
    case SCENE_BOOLEAN:
        if (strcasecmp(value, "true") == 0)
            p->value.b = true;
        else if (strcasecmp(value, "false") == 0)
            p->value.b = false;
        else
            return scene_fail(c, line, "bad boolean '%s' for <boolean name=\"%s\"> (true or false)", value, p->name);
        return 0;
    case SCENE_RGB: {
        double v[3];
        int k = scene_parse_list(value, v, 3);
        if (k == 1)
            v[1] = v[2] = v[0];
        else if (k != 3)
            return scene_fail(c, line, "bad color '%s' for <rgb name=\"%s\"> (one or three numbers)", value, p->name);
        p->value.rgb = (scene_rgb){v[0], v[1], v[2]};
        return 0;
    }
    default:
        return scene_fail(c, line, "internal: <%s> has no scalar value", tag);
    }
}

int scene_parse_property(scene_ctx *c, const xmlNode *n, scene_class owner, scene_prop *p)
{
    const char *tag = (const char *)n->name;
    memset(p, 0, sizeof *p);
    p->file = c->file;
    p->line = scene_line(n);
    for (int t = SCENE_FLOAT; t <= SCENE_TRANSFORM; t++)
        if (strcmp(tag, property_tags[t]) == 0)
            p->type = (scene_prop_type)t;

    if (p->type == SCENE_SPECTRUM)
        return scene_parse_spectrum(c, n, owner, p);
    const char *allowed = p->type == SCENE_TRANSFORM                          ? "name"
                          : (p->type == SCENE_POINT || p->type == SCENE_VECTOR) ? "name|value|x|y|z"
                                                                                : "name|value";
    if (scene_check_attrs(c, n, allowed) != 0 || scene_attr_req(c, n, "name", &p->name) != 0)
        return -1;
    if (p->type != SCENE_TRANSFORM) /* text content is meaningless on the other property tags */
        for (const xmlNode *ch = n->children; ch; ch = ch->next)
            if (ch->type != XML_COMMENT_NODE && !(ch->type == XML_TEXT_NODE && xmlIsBlankNode(ch)))
                return scene_fail(c, scene_line(n), "<%s name=\"%s\"> takes no content", tag, p->name);

    switch (p->type) {
    case SCENE_TRANSFORM:
        return parse_transform(c, n, &p->value.xf);
    case SCENE_POINT:
    case SCENE_VECTOR:
        if (!xmlHasProp(n, (const xmlChar *)"value") && !xmlHasProp(n, (const xmlChar *)"x") &&
            !xmlHasProp(n, (const xmlChar *)"y") && !xmlHasProp(n, (const xmlChar *)"z"))
            return scene_fail(c, p->line, "<%s name=\"%s\"> needs a 'value' or x/y/z attributes", tag, p->name);
        return parse_xyz(c, n, 0.0, &p->value.v);
    case SCENE_STRING:
        return scene_attr_req(c, n, "value", &p->value.s);
    default: {
        char *value;
        if (scene_attr_req(c, n, "value", &value) != 0)
            return -1;
        int rc = parse_value(c, n, p, value);
        free(value);
        return rc;
    }
    }
}
