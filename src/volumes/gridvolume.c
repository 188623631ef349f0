/* The `gridvolume` volume: a voxel grid read from Mitsuba's binary .vol
 * file (`filename`): "VOL", version byte 3, then little-endian int32
 * encoding (1: float32, the only one read here), int32 xres, yres, zres,
 * int32 channels (1 or 3), six float32 of a bounding box (min, max) and the
 * float32 values, x fastest, then y, then z. The grid fills the unit cube,
 * placed by `to_world`; with `use_grid_bbox` (false) the file's box is
 * placed by it instead. `filter_type` trilinear (default) or nearest,
 * `wrap_mode` clamp (default), repeat or mirror; `raw` is accepted and
 * changes nothing in RGB. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "volumes/volume_impl.h"

enum { HEADER_BYTES = 48 };

static int32_t le32(const unsigned char *b)
{
    return (int32_t)((uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24);
}

static float lef32(const unsigned char *b)
{
    uint32_t u = (uint32_t)le32(b);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* The grid of the .vol file in buf (len bytes) into v and the file's box:
 * 0, or -1 with the problem in why. */
static int parse_vol(const unsigned char *buf, size_t len, volume_t *v, vec3 *lo, vec3 *hi, char *why, size_t whylen)
{
    if (len < HEADER_BYTES || memcmp(buf, "VOL", 3) != 0 || buf[3] != 3) {
        snprintf(why, whylen, "not a Mitsuba .vol file of version 3");
        return -1;
    }
    if (le32(buf + 4) != 1) {
        snprintf(why, whylen, "encoding %d is not float32 (1)", le32(buf + 4));
        return -1;
    }
    int32_t nx = le32(buf + 8), ny = le32(buf + 12), nz = le32(buf + 16), ch = le32(buf + 20);
    if (nx < 1 || ny < 1 || nz < 1 || (ch != 1 && ch != 3)) {
        snprintf(why, whylen, "bad size %dx%dx%d with %d channels (1 or 3)", nx, ny, nz, ch);
        return -1;
    }
    size_t count = (size_t)nx * (size_t)ny * (size_t)nz * (size_t)ch;
    if (count / (size_t)ch / (size_t)nz / (size_t)ny != (size_t)nx || (len - HEADER_BYTES) / 4 != count) {
        snprintf(why, whylen, "holds %zu bytes of values, not 4 x %dx%dx%d x %d", len - HEADER_BYTES, nx, ny, nz, ch);
        return -1;
    }
    *lo = v3(lef32(buf + 24), lef32(buf + 28), lef32(buf + 32));
    *hi = v3(lef32(buf + 36), lef32(buf + 40), lef32(buf + 44));
    v->grid = malloc(count * sizeof *v->grid);
    if (!v->grid) {
        snprintf(why, whylen, "out of memory");
        return -1;
    }
    v->nx = nx, v->ny = ny, v->nz = nz, v->channels = ch;
    v->max = 0.0;
    for (size_t i = 0; i < count; i++) {
        float f = lef32(buf + HEADER_BYTES + 4 * i);
        if (!(f >= 0.0f) || !isfinite(f)) {
            snprintf(why, whylen, "value %zu is %g: values must be finite and not negative", i, (double)f);
            return -1;
        }
        v->grid[i] = f;
        v->max = fmax(v->max, f);
    }
    return 0;
}

static volume_t *gridvolume_create(scene_obj *o, char *err, size_t errlen)
{
    const char *path = scene_obj_string(o, "filename", "");
    const char *wrap = scene_obj_string(o, "wrap_mode", "clamp");
    bool nearest = strcmp(scene_obj_string(o, "filter_type", "trilinear"), "nearest") == 0;
    bool grid_box = scene_obj_bool(o, "use_grid_bbox", false);
    (void)scene_obj_bool(o, "raw", false);
    transform4 to_world = scene_obj_transform(o, "to_world");
    volume_t *v = volume_alloc(o, err, errlen);
    if (!v)
        return NULL;
    v->nearest = nearest;
    v->wrap = strcmp(wrap, "repeat") == 0 ? VOLUME_REPEAT : strcmp(wrap, "mirror") == 0 ? VOLUME_MIRROR : VOLUME_CLAMP;
    char *buf = NULL, why[256];
    size_t len = 0;
    vec3 lo, hi;
    if (input_read_all(path, INPUT_MAX_DATA_BYTES, &buf, &len, why, sizeof why) != 0 ||
        parse_vol((const unsigned char *)buf, len, v, &lo, &hi, why, sizeof why) != 0) {
        scene_obj_error(o, err, errlen, "%s: %s", path, why);
        free(buf);
        volume_destroy(v);
        return NULL;
    }
    free(buf);
    if (grid_box) {
        vec3 size = v3_sub(hi, lo);
        if (!(size.x > 0.0 && size.y > 0.0 && size.z > 0.0)) {
            scene_obj_error(o, err, errlen, "%s: the file's bounding box is empty (use_grid_bbox)", path);
            volume_destroy(v);
            return NULL;
        }
        transform4 t = transform_translate(lo), s = transform_scale(size), box = transform_compose(&t, &s);
        to_world = transform_compose(&to_world, &box);
    }
    v->bounded = true;
    v->to_local = transform_inverse(&to_world);
    return v;
}

static const scene_param_decl gridvolume_params[] = {
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    {"use_grid_bbox", PARAM_BOOL, 0, NULL},
    {"filter_type", PARAM_STRING, 0, "trilinear|nearest"},
    {"wrap_mode", PARAM_STRING, 0, "clamp|repeat|mirror"},
    {"raw", PARAM_BOOL, 0, NULL},
    {NULL, 0, 0, NULL},
};

const volume_plugin volume_gridvolume = {
    .decl = {.cls = SCENE_VOLUME, .type = "gridvolume", .params = gridvolume_params},
    .create = gridvolume_create,
};
