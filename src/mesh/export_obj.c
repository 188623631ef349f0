/* Wavefront OBJ and its material library. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "celadon/mesh.h"
#include "mesh/format_float.h"

static int fail(char *err, size_t errlen, const char *path, atomic_file *af)
{
    snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno ? errno : EIO));
    if (af)
        atomic_file_abort(af);
    return -1;
}

/* Appends "tag x y z...\n" (count floats at %.<prec>g) to the line buffer. */
static char *put_floats(char *o, const char *tag, const float *v, int count, int prec)
{
    size_t tl = strlen(tag);
    memcpy(o, tag, tl);
    o += tl;
    for (int k = 0; k < count; k++) {
        *o++ = ' ';
        o += format_float_g(o, v[k], prec);
    }
    *o++ = '\n';
    return o;
}

int mesh_write_obj(const char *path, const mesh_t *m, const char *mtl_filename, char *err, size_t errlen)
{
    atomic_file af;
    errno = 0;
    if (atomic_file_open(&af, path) != 0)
        return fail(err, errlen, path, NULL);
    /* Lines are formatted into a block (format_float_g, byte-identical to
     * "%.7g"/"%.6g" and ~10x faster than fprintf) and written in blocks. */
    enum { BLOCK = 1 << 20, LINE_MAX_BYTES = 128 };
    char *buf = malloc(BLOCK);
    if (!buf)
        return fail(err, errlen, path, &af);
    FILE *f = af.fp;
    fprintf(f, "# celadon surface of revolution: %d vertices, %d triangles\n", m->n_verts, m->n_tris);
    if (mtl_filename)
        fprintf(f, "mtllib %s\n", mtl_filename);
    char *o = buf;
    int ok = 1;
#define FLUSH_IF_FULL()                                                                                            \
    if (o - buf > BLOCK - LINE_MAX_BYTES) {                                                                         \
        ok &= fwrite(buf, 1, (size_t)(o - buf), f) == (size_t)(o - buf);                                            \
        o = buf;                                                                                                   \
    }
    for (int i = 0; i < m->n_verts; i++) {
        o = put_floats(o, "v", m->pos + 3 * (size_t)i, 3, 7);
        FLUSH_IF_FULL()
    }
    for (int i = 0; i < m->n_verts; i++) {
        o = put_floats(o, "vt", m->uv + 2 * (size_t)i, 2, 7);
        FLUSH_IF_FULL()
    }
    for (int i = 0; i < m->n_verts; i++) {
        o = put_floats(o, "vn", m->nrm + 3 * (size_t)i, 3, 6);
        FLUSH_IF_FULL()
    }
    if (mtl_filename) {
        memcpy(o, "usemtl celadon\n", 15);
        o += 15;
    }
    for (int t = 0; t < m->n_tris; t++) {
        const uint32_t *v = m->tri + 3 * (size_t)t;
        *o++ = 'f';
        for (int k = 0; k < 3; k++) {
            char idx[10];
            int n = format_uint(idx, v[k] + 1u);
            *o++ = ' ';
            for (int r = 0; r < 3; r++) { /* v/vt/vn share the index */
                memcpy(o, idx, (size_t)n);
                o += n;
                *o++ = r < 2 ? '/' : ' ';
            }
            o--;
        }
        *o++ = '\n';
        FLUSH_IF_FULL()
    }
#undef FLUSH_IF_FULL
    ok &= fwrite(buf, 1, (size_t)(o - buf), f) == (size_t)(o - buf);
    free(buf);
    if (!ok)
        return fail(err, errlen, path, &af);
    return atomic_file_commit(&af) == 0 ? 0 : fail(err, errlen, path, NULL);
}

int mesh_write_mtl(const char *path, const char *texture_filename, char *err, size_t errlen)
{
    atomic_file af;
    errno = 0;
    if (atomic_file_open(&af, path) != 0)
        return fail(err, errlen, path, NULL);
    fprintf(af.fp,
            "# celadon material: the photograph's texture, diffuse\n"
            "newmtl celadon\n"
            "Ka 0 0 0\nKd 1 1 1\nKs 0 0 0\nd 1\nillum 1\n"
            "map_Kd %s\n",
            texture_filename);
    if (atomic_file_commit(&af) != 0)
        return fail(err, errlen, path, NULL);
    return 0;
}
