/* Triangle meshes of a surface of revolution, and their exporters. */
#ifndef CELADON_MESH_H
#define CELADON_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "celadon/bspline.h"

/* Vertex arrays are float (what Embree and the file formats take). */
typedef struct {
    int n_verts, n_tris;
    float *pos;    /* 3 per vertex, object space (Y up, base at y = 0) */
    float *nrm;    /* 3 per vertex, unit, outward */
    float *uv;     /* 2 per vertex, DESIGN.md texture convention */
    uint32_t *tri; /* 3 per triangle, counter-clockwise seen from outside */
} mesh_t;

enum { MESH_CAP_BASE = 1u, MESH_CAP_MOUTH = 2u };

/* Revolves the profile into segments angular steps. Rings are placed at the
 * profile parameters u_rings[0..n_rings-1] (increasing, from 0 to 1: the
 * curvature domains of profile.json), scaled so the rim is at y = height.
 * Returns 0, or -1 on bad arguments or allocation failure. */
int mesh_revolve(const bspline_t *profile, const double *u_rings, int n_rings, double height, int segments,
                 unsigned caps, mesh_t *out);
void mesh_free(mesh_t *m);

#endif
