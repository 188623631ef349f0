/* Triangle meshes of a surface of revolution, and their exporters. */
#ifndef CELADON_MESH_H
#define CELADON_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "celadon/bspline.h"

/* Vertex arrays are float (what Embree and the file formats take). pos has one
 * float of padding after the last vertex, so Embree may share it directly
 * (rtcSetSharedGeometryBuffer reads 16 bytes at the last float3). */
typedef struct {
    int n_verts, n_tris;
    float *pos;    /* 3 per vertex, object space (Y up, base at y = 0) */
    float *nrm;    /* 3 per vertex, unit, outward */
    float *uv;     /* 2 per vertex, texture convention of docs/conventions.md */
    uint32_t *tri; /* 3 per triangle, counter-clockwise seen from outside */
} mesh_t;

enum { MESH_CAP_BASE = 1u, MESH_CAP_MOUTH = 2u };

/* Revolves the profile into segments angular steps. Rings are placed at the
 * profile parameters u_rings[0..n_rings-1] (strictly increasing, inside the
 * curve's domain: normally the curvature domains of profile.json, from 0 to 1),
 * or, when u_rings is NULL, at n_rings uniformly spaced parameters from the
 * first knot to the last. The profile is scaled so the rim (the end of the
 * curve, h(1)) is at y = height.
 *
 * Layout (what the counts are, for any segments >= 3 and n_rings >= 2):
 *   wall: vertex ring*segments + j at phi_j = 2 pi j / segments; no seam column
 *         (the texture u of docs/conventions.md is mirror-symmetric, u(0) = u(2 pi) = 1);
 *         2 * segments * (n_rings - 1) triangles.
 *   each cap asked for in caps (MESH_CAP_*): its own copy of the end ring
 *         (normal -Y for the base, +Y for the mouth, so the crease stays
 *         sharp), then one centre vertex per segment (u = the middle of that
 *         segment's u, so a cap's texture follows the angle as the analytic
 *         cap's does), segments triangles. A cap whose end ring lies on the
 *         axis (r = 0) would have no area and is left out.
 * Returns 0, or -1 on bad arguments (including a profile whose rim is not
 * above h = 0, or that would not fit in float range once scaled) or
 * allocation failure (out zeroed). */
int mesh_revolve(const bspline_t *profile, const double *u_rings, int n_rings, double height, int segments,
                 unsigned caps, mesh_t *out);
void mesh_free(mesh_t *m);

/* Turns the mesh into Z-up coordinates for tools that expect them (Blender,
 * 3ds Max): (x, y, z) -> (x, -z, y) for positions and normals, a rotation
 * of +90 degrees about x; the axis becomes +z and the front meridian, which
 * faced the camera along +z, faces -y (Blender's front view). */
void mesh_to_z_up(mesh_t *m);

/* Exporters. All write atomically (whole file or nothing) and return 0, or -1
 * with a one-line reason in err. */

/* Wavefront OBJ: v, vt, vn, then f v/vt/vn (1-based). mtl_filename (may be
 * NULL) is written as "mtllib" with "usemtl celadon". */
int mesh_write_obj(const char *path, const mesh_t *m, const char *mtl_filename, char *err, size_t errlen);
/* A material library with one material "celadon" whose map_Kd is texture_filename. */
int mesh_write_mtl(const char *path, const char *texture_filename, char *err, size_t errlen);
/* Binary little-endian PLY: vertex x y z nx ny nz s t (float), face
 * vertex_indices (uchar count, uint index). */
int mesh_write_ply(const char *path, const mesh_t *m, char *err, size_t errlen);

#endif
