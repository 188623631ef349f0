/* Ray queries against the whole scene through accel: one Embree scene, one
 * BVH over every shape. Meshes (and SORs under --geometry mesh:N) are Embree
 * triangles, with the hit refined in double; sphere, disk, cylinder and the
 * analytic SOR are Embree user geometries solved exactly in double. */
#include <stdio.h>

#include "render/scene_impl.h"

int scene_trace_build(struct scene *s, char *err, size_t errlen)
{
    char why[512];
    /* Robust: the watertight triangle test, so no path slips between two
     * triangles of a closed mesh. */
    s->accel = accel_create(ACCEL_BUILD_FAST | ACCEL_BUILD_ROBUST, why, sizeof why);
    if (!s->accel) {
        snprintf(err, errlen, "cannot start Embree: %s", why);
        return -1;
    }
    for (int i = 0; i < s->nshapes; i++) {
        const shape_t *sh = &s->shapes[i];
        s->straight_shadows |= (bsdf_flags(sh->bsdf) & BSDF_STRAIGHT_TRANSMISSION) != 0;
        unsigned id = sh->is_mesh ? shape_mesh_add(sh, s->accel, why, sizeof why)
                                  : sh->ops->add(sh->data, s->accel, &sh->to_world, why, sizeof why);
        /* accel numbers geometries in the order added: id = shape index. */
        if (id != (unsigned)i) {
            snprintf(err, errlen, "%s:%d: %s", sh->file, sh->line, why);
            return -1;
        }
    }
    if (accel_commit(s->accel, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s", why);
        return -1;
    }
    return 0;
}

void scene_trace_free(struct scene *s) { accel_destroy(s->accel); }

bool scene_intersect(const struct scene *s, const ray3 *r, double tmin, double tmax, surface_hit *hit)
{
    accel_hit ah;
    if (!accel_intersect(s->accel, r, tmin, tmax, &ah))
        return false;
    const shape_t *sh = &s->shapes[ah.geom_id];
    if (sh->is_mesh) {
        shape_mesh_finish(sh, (int)ah.prim, ah.param[0], ah.param[1], ah.t, hit);
    } else {
        shape_local_hit lh;
        sh->ops->local_hit(sh->data, &ah, &lh);
        shape_analytic_finish(sh, &lh, hit);
    }
    hit->shape = (int)ah.geom_id;
    return true;
}

bool scene_occluded(const struct scene *s, const ray3 *r, double tmin, double tmax)
{
    return accel_occluded(s->accel, r, tmin, tmax) != 0;
}
