/* Wavefront OBJ reader for the `obj` shape: v, vt, vn and polygonal f
 * (v, v/vt, v//vn, v/vt/vn; negative indices count from the end), fanned
 * into triangles. Each distinct (v, vt, vn) corner becomes one vertex.
 * Other statements (o, g, s, usemtl, mtllib, ...) are ignored, as Mitsuba does.
 * `flip_tex_coords` (default true, as in Mitsuba) makes v = 1 - v. */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "shapes/shape_impl.h"

typedef struct {
    double *v;
    size_t n, cap; /* in doubles */
} dbuf;

static int dbuf_push(dbuf *b, const double *x, int k)
{
    if (b->n + (size_t)k > b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 1024;
        double *v = realloc(b->v, cap * sizeof *v);
        if (!v)
            return -1;
        b->v = v, b->cap = cap;
    }
    memcpy(b->v + b->n, x, (size_t)k * sizeof *x);
    b->n += (size_t)k;
    return 0;
}

typedef struct {
    long key[3];
    unsigned vert;
} corner_slot;

typedef struct {
    corner_slot *slot;
    size_t cap; /* power of two */
    size_t used;
} corner_map;

static uint64_t corner_hash(const long *k)
{
    uint64_t h = 1469598103934665603ull;
    for (int i = 0; i < 3; i++)
        h = (h ^ (uint64_t)k[i]) * 1099511628211ull;
    return h ^ (h >> 29);
}

static int corner_map_grow(corner_map *m)
{
    size_t cap = m->cap ? 2 * m->cap : 4096;
    corner_slot *s = malloc(cap * sizeof *s);
    if (!s)
        return -1;
    for (size_t i = 0; i < cap; i++)
        s[i].key[0] = -1;
    for (size_t i = 0; i < m->cap; i++) {
        if (m->slot[i].key[0] < 0)
            continue;
        size_t j = corner_hash(m->slot[i].key) & (cap - 1);
        while (s[j].key[0] >= 0)
            j = (j + 1) & (cap - 1);
        s[j] = m->slot[i];
    }
    free(m->slot);
    m->slot = s, m->cap = cap;
    return 0;
}

typedef struct {
    const dbuf *v, *vt, *vn;
    corner_map map;
    dbuf pos, nrm, uv;
    unsigned nverts;
    bool flip_v;
} obj_builder;

/* The vertex of corner (iv, ivt, ivn) (0-based, -1 when absent). */
static long corner_vertex(obj_builder *b, const long *key)
{
    if ((b->map.used + 1) * 2 > b->map.cap && corner_map_grow(&b->map) != 0)
        return -1;
    size_t j = corner_hash(key) & (b->map.cap - 1);
    while (b->map.slot[j].key[0] >= 0) {
        if (!memcmp(b->map.slot[j].key, key, sizeof b->map.slot[j].key))
            return b->map.slot[j].vert;
        j = (j + 1) & (b->map.cap - 1);
    }
    double uv[2] = {0, 0}, n[3] = {0, 0, 0};
    if (key[1] >= 0)
        uv[0] = b->vt->v[2 * key[1]], uv[1] = b->flip_v ? 1.0 - b->vt->v[2 * key[1] + 1] : b->vt->v[2 * key[1] + 1];
    if (key[2] >= 0)
        memcpy(n, b->vn->v + 3 * key[2], sizeof n);
    if (dbuf_push(&b->pos, b->v->v + 3 * key[0], 3) || dbuf_push(&b->uv, uv, 2) || dbuf_push(&b->nrm, n, 3))
        return -1;
    memcpy(b->map.slot[j].key, key, sizeof b->map.slot[j].key);
    b->map.slot[j].vert = b->nverts;
    b->map.used++;
    return b->nverts++;
}

/* Parses "i", "i/j", "i//k", "i/j/k" into 0-based indices; -1 when absent. */
static int parse_corner(const char *tok, const size_t count[3], long out[3])
{
    const char *s = tok;
    out[0] = out[1] = out[2] = -1;
    for (int k = 0; k < 3; k++) {
        if (k > 0) {
            if (*s != '/')
                break;
            s++;
        }
        if (*s == '/' || *s == '\0')
            continue;
        char *end;
        errno = 0;
        long i = strtol(s, &end, 10);
        if (end == s || errno || i == 0)
            return -1;
        i = i > 0 ? i - 1 : (long)count[k] + i;
        if (i < 0 || (size_t)i >= count[k])
            return -1;
        out[k] = i;
        s = end;
    }
    return *s == '\0' && out[0] >= 0 ? 0 : -1;
}

static float *to_floats(const dbuf *b, size_t n, size_t pad)
{
    float *f = calloc(n + pad, sizeof *f);
    if (f)
        for (size_t i = 0; i < n; i++)
            f[i] = (float)b->v[i];
    return f;
}

static int obj_read(const char *path, bool flip_tex_coords, shape_mesh_data *m, char *err, size_t errlen)
{
    char why[256];
    FILE *fp = input_open(path, INPUT_MAX_DATA_BYTES, NULL, why, sizeof why);
    if (!fp) {
        snprintf(err, errlen, "'%s': %s", path, why);
        return -1;
    }
    dbuf v = {0}, vt = {0}, vn = {0}, tris = {0};
    obj_builder b = {.v = &v, .vt = &vt, .vn = &vn, .flip_v = flip_tex_coords};
    char line[4096];
    int lineno = 0, rc = 0;
    while (rc == 0 && fgets(line, sizeof line, fp)) {
        lineno++;
        char *save, *tok = strtok_r(line, " \t\r\n", &save);
        if (!tok || tok[0] == '#')
            continue;
        int want = !strcmp(tok, "v") ? 3 : !strcmp(tok, "vn") ? 3 : !strcmp(tok, "vt") ? 2 : 0;
        if (want) {
            dbuf *dst = tok[1] == 'n' ? &vn : tok[1] == 't' ? &vt : &v;
            double x[3] = {0, 0, 0};
            for (int k = 0; k < want; k++) {
                char *num = strtok_r(NULL, " \t\r\n", &save), *end;
                x[k] = num ? strtod(num, &end) : 0.0;
                if (!num || *end || !isfinite(x[k]))
                    rc = -1;
            }
            if (rc || dbuf_push(dst, x, want))
                rc = -1;
        } else if (!strcmp(tok, "f")) {
            size_t count[3] = {v.n / 3, vt.n / 2, vn.n / 3};
            long first = -1, prev = -1;
            int nc = 0;
            for (char *c; rc == 0 && (c = strtok_r(NULL, " \t\r\n", &save)); nc++) {
                long key[3];
                long vert = parse_corner(c, count, key) == 0 ? corner_vertex(&b, key) : -1;
                if (vert < 0) {
                    rc = -1;
                    break;
                }
                if (nc == 0)
                    first = vert;
                else if (nc >= 2) {
                    double t[3] = {(double)first, (double)prev, (double)vert};
                    rc = dbuf_push(&tris, t, 3);
                }
                prev = vert;
            }
            if (nc < 3)
                rc = -1;
        }
    }
    fclose(fp);
    if (rc == 0 && tris.n == 0) {
        snprintf(err, errlen, "'%s' has no faces", path);
        rc = -2;
    } else if (rc == -1) {
        snprintf(err, errlen, "'%s' line %d: malformed OBJ statement", path, lineno);
    }
    if (rc == 0) {
        memset(m, 0, sizeof *m);
        m->n_verts = (int)b.nverts;
        m->n_tris = (int)(tris.n / 3);
        m->pos = to_floats(&b.pos, b.pos.n, 1);
        m->uv = vt.n ? to_floats(&b.uv, b.uv.n, 0) : NULL;
        m->nrm = vn.n ? to_floats(&b.nrm, b.nrm.n, 0) : NULL;
        m->tri = malloc(tris.n * sizeof *m->tri);
        if (!m->pos || !m->tri || (vt.n && !m->uv) || (vn.n && !m->nrm)) {
            snprintf(err, errlen, "out of memory reading '%s'", path);
            shape_mesh_data_free(m);
            rc = -1;
        } else {
            for (size_t i = 0; i < tris.n; i++)
                m->tri[i] = (unsigned)tris.v[i];
        }
    }
    free(v.v), free(vt.v), free(vn.v), free(tris.v);
    free(b.pos.v), free(b.uv.v), free(b.nrm.v), free(b.map.slot);
    return rc == 0 ? 0 : -1;
}

static int obj_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh, char *err,
                      size_t errlen)
{
    (void)opt, (void)to_world;
    char why[600] = "";
    int rc = obj_read(scene_obj_string(o, "filename", NULL), scene_obj_bool(o, "flip_tex_coords", true), &sh->mesh,
                      why, sizeof why);
    return shape_mesh_from_file(o, rc, why, sh, err, errlen);
}

static const scene_param_decl obj_params[] = {
    SHAPE_PARAMS_COMMON,
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"face_normals", PARAM_BOOL, 0, NULL},
    {"flip_tex_coords", PARAM_BOOL, 0, NULL},
    SHAPE_PARAMS_END,
};

const shape_plugin shape_obj = {
    .decl = {.cls = SCENE_SHAPE, .type = "obj", .params = obj_params, .children = shape_children},
    .create = obj_create,
};
