/* Mitsuba's `serialized` shape: a triangle mesh from a .serialized file,
 * versions 3 and 4 of the format (Mitsuba 0.4 to 3.6 write them). A file
 * holds one or more meshes, each a little-endian header (uint16 0x041C,
 * uint16 version) followed by a zlib stream: uint32 flags (0x1 normals, 0x2
 * texture coordinates, 0x8 vertex colours, 0x2000 double precision), the
 * mesh's name as a NUL-terminated string (version 4), uint64 vertex and
 * triangle counts, the positions, normals, uvs and colours of the vertices,
 * and uint32 vertex indices, 3 per triangle. The file ends with the offset
 * of every mesh (uint64; uint32 in version 3) and their count (uint32).
 * The uvs are used as stored (Mitsuba flips them for OBJ only). */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "core/core.h"
#include "shapes/shape_impl.h"

enum {
    SERIALIZED_MAGIC = 0x041C,
    SERIALIZED_NORMALS = 0x0001,
    SERIALIZED_TEXCOORDS = 0x0002,
    SERIALIZED_COLORS = 0x0008,
    SERIALIZED_DOUBLE = 0x2000,
    SERIALIZED_MAX_ELEMS = 1 << 28, /* vertices or triangles: the meshes' int indices, with room */
    DEFLATE_MAX_RATIO = 1032,       /* zlib's bound on what one byte of a deflate stream expands to */
};

typedef struct {
    unsigned char *file;
    size_t size;
    z_stream z;
    int z_open;
} serialized_reader;

static uint64_t le(const unsigned char *b, int n)
{
    uint64_t u = 0;
    for (int i = n - 1; i >= 0; i--)
        u = (u << 8) | b[i];
    return u;
}

static int read_file(const char *path, serialized_reader *r, char *why, size_t whylen)
{
    char *buf, reason[256];
    size_t len;
    if (input_read_all(path, INPUT_MAX_DATA_BYTES, &buf, &len, reason, sizeof reason) != 0) {
        snprintf(why, whylen, "cannot read '%s': %s", path, reason);
        return -1;
    }
    r->file = (unsigned char *)buf;
    r->size = len;
    return 0;
}

/* The file offset of mesh index, from the dictionary at the end. */
static int mesh_offset(const serialized_reader *r, int version, long long index, size_t *off, char *why,
                       size_t whylen)
{
    if (index == 0) {
        *off = 0;
        return 0;
    }
    size_t entry = version >= 4 ? 8 : 4;
    uint64_t count = r->size >= 4 ? le(r->file + r->size - 4, 4) : 0;
    if (index < 0 || (uint64_t)index >= count || count * entry + 4 > r->size) {
        snprintf(why, whylen, "shape_index %lld is out of range (the file holds %llu meshes)", index,
                 (unsigned long long)count);
        return -1;
    }
    const unsigned char *at = r->file + r->size - 4 - entry * (count - (uint64_t)index);
    *off = (size_t)le(at, (int)entry);
    return 0;
}

/* n more bytes of the mesh's zlib stream into dst (NULL: skipped). */
static int zread(serialized_reader *r, void *dst, size_t n)
{
    unsigned char scratch[4096];
    while (n > 0) {
        size_t chunk = dst ? n : (n < sizeof scratch ? n : sizeof scratch);
        r->z.next_out = dst ? dst : scratch;
        r->z.avail_out = (uInt)(chunk < (1u << 30) ? chunk : (1u << 30));
        uInt want = r->z.avail_out;
        int st = inflate(&r->z, Z_NO_FLUSH);
        uInt got = want - r->z.avail_out;
        if (got == 0 && st != Z_OK)
            return -1;
        if (dst)
            dst = (unsigned char *)dst + got;
        n -= got;
    }
    return 0;
}

/* count records of dim reals (float or double) into out (NULL: skipped). */
static int read_reals(serialized_reader *r, int dbl, size_t count, int dim, float *out)
{
    size_t n = count * (size_t)dim, size = dbl ? 8 : 4;
    unsigned char buf[8 * 3 * 256];
    for (size_t i = 0; i < n;) {
        size_t k = n - i < 3 * 256 ? n - i : 3 * 256;
        if (zread(r, buf, k * size) != 0)
            return -1;
        for (size_t j = 0; j < k && out; j++, i++) {
            uint64_t u = le(buf + j * size, (int)size);
            double v;
            if (dbl) {
                memcpy(&v, &u, 8);
            } else {
                uint32_t w = (uint32_t)u;
                float f;
                memcpy(&f, &w, 4);
                v = f;
            }
            if (!isfinite(v))
                return -2;
            out[i] = (float)v;
        }
        if (!out)
            i += k;
    }
    return 0;
}

static int read_mesh(serialized_reader *r, int version, shape_mesh_data *m, char *why, size_t whylen)
{
    unsigned char b[16];
    if (zread(r, b, 4) != 0)
        goto truncated;
    uint32_t flags = (uint32_t)le(b, 4);
    for (int i = 0; version >= 4 && i < 4096; i++) { /* the mesh's name */
        if (zread(r, b, 1) != 0)
            goto truncated;
        if (b[0] == 0)
            break;
    }
    if (zread(r, b, 16) != 0)
        goto truncated;
    uint64_t nv = le(b, 8), nt = le(b + 8, 8);
    if (nv == 0 || nt == 0 || nv > SERIALIZED_MAX_ELEMS || nt > SERIALIZED_MAX_ELEMS) {
        snprintf(why, whylen, "the mesh has %llu vertices and %llu triangles (1 to %d each supported)",
                 (unsigned long long)nv, (unsigned long long)nt, SERIALIZED_MAX_ELEMS);
        return -1;
    }
    /* What the counts claim must fit in the stream's bytes, so that a small
     * file cannot make us allocate gigabytes before it runs out. */
    size_t real = flags & SERIALIZED_DOUBLE ? 8 : 4;
    uint64_t per_vertex = real * (3 + (flags & SERIALIZED_NORMALS ? 3 : 0) + (flags & SERIALIZED_TEXCOORDS ? 2 : 0) +
                                  (flags & SERIALIZED_COLORS ? 3 : 0));
    uint64_t claimed = nv * per_vertex + nt * 3 * sizeof(unsigned);
    if (claimed / DEFLATE_MAX_RATIO > r->z.avail_in + (uint64_t)r->z.total_in) {
        snprintf(why, whylen,
                 "the mesh claims %llu vertices and %llu triangles, more than its %llu compressed bytes can hold",
                 (unsigned long long)nv, (unsigned long long)nt,
                 (unsigned long long)(r->z.avail_in + (uint64_t)r->z.total_in));
        return -1;
    }
    if (shape_mesh_alloc(m, (int)nv, (int)nt) != 0) {
        snprintf(why, whylen, "out of memory");
        return -1;
    }
    int dbl = real == 8, rc = read_reals(r, dbl, nv, 3, m->pos);
    if (rc == 0 && (flags & SERIALIZED_NORMALS))
        rc = read_reals(r, dbl, nv, 3, m->nrm);
    if (rc == 0 && (flags & SERIALIZED_TEXCOORDS))
        rc = read_reals(r, dbl, nv, 2, m->uv);
    if (rc == 0 && (flags & SERIALIZED_COLORS))
        rc = read_reals(r, dbl, nv, 3, NULL);
    if (rc == -2) {
        snprintf(why, whylen, "a vertex value is not a finite number");
        return -1;
    }
    if (rc != 0 || zread(r, m->tri, sizeof(unsigned) * 3 * (size_t)nt) != 0)
        goto truncated;
    for (size_t i = 0; i < 3 * (size_t)nt; i++) {
        m->tri[i] = (unsigned)le((const unsigned char *)&m->tri[i], 4);
        if (m->tri[i] >= nv) {
            snprintf(why, whylen, "triangle %zu names vertex %u of %llu", i / 3, m->tri[i], (unsigned long long)nv);
            return -1;
        }
    }
    if (!(flags & SERIALIZED_NORMALS)) {
        free(m->nrm);
        m->nrm = NULL;
    }
    if (!(flags & SERIALIZED_TEXCOORDS)) {
        free(m->uv);
        m->uv = NULL;
    }
    return 0;
truncated:
    snprintf(why, whylen, "the mesh data is truncated or corrupt (%s)", r->z.msg ? r->z.msg : "zlib stream ended early");
    return -1;
}

/* Reads mesh index of the file at path into m: 0, or -1 with why. */
static int serialized_read(const char *path, long long index, shape_mesh_data *m, char *why, size_t whylen)
{
    serialized_reader r = {0};
    if (read_file(path, &r, why, whylen) != 0)
        return -1;
    int rc = -1;
    size_t off = 0;
    int version = r.size >= 4 ? (int)le(r.file + 2, 2) : 0;
    if (r.size < 4 || le(r.file, 2) != SERIALIZED_MAGIC)
        snprintf(why, whylen, "not a Mitsuba .serialized file");
    else if (version != 3 && version != 4)
        snprintf(why, whylen, "serialized format version %d is not supported (versions 3 and 4 are)", version);
    else if (mesh_offset(&r, version, index, &off, why, whylen) != 0)
        ; /* why says it */
    else if (off > r.size - 4) /* not off + 4 > size: off is the file's to choose, up to 2^64 - 1 */
        snprintf(why, whylen, "the offset of mesh %lld is past the end of the file", index);
    else if (inflateInit(&r.z) != Z_OK)
        snprintf(why, whylen, "out of memory");
    else {
        r.z_open = 1;
        r.z.next_in = r.file + off + 4;
        r.z.avail_in = (uInt)(r.size - off - 4 < (1u << 31) ? r.size - off - 4 : (1u << 31));
        rc = read_mesh(&r, version, m, why, whylen);
    }
    if (r.z_open)
        inflateEnd(&r.z);
    free(r.file);
    if (rc != 0)
        shape_mesh_data_free(m);
    return rc;
}

static int serialized_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh,
                             char *err, size_t errlen)
{
    (void)opt, (void)to_world;
    char why[600] = "";
    const char *path = scene_obj_string(o, "filename", NULL);
    long long index = scene_obj_int(o, "shape_index", 0);
    int rc = serialized_read(path, index, &sh->mesh, why, sizeof why);
    return shape_mesh_from_file(o, rc, why, sh, err, errlen);
}

static const scene_param_decl serialized_params[] = {
    SHAPE_PARAMS_COMMON,
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"shape_index", PARAM_INT, 0, NULL},
    {"face_normals", PARAM_BOOL, 0, NULL},
    SHAPE_PARAMS_END,
};

const shape_plugin shape_serialized = {
    .decl = {.cls = SCENE_SHAPE, .type = "serialized", .params = serialized_params, .children = shape_children},
    .create = serialized_create,
};
