/* Binary little-endian PLY, written byte by byte in little-endian order so the
 * file is the same on any host. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "celadon/mesh.h"

static unsigned char *put_u32le(unsigned char *o, uint32_t v)
{
    o[0] = (unsigned char)v, o[1] = (unsigned char)(v >> 8), o[2] = (unsigned char)(v >> 16),
    o[3] = (unsigned char)(v >> 24);
    return o + 4;
}

static unsigned char *put_f32le(unsigned char *o, float f)
{
    uint32_t v;
    memcpy(&v, &f, sizeof v);
    return put_u32le(o, v);
}

enum { VERT_BYTES = 8 * 4, FACE_BYTES = 1 + 3 * 4, CHUNK = 4096 };

int mesh_write_ply(const char *path, const mesh_t *m, char *err, size_t errlen)
{
    atomic_file af;
    errno = 0;
    unsigned char *buf = malloc((size_t)CHUNK * VERT_BYTES);
    if (!buf || atomic_file_open(&af, path) != 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno ? errno : ENOMEM));
        free(buf);
        return -1;
    }
    FILE *f = af.fp;
    fprintf(f,
            "ply\nformat binary_little_endian 1.0\ncomment celadon surface of revolution\n"
            "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\nproperty float nz\nproperty float s\nproperty float t\n"
            "element face %d\nproperty list uchar uint vertex_indices\nend_header\n",
            m->n_verts, m->n_tris);
    /* Vertices and faces go out in chunks of CHUNK records through one buffer. */
    for (int i0 = 0; i0 < m->n_verts; i0 += CHUNK) {
        int i1 = i0 + CHUNK < m->n_verts ? i0 + CHUNK : m->n_verts;
        unsigned char *o = buf;
        for (int i = i0; i < i1; i++) {
            const float *p = m->pos + 3 * (size_t)i, *n = m->nrm + 3 * (size_t)i, *t = m->uv + 2 * (size_t)i;
            o = put_f32le(put_f32le(put_f32le(o, p[0]), p[1]), p[2]);
            o = put_f32le(put_f32le(put_f32le(o, n[0]), n[1]), n[2]);
            o = put_f32le(put_f32le(o, t[0]), t[1]);
        }
        fwrite(buf, 1, (size_t)(o - buf), f);
    }
    for (int t0 = 0; t0 < m->n_tris; t0 += CHUNK) {
        int t1 = t0 + CHUNK < m->n_tris ? t0 + CHUNK : m->n_tris;
        unsigned char *o = buf;
        for (int t = t0; t < t1; t++) {
            const uint32_t *v = m->tri + 3 * (size_t)t;
            *o++ = 3;
            o = put_u32le(put_u32le(put_u32le(o, v[0]), v[1]), v[2]);
        }
        fwrite(buf, 1, (size_t)(o - buf), f);
    }
    free(buf);
    if (atomic_file_commit(&af) != 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno ? errno : EIO));
        return -1;
    }
    return 0;
}
