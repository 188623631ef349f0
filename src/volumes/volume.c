/* What every volume shares: evaluation (a constant, or a grid's trilinear or
 * nearest lookup under its wrap mode), building from a parameter, lifetime. */
#include <math.h>
#include <stdlib.h>

#include "volumes/volume_impl.h"

/* Index i wrapped into [0, n). */
static int wrap_index(int i, int n, volume_wrap w)
{
    switch (w) {
    case VOLUME_REPEAT: i %= n; return i < 0 ? i + n : i;
    case VOLUME_MIRROR: {
        int period = 2 * n;
        i %= period;
        if (i < 0)
            i += period;
        return i < n ? i : period - 1 - i;
    }
    default: return i < 0 ? 0 : (i >= n ? n - 1 : i);
    }
}

static rgb voxel(const volume_t *v, int i, int j, int k)
{
    i = wrap_index(i, v->nx, v->wrap);
    j = wrap_index(j, v->ny, v->wrap);
    k = wrap_index(k, v->nz, v->wrap);
    const float *c = v->grid + (((size_t)k * (size_t)v->ny + (size_t)j) * (size_t)v->nx + (size_t)i) * (size_t)v->channels;
    return v->channels == 1 ? rgb_gray(c[0]) : (rgb){c[0], c[1], c[2]};
}

rgb volume_eval(const volume_t *v, vec3 p)
{
    if (!v->grid)
        return v->value;
    vec3 q = transform_point(&v->to_local, p);
    /* voxel coordinates with centres on the integers */
    double x = q.x * v->nx - 0.5, y = q.y * v->ny - 0.5, z = q.z * v->nz - 0.5;
    if (!isfinite(x) || !isfinite(y) || !isfinite(z))
        return rgb_gray(0.0);
    x = fmax(-1e9, fmin(1e9, x)), y = fmax(-1e9, fmin(1e9, y)), z = fmax(-1e9, fmin(1e9, z));
    if (v->nearest)
        return voxel(v, (int)lround(x), (int)lround(y), (int)lround(z));
    int i = (int)floor(x), j = (int)floor(y), k = (int)floor(z);
    double fx = x - i, fy = y - j, fz = z - k;
    rgb acc = rgb_gray(0.0);
    for (int c = 0; c < 8; c++) {
        int dx = c & 1, dy = (c >> 1) & 1, dz = c >> 2;
        double w = (dx ? fx : 1.0 - fx) * (dy ? fy : 1.0 - fy) * (dz ? fz : 1.0 - fz);
        acc = rgb_add(acc, rgb_scale(voxel(v, i + dx, j + dy, k + dz), w));
    }
    return acc;
}

double volume_max(const volume_t *v)
{
    return v->grid ? v->max : rgb_max(v->value);
}

bool volume_contains(const volume_t *v, vec3 p)
{
    if (!v->bounded)
        return true;
    vec3 q = transform_point(&v->to_local, p);
    return q.x >= 0.0 && q.x <= 1.0 && q.y >= 0.0 && q.y <= 1.0 && q.z >= 0.0 && q.z <= 1.0;
}

bool volume_is_constant(const volume_t *v)
{
    return !v->grid;
}

void volume_destroy(volume_t *v)
{
    if (!v)
        return;
    free(v->grid);
    free(v);
}

volume_t *volume_alloc(const scene_obj *o, char *err, size_t errlen)
{
    volume_t *v = calloc(1, sizeof *v);
    if (!v)
        scene_obj_error(o, err, errlen, "out of memory");
    return v;
}

volume_t *volume_of_param(scene_obj *o, const char *name, rgb def, char *err, size_t errlen)
{
    scene_prop *p = scene_obj_prop(o, name);
    if (p && p->type == SCENE_OBJECT) {
        scene_obj *vo = scene_obj_texture(o, name);
        const volume_plugin *plugin = vo->cls == SCENE_VOLUME ? volume_plugin_find(vo->type) : NULL;
        if (!plugin) {
            scene_obj_error(o, err, errlen, "%s must be a <volume> or a color", name);
            return NULL;
        }
        return plugin->create(vo, err, errlen);
    }
    scene_rgb c = scene_obj_rgb(o, name, (scene_rgb){def.r, def.g, def.b});
    if (!(c.r >= 0.0 && c.g >= 0.0 && c.b >= 0.0 && isfinite(c.r + c.g + c.b))) {
        scene_obj_error(o, err, errlen, "%s must be finite and not negative", name);
        return NULL;
    }
    volume_t *v = volume_alloc(o, err, errlen);
    if (v)
        v->value = (rgb){c.r, c.g, c.b};
    return v;
}
