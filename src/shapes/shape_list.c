/* Ray queries against all of a scene's shapes through accel: one Embree
 * scene, one BVH over every shape. Meshes (and SORs under --geometry mesh:N)
 * are Embree triangles, with the hit refined in double; sphere, disk,
 * cylinder and the analytic SOR are Embree user geometries solved exactly in
 * double. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "shapes/shape_impl.h"

int shape_list_commit(shape_list *l, char *err, size_t errlen)
{
    char why[512];
    /* Robust: the watertight triangle test, so no path slips between two
     * triangles of a closed mesh. */
    l->accel = accel_create(ACCEL_BUILD_FAST | ACCEL_BUILD_ROBUST, why, sizeof why);
    if (!l->accel) {
        snprintf(err, errlen, "cannot start Embree: %s", why);
        return -1;
    }
    for (int i = 0; i < l->count; i++) {
        const shape_t *sh = &l->items[i];
        vec3 lo, hi;
        shape_world_bounds(sh, &lo, &hi);
        double reach = fmax(fmax(fmax(fabs(lo.x), fabs(lo.y)), fmax(fabs(lo.z), fabs(hi.x))), fmax(fabs(hi.y), fabs(hi.z)));
        if (!(reach <= SHAPE_MAX_COORD) || lo.x != lo.x || lo.y != lo.y || lo.z != lo.z) {
            snprintf(err, errlen, "%s:%d: the shape reaches %g from the origin (at most %g is traced)", sh->file,
                     sh->line, reach, SHAPE_MAX_COORD);
            return -1;
        }
        l->straight_shadows |= (bsdf_flags(sh->bsdf) & BSDF_STRAIGHT_TRANSMISSION) != 0;
        unsigned id = sh->is_mesh ? shape_mesh_add(sh, l->accel, why, sizeof why)
                                  : sh->ops->add(sh->data, l->accel, &sh->to_world, why, sizeof why);
        /* accel numbers geometries in the order added: id = shape index. */
        if (id != (unsigned)i) {
            snprintf(err, errlen, "%s:%d: %s", sh->file, sh->line, why);
            return -1;
        }
    }
    if (accel_commit(l->accel, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s", why);
        return -1;
    }
    return 0;
}

void shape_list_free(shape_list *l)
{
    accel_destroy(l->accel);
    for (int i = 0; i < l->count; i++)
        shape_free(&l->items[i]);
    free(l->items);
    *l = (shape_list){0};
}

bool shape_list_intersect(const shape_list *l, const ray3 *r, double tmin, double tmax, surface_hit *hit)
{
    accel_hit ah;
    if (!accel_intersect_refined(l->accel, r, tmin, tmax, &ah))
        return false;
    const shape_t *sh = &l->items[ah.geom_id];
    if (sh->is_mesh) {
        shape_mesh_finish(sh, (int)ah.prim, ah.param[0], ah.param[1], ah.t, hit);
    } else {
        shape_local_hit lh;
        sh->ops->local_hit(sh->data, &ah, &lh);
        shape_analytic_finish(sh, &lh, hit);
    }
    hit->shape = sh;
    return true;
}

bool shape_list_occluded(const shape_list *l, const ray3 *r, double tmin, double tmax)
{
    return accel_occluded(l->accel, r, tmin, tmax) != 0;
}
