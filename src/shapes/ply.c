/* Stanford PLY reader for the `ply` shape: ascii and binary_little_endian,
 * vertex x y z, optional nx ny nz and u v (or s t, texture_u texture_v),
 * faces as a list property vertex_indices (or vertex_index), fanned into
 * triangles. The other scalar properties of vertices and faces are the
 * mesh's attributes, named as Mitsuba names them: stem_0, stem_1, ... (or
 * one property stem) are vertex_stem or face_stem with that many channels,
 * r g b (red green blue) are color; attributes of 1 or 3 channels are kept
 * (a face's values for each of its triangles), others skipped. Other
 * elements are read and skipped. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "shapes/shape_impl.h"

enum { PLY_MAX_PROPS = 32, PLY_MAX_ELEMS = 8 };

typedef struct {
    char name[64];
    int type, count_type; /* byte sizes tagged by kind; count_type 0 when not a list */
} ply_prop;

typedef struct {
    char name[64];
    long count;
    int nprops;
    ply_prop props[PLY_MAX_PROPS];
} ply_elem;

/* Types: index into this table. */
static const struct { const char *name, *alt; int size, is_float, is_signed; } ply_types[] = {
    {"char", "int8", 1, 0, 1},   {"uchar", "uint8", 1, 0, 0},   {"short", "int16", 2, 0, 1},
    {"ushort", "uint16", 2, 0, 0}, {"int", "int32", 4, 0, 1},   {"uint", "uint32", 4, 0, 0},
    {"float", "float32", 4, 1, 1}, {"double", "float64", 8, 1, 1},
};

static int ply_type(const char *s)
{
    for (int i = 0; i < (int)(sizeof ply_types / sizeof ply_types[0]); i++)
        if (!strcmp(s, ply_types[i].name) || !strcmp(s, ply_types[i].alt))
            return i;
    return -1;
}

/* Reads one value; returns 0 or -1 at end of file or on a bad number. */
static int ply_value(FILE *fp, int binary, int type, double *out)
{
    if (!binary)
        return fscanf(fp, "%lf", out) == 1 && isfinite(*out) ? 0 : -1;
    unsigned char b[8];
    int size = ply_types[type].size;
    if (fread(b, 1, (size_t)size, fp) != (size_t)size)
        return -1;
    uint64_t u = 0;
    for (int i = size - 1; i >= 0; i--)
        u = (u << 8) | b[i];
    if (ply_types[type].is_float) {
        if (size == 4) {
            uint32_t w = (uint32_t)u;
            float f;
            memcpy(&f, &w, 4);
            *out = f;
        } else {
            memcpy(out, &u, 8);
        }
        return isfinite(*out) ? 0 : -1;
    }
    if (ply_types[type].is_signed && size < 8 && (u >> (8 * size - 1)) & 1u)
        *out = (double)(int64_t)(u - (1ull << (8 * size)));
    else
        *out = (double)u;
    return 0;
}

/* Every element takes at least one byte of the file's size, so a header
 * cannot make the reader allocate more than the file could fill. */
static int ply_header(FILE *fp, long long size, int *binary, ply_elem *elems, int *nelems)
{
    char line[512], a[64], b[64], c[64], d[64];
    if (!fgets(line, sizeof line, fp) || strncmp(line, "ply", 3))
        return -1;
    *nelems = 0;
    int have_format = 0;
    while (fgets(line, sizeof line, fp)) {
        if (!strncmp(line, "end_header", 10))
            return have_format ? 0 : -1;
        int n = sscanf(line, "%63s %63s %63s %63s %63s", a, b, c, d, d);
        if (n < 1 || !strcmp(a, "comment") || !strcmp(a, "obj_info"))
            continue;
        if (!strcmp(a, "format") && n >= 2) {
            if (strcmp(b, "ascii") && strcmp(b, "binary_little_endian"))
                return -1;
            *binary = strcmp(b, "ascii") != 0;
            have_format = 1;
        } else if (!strcmp(a, "element") && n >= 3 && *nelems < PLY_MAX_ELEMS) {
            ply_elem *e = &elems[(*nelems)++];
            memset(e, 0, sizeof *e);
            snprintf(e->name, sizeof e->name, "%s", b);
            char *end;
            e->count = strtol(c, &end, 10);
            if (*end || e->count < 0 || e->count > size)
                return -1;
        } else if (!strcmp(a, "property") && *nelems > 0 && elems[*nelems - 1].nprops < PLY_MAX_PROPS) {
            ply_elem *e = &elems[*nelems - 1];
            ply_prop *p = &e->props[e->nprops++];
            if (!strcmp(b, "list") && n >= 5) {
                sscanf(line, "%*s %*s %63s %63s %63s", b, c, d);
                p->count_type = ply_type(b) + 1;
                p->type = ply_type(c);
                snprintf(p->name, sizeof p->name, "%s", d);
                if (p->count_type <= 0)
                    return -1;
            } else {
                p->type = ply_type(b);
                snprintf(p->name, sizeof p->name, "%s", c);
            }
            if (p->type < 0)
                return -1;
        } else {
            return -1;
        }
    }
    return -1;
}

static int vertex_slot(const char *name)
{
    static const char *names[][3] = {{"x", NULL, NULL},     {"y", NULL, NULL},     {"z", NULL, NULL},
                                     {"nx", NULL, NULL},    {"ny", NULL, NULL},    {"nz", NULL, NULL},
                                     {"u", "s", "texture_u"}, {"v", "t", "texture_v"}};
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++)
            if (names[i][k] && !strcmp(name, names[i][k]))
                return i;
    return -1;
}

/* The stem and channel of a scalar property as an attribute. */
static void attribute_stem(const char *name, char *stem, size_t len, int *channel)
{
    static const char *rgb[3][2] = {{"r", "red"}, {"g", "green"}, {"b", "blue"}};
    for (int c = 0; c < 3; c++)
        if (!strcmp(name, rgb[c][0]) || !strcmp(name, rgb[c][1])) {
            snprintf(stem, len, "color");
            *channel = c;
            return;
        }
    size_t n = strlen(name);
    if (n >= 3 && name[n - 2] == '_' && name[n - 1] >= '0' && name[n - 1] <= '9') {
        snprintf(stem, len, "%.*s", (int)(n - 2), name);
        *channel = name[n - 1] - '0';
        return;
    }
    snprintf(stem, len, "%s", name);
    *channel = 0;
}

/* The attributes of element e (a vertex or face element): for each scalar
 * property that is not a vertex slot, its attribute in m->attrs (appended;
 * -1 when skipped) and channel. 0, or -1 when out of memory. */
static int plan_attributes(const ply_elem *e, const int *slot, bool per_face, shape_mesh_data *m, int *attr, int *chan)
{
    for (int k = 0; k < e->nprops; k++) {
        attr[k] = -1;
        if (e->props[k].count_type || slot[k] >= 0)
            continue;
        char stem[64], name[80];
        attribute_stem(e->props[k].name, stem, sizeof stem, &chan[k]);
        snprintf(name, sizeof name, "%s_%s", per_face ? "face" : "vertex", stem);
        int a = 0;
        while (a < m->attrs.count && strcmp(m->attrs.items[a].name, name) != 0)
            a++;
        if (a == m->attrs.count) {
            texture_attribute *items = realloc(m->attrs.items, sizeof *items * (size_t)(a + 1));
            if (!items)
                return -1;
            m->attrs.items = items;
            items[a] = (texture_attribute){.name = strdup(name), .per_face = per_face};
            m->attrs.count++;
            if (!items[a].name)
                return -1;
        }
        texture_attribute *t = &m->attrs.items[a];
        t->channels = chan[k] + 1 > t->channels ? chan[k] + 1 : t->channels;
        attr[k] = a;
    }
    /* Only 1 or 3 channels make a value: drop the others' properties. */
    for (int k = 0; k < e->nprops; k++)
        if (attr[k] >= 0 && m->attrs.items[attr[k]].channels != 1 && m->attrs.items[attr[k]].channels != 3)
            attr[k] = -1;
    return 0;
}

/* Room for count more values (of channels each) of attribute a: 0 or -1. */
static int grow_attribute(texture_attribute *a, size_t have, size_t count)
{
    float *v = realloc(a->values, sizeof *v * (have + count) * (size_t)a->channels);
    if (!v)
        return -1;
    a->values = v;
    memset(v + have * (size_t)a->channels, 0, sizeof *v * count * (size_t)a->channels);
    return 0;
}

static int read_elements(FILE *fp, int binary, const ply_elem *elems, int nelems, shape_mesh_data *m,
                         size_t *tri_cap)
{
    for (int ei = 0; ei < nelems; ei++) {
        const ply_elem *e = &elems[ei];
        int is_vertex = !strcmp(e->name, "vertex"), is_face = !strcmp(e->name, "face");
        int slot[PLY_MAX_PROPS], has[8] = {0};
        for (int k = 0; k < e->nprops; k++) {
            slot[k] = is_vertex && !e->props[k].count_type ? vertex_slot(e->props[k].name) : -1;
            if (slot[k] >= 0)
                has[slot[k]] = 1;
        }
        if (is_vertex) {
            if (!has[0] || !has[1] || !has[2] || e->count > INT32_MAX / 4)
                return -1;
            m->n_verts = (int)e->count;
            m->pos = calloc((size_t)m->n_verts * 3 + 1, sizeof(float));
            m->nrm = has[3] && has[4] && has[5] ? calloc((size_t)m->n_verts * 3, sizeof(float)) : NULL;
            m->uv = has[6] && has[7] ? calloc((size_t)m->n_verts * 2, sizeof(float)) : NULL;
            if (!m->pos)
                return -1;
        }
        int attr[PLY_MAX_PROPS], chan[PLY_MAX_PROPS], first_attr = m->attrs.count;
        if ((is_vertex || is_face) && plan_attributes(e, slot, is_face, m, attr, chan) != 0)
            return -1;
        for (int a = first_attr; is_vertex && a < m->attrs.count; a++)
            if (grow_attribute(&m->attrs.items[a], 0, (size_t)m->n_verts) != 0)
                return -1;
        for (long i = 0; i < e->count; i++) {
            float face_values[PLY_MAX_PROPS];
            int tris_before = m->n_tris;
            for (int k = 0; k < e->nprops; k++) {
                const ply_prop *p = &e->props[k];
                double x;
                if (!p->count_type) {
                    if (ply_value(fp, binary, p->type, &x) != 0)
                        return -1;
                    if ((is_vertex || is_face) && attr[k] >= 0) {
                        texture_attribute *a = &m->attrs.items[attr[k]];
                        if (is_vertex)
                            a->values[(size_t)i * (size_t)a->channels + (size_t)chan[k]] = (float)x;
                        else
                            face_values[k] = (float)x;
                        continue;
                    }
                    int s = slot[k];
                    if (s >= 0 && s < 3)
                        m->pos[3 * i + s] = (float)x;
                    else if (s >= 3 && s < 6 && m->nrm)
                        m->nrm[3 * i + s - 3] = (float)x;
                    else if (s >= 6 && m->uv)
                        m->uv[2 * i + s - 6] = (float)x; /* as stored: Mitsuba flips only OBJ's v */
                    continue;
                }
                double cnt;
                if (ply_value(fp, binary, p->count_type - 1, &cnt) != 0 || cnt < 0 || cnt > 1024)
                    return -1;
                int face_list = is_face && (!strcmp(p->name, "vertex_indices") || !strcmp(p->name, "vertex_index"));
                unsigned first = 0, prev = 0;
                for (int j = 0; j < (int)cnt; j++) {
                    if (ply_value(fp, binary, p->type, &x) != 0)
                        return -1;
                    if (!face_list)
                        continue;
                    if (x < 0 || x >= m->n_verts)
                        return -1;
                    unsigned vi = (unsigned)x;
                    if (j == 0)
                        first = vi;
                    if (j >= 2) {
                        if ((size_t)m->n_tris + 1 > *tri_cap) {
                            *tri_cap = *tri_cap ? 2 * *tri_cap : 1024;
                            unsigned *t = realloc(m->tri, *tri_cap * 3 * sizeof *t);
                            if (!t)
                                return -1;
                            m->tri = t;
                        }
                        unsigned *t = &m->tri[3 * m->n_tris++];
                        t[0] = first, t[1] = prev, t[2] = vi;
                    }
                    prev = vi;
                }
            }
            /* The face's values, for each triangle it was fanned into. */
            size_t added = (size_t)(m->n_tris - tris_before);
            for (int a = first_attr; is_face && added > 0 && a < m->attrs.count; a++)
                if (grow_attribute(&m->attrs.items[a], (size_t)tris_before, added) != 0)
                    return -1;
            for (int k = 0; is_face && k < e->nprops; k++) {
                if (attr[k] < 0)
                    continue;
                texture_attribute *a = &m->attrs.items[attr[k]];
                for (size_t t = (size_t)tris_before; t < (size_t)m->n_tris; t++)
                    a->values[t * (size_t)a->channels + (size_t)chan[k]] = face_values[k];
            }
        }
    }
    m->attrs.tri = m->tri;
    return m->n_verts > 0 && m->n_tris > 0 ? 0 : -1;
}

static int ply_read(const char *path, shape_mesh_data *m, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    char why[256];
    long long size;
    FILE *fp = input_open(path, INPUT_MAX_DATA_BYTES, &size, why, sizeof why);
    if (!fp) {
        snprintf(err, errlen, "'%s': %s", path, why);
        return -1;
    }
    ply_elem elems[PLY_MAX_ELEMS];
    int nelems = 0, binary = 0;
    size_t tri_cap = 0;
    int rc = ply_header(fp, size, &binary, elems, &nelems);
    if (rc != 0)
        snprintf(err, errlen, "'%s' is not a PLY file this reader knows (ascii or binary_little_endian)", path);
    else if ((rc = read_elements(fp, binary, elems, nelems, m, &tri_cap)) != 0)
        snprintf(err, errlen, "'%s': truncated or malformed PLY data (needs vertex x y z and face vertex_indices)",
                 path);
    fclose(fp);
    if (rc != 0)
        shape_mesh_data_free(m);
    return rc;
}

static int ply_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh, char *err,
                      size_t errlen)
{
    (void)opt, (void)to_world;
    char why[600] = "";
    int rc = ply_read(scene_obj_string(o, "filename", NULL), &sh->mesh, why, sizeof why);
    if (rc == 0 && sh->mesh.uv && scene_obj_bool(o, "flip_tex_coords", false)) /* Mitsuba's option, off by default */
        for (int i = 0; i < sh->mesh.n_verts; i++)
            sh->mesh.uv[2 * i + 1] = 1.0f - sh->mesh.uv[2 * i + 1];
    return shape_mesh_from_file(o, rc, why, sh, err, errlen);
}

static const scene_param_decl ply_params[] = {
    SHAPE_PARAMS_COMMON,
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"face_normals", PARAM_BOOL, 0, NULL},
    {"flip_tex_coords", PARAM_BOOL, 0, NULL},
    SHAPE_PARAMS_END,
};

const shape_plugin shape_ply = {
    .decl = {.cls = SCENE_SHAPE, .type = "ply", .params = ply_params, .children = shape_children},
    .create = ply_create,
};
