/* The GLB container: a 12-byte header, a JSON chunk and a BIN chunk, all
 * little-endian. See glb.h. */
#include "core/core.h"
#include "museum/glb.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


enum {
    GLB_MAGIC = 0x46546C67,      /* "glTF" */
    GLB_VERSION = 2,
    CHUNK_JSON = 0x4E4F534A,     /* "JSON" */
    CHUNK_BIN = 0x004E4942,      /* "BIN\0" */
};

int glb_init(glb_t *g, const char *generator)
{
    memset(g, 0, sizeof *g);
    g->doc = json_pack("{s:{s:s, s:s}}", "asset", "version", "2.0", "generator", generator);
    return g->doc ? 0 : -1;
}

void glb_free(glb_t *g)
{
    json_decref(g->doc);
    free(g->bin);
    memset(g, 0, sizeof *g);
}

int glb_append(glb_t *g, const char *key, json_t *obj)
{
    if (!obj)
        return -1;
    json_t *arr = json_object_get(g->doc, key);
    if (!arr) {
        arr = json_array();
        if (!arr || json_object_set_new(g->doc, key, arr) != 0) {
            json_decref(obj);
            return -1;
        }
    }
    if (json_array_append_new(arr, obj) != 0)
        return -1;
    return (int)json_array_size(arr) - 1;
}

static int reserve(glb_t *g, size_t more)
{
    if (g->bin_len + more <= g->bin_cap)
        return 0;
    size_t cap = g->bin_cap ? g->bin_cap : 1u << 20;
    while (cap < g->bin_len + more)
        cap *= 2;
    uint8_t *grown = realloc(g->bin, cap);
    if (!grown)
        return -1;
    g->bin = grown;
    g->bin_cap = cap;
    return 0;
}

int glb_add_view(glb_t *g, const void *data, size_t len, int target)
{
    return glb_add_strided_view(g, data, len, target, 0);
}

int glb_add_strided_view(glb_t *g, const void *data, size_t len, int target, int stride)
{
    size_t pad = (4 - g->bin_len % 4) % 4;
    if (len == 0 || reserve(g, pad + len) != 0)
        return -1;
    memset(g->bin + g->bin_len, 0, pad);
    g->bin_len += pad;
    size_t offset = g->bin_len;
    memcpy(g->bin + offset, data, len);
    g->bin_len += len;
    json_t *view = json_pack("{s:i, s:I, s:I}", "buffer", 0, "byteOffset", (json_int_t)offset, "byteLength",
                             (json_int_t)len);
    if (view && target)
        json_object_set_new(view, "target", json_integer(target));
    if (view && stride)
        json_object_set_new(view, "byteStride", json_integer(stride));
    return glb_append(g, "bufferViews", view);
}

static json_t *number_array(const double *v, int n)
{
    json_t *a = json_array();
    for (int i = 0; a && i < n; i++)
        json_array_append_new(a, json_real(v[i]));
    return a;
}

int glb_add_accessor(glb_t *g, int view, int component_type, int count, const char *type, const double *min,
                     const double *max)
{
    int ncomp = !strcmp(type, "SCALAR") ? 1 : !strcmp(type, "VEC2") ? 2 : !strcmp(type, "VEC3") ? 3 : 4;
    json_t *acc = json_pack("{s:i, s:i, s:i, s:s}", "bufferView", view, "componentType", component_type, "count",
                            count, "type", type);
    if (acc && min && max) {
        json_object_set_new(acc, "min", number_array(min, ncomp));
        json_object_set_new(acc, "max", number_array(max, ncomp));
    }
    return glb_append(g, "accessors", acc);
}

int glb_set_normalized(glb_t *g, int accessor)
{
    json_t *a = json_array_get(json_object_get(g->doc, "accessors"), (size_t)accessor);
    return a ? json_object_set_new(a, "normalized", json_true()) : -1;
}

/* Appends name to the top-level list key unless it is there. */
static int list_once(glb_t *g, const char *key, const char *name)
{
    json_t *list = json_object_get(g->doc, key);
    size_t i;
    json_t *v;
    json_array_foreach(list, i, v)
        if (!strcmp(json_string_value(v), name))
            return 0;
    return glb_append(g, key, json_string(name)) < 0 ? -1 : 0;
}

int glb_use_extension(glb_t *g, const char *name) { return list_once(g, "extensionsUsed", name); }

int glb_require_extension(glb_t *g, const char *name)
{
    return list_once(g, "extensionsUsed", name) || list_once(g, "extensionsRequired", name) ? -1 : 0;
}

static void put_u32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

/* Header, JSON chunk (space-padded), BIN chunk (zero-padded). */
static int write_chunks(FILE *f, const char *json, size_t json_len, const uint8_t *bin, size_t bin_len)
{
    static const uint8_t zeros[4] = {0}, spaces[4] = {' ', ' ', ' ', ' '};
    size_t json_pad = (4 - json_len % 4) % 4, bin_pad = (4 - bin_len % 4) % 4;
    size_t total = 12 + 8 + json_len + json_pad + (bin_len ? 8 + bin_len + bin_pad : 0);
    if (total > UINT32_MAX)
        return -1;
    uint8_t head[20];
    put_u32(head, GLB_MAGIC);
    put_u32(head + 4, GLB_VERSION);
    put_u32(head + 8, (uint32_t)total);
    put_u32(head + 12, (uint32_t)(json_len + json_pad));
    put_u32(head + 16, CHUNK_JSON);
    int ok = fwrite(head, 1, 20, f) == 20 && fwrite(json, 1, json_len, f) == json_len &&
             fwrite(spaces, 1, json_pad, f) == json_pad;
    if (ok && bin_len) {
        put_u32(head, (uint32_t)(bin_len + bin_pad));
        put_u32(head + 4, CHUNK_BIN);
        ok = fwrite(head, 1, 8, f) == 8 && fwrite(bin, 1, bin_len, f) == bin_len &&
             fwrite(zeros, 1, bin_pad, f) == bin_pad;
    }
    return ok ? 0 : -1;
}

int glb_write(glb_t *g, const char *path, char *err, size_t errlen)
{
    if (g->bin_len) {
        json_t *buffers = json_pack("[{s:I}]", "byteLength", (json_int_t)g->bin_len);
        if (!buffers || json_object_set_new(g->doc, "buffers", buffers) != 0) {
            snprintf(err, errlen, "out of memory");
            return -1;
        }
    }
    char *json = json_dumps(g->doc, JSON_COMPACT | JSON_REAL_PRECISION(9));
    if (!json) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    atomic_file af;
    int rc = -1;
    if (atomic_file_open(&af, path) == 0) {
        if (write_chunks(af.fp, json, strlen(json), g->bin, g->bin_len) == 0)
            rc = atomic_file_commit(&af);
        else
            atomic_file_abort(&af);
    }
    if (rc != 0)
        snprintf(err, errlen, "cannot write %s: %s", path, errno ? strerror(errno) : "file too large");
    free(json);
    return rc;
}
