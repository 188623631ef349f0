/* Wavefront OBJ and its material library. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/atomic_file.h"
#include "celadon/mesh.h"

static int fail(char *err, size_t errlen, const char *path, atomic_file *af)
{
    snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno ? errno : EIO));
    if (af)
        atomic_file_abort(af);
    return -1;
}

int mesh_write_obj(const char *path, const mesh_t *m, const char *mtl_filename, char *err, size_t errlen)
{
    atomic_file af;
    errno = 0;
    if (atomic_file_open(&af, path) != 0)
        return fail(err, errlen, path, NULL);
    /* A large stdio buffer: the file is a few million short lines. */
    char *buf = malloc(1 << 20);
    if (buf)
        setvbuf(af.fp, buf, _IOFBF, 1 << 20);
    FILE *f = af.fp;
    fprintf(f, "# celadon surface of revolution: %d vertices, %d triangles\n", m->n_verts, m->n_tris);
    if (mtl_filename)
        fprintf(f, "mtllib %s\n", mtl_filename);
    for (int i = 0; i < m->n_verts; i++) {
        const float *p = m->pos + 3 * (size_t)i;
        fprintf(f, "v %.7g %.7g %.7g\n", p[0], p[1], p[2]);
    }
    for (int i = 0; i < m->n_verts; i++) {
        const float *t = m->uv + 2 * (size_t)i;
        fprintf(f, "vt %.7g %.7g\n", t[0], t[1]);
    }
    for (int i = 0; i < m->n_verts; i++) {
        const float *n = m->nrm + 3 * (size_t)i;
        fprintf(f, "vn %.6g %.6g %.6g\n", n[0], n[1], n[2]);
    }
    if (mtl_filename)
        fputs("usemtl celadon\n", f);
    for (int t = 0; t < m->n_tris; t++) {
        const uint32_t *v = m->tri + 3 * (size_t)t;
        unsigned a = v[0] + 1u, b = v[1] + 1u, c = v[2] + 1u;
        fprintf(f, "f %u/%u/%u %u/%u/%u %u/%u/%u\n", a, a, a, b, b, b, c, c, c);
    }
    int rc = atomic_file_commit(&af) == 0 ? 0 : fail(err, errlen, path, NULL);
    free(buf); /* only after fclose, which still used it */
    return rc;
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
