/* What the texture plugins share (texture.c): the texture record they fill,
 * the uv transform and the to_uv parameter. Private to src/textures/. */
#ifndef CELADON_TEXTURE_IMPL_H
#define CELADON_TEXTURE_IMPL_H

#include "textures/textures.h"

/* uv' = (m[0][0] u + m[0][1] v + m[0][2], m[1][0] u + m[1][1] v + m[1][2]):
 * the upper 2x3 block of Mitsuba's 3x3 to_uv matrix. */
typedef struct {
    double m[2][3];
} uv_transform;

typedef struct {
    /* The value at uv, already moved by the texture's to_uv. */
    rgb (*lookup)(const texture_t *t, vec2 uv);
    /* Frees what data points to (not data itself); may be NULL. */
    void (*release)(void *data);
    /* The gradient of the value's luminance by the (moved) uv; NULL: zero. */
    vec2 (*gradient_1)(const texture_t *t, vec2 uv);
    /* For a texture of the surface point rather than of uv (mesh_attribute):
     * the value at at (no to_uv); NULL: lookup at the moved uv. */
    rgb (*lookup_at)(const texture_t *t, const texture_point *at);
    /* The value read as a scalar (Mitsuba's eval_1) at the moved uv, where
     * it is not the luminance of lookup; NULL: that luminance. */
    double (*lookup_1)(const texture_t *t, vec2 uv);
} texture_ops;

struct texture {
    const texture_ops *ops;
    uv_transform to_uv;
    rgb mean;
    int width, height; /* resolution: 1 x 1 unless the plugin says */
    void *data;        /* the plugin's, allocated with the texture */
};

/* One allocation holding the texture and data_size zeroed bytes of plugin
 * data; NULL when out of memory. */
texture_t *texture_alloc(const texture_ops *ops, size_t data_size);

/* The to_uv parameter of o (identity when absent): the 2D part of the 4x4,
 * scale and rotation from the upper-left 2x2, translation from the last
 * column. */
uv_transform texture_to_uv_param(scene_obj *o);

#endif
