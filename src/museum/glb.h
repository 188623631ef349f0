/* A binary glTF 2.0 (.glb) under construction: the JSON document (jansson)
 * and the one binary buffer it refers to, written as the two chunks of the
 * GLB container (glTF 2.0 specification, section "Binary glTF Layout").
 *
 * Every bufferView starts on a 4-byte boundary, so any accessor component
 * type is aligned; the JSON chunk is padded with spaces and the binary chunk
 * with zeros to a multiple of 4, as the container requires. */
#ifndef CELADON_MUSEUM_GLB_H
#define CELADON_MUSEUM_GLB_H

#include <jansson.h>
#include <stddef.h>
#include <stdint.h>

enum {
    GLB_BYTE = 5120,
    GLB_SHORT = 5122,
    GLB_UNSIGNED_SHORT = 5123,
    GLB_UNSIGNED_INT = 5125,
    GLB_FLOAT = 5126,
    GLB_ARRAY_BUFFER = 34962,         /* bufferView target of vertex attributes */
    GLB_ELEMENT_ARRAY_BUFFER = 34963, /* ... of indices */
};

typedef struct {
    json_t *doc; /* the glTF document; "buffers" is filled in by glb_write */
    uint8_t *bin;
    size_t bin_len, bin_cap;
} glb_t;

/* A document with asset (generator) and nothing else. Returns 0 or -1. */
int glb_init(glb_t *g, const char *generator);
void glb_free(glb_t *g);

/* Appends obj (stolen) to the top-level array named key (created when
 * missing) and returns its index, or -1 when out of memory. */
int glb_append(glb_t *g, const char *key, json_t *obj);

/* Copies len bytes into the binary buffer as a new bufferView (target 0:
 * none, e.g. an image). Returns its index or -1. */
int glb_add_view(glb_t *g, const void *data, size_t len, int target);

/* glb_add_view for interleaved or padded vertex data: elements stride bytes
 * apart (a multiple of 4, as glTF wants of vertex attributes). */
int glb_add_strided_view(glb_t *g, const void *data, size_t len, int target, int stride);

/* A tightly packed accessor over a whole bufferView: count elements of type
 * ("SCALAR", "VEC2", "VEC3") with the given component type; min/max (may be
 * NULL) have as many values as the type has components. Returns its index
 * or -1. */
int glb_add_accessor(glb_t *g, int view, int component_type, int count, const char *type, const double *min,
                     const double *max);

/* Marks the accessor's integers as normalized (to [0, 1] or [-1, 1]). */
int glb_set_normalized(glb_t *g, int accessor);

/* Declares an extension in extensionsUsed (once). Returns 0 or -1. */
int glb_use_extension(glb_t *g, const char *name);

/* ... and in extensionsRequired: a loader without it cannot read the file. */
int glb_require_extension(glb_t *g, const char *name);

/* Writes the GLB file atomically. Returns 0, or -1 with a one-line reason. */
int glb_write(glb_t *g, const char *path, char *err, size_t errlen);

#endif
