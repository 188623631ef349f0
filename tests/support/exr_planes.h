/* Every channel of a float32 scanline OpenEXR read into its own plane
 * through the OpenEXR core API (plane by plane: the 3.1 core API misorders
 * interleaved RGBA decodes), for the film's and the outputs' tests. */
#ifndef CELADON_TEST_EXR_PLANES_H
#define CELADON_TEST_EXR_PLANES_H

enum { EXR_PLANES_MAX = 40 };
typedef struct {
    int width, height, nch;
    char names[EXR_PLANES_MAX][32];
    float *planes[EXR_PLANES_MAX];
} exr_planes;

/* Reads path (asserting it is whole and float32) into out. */
void read_exr(const char *path, exr_planes *out);
/* The plane of the channel name (asserting there is one). */
int plane_index(const exr_planes *e, const char *name);
/* Whether the file has the channel. */
int exr_planes_has(const exr_planes *e, const char *name);
void exr_planes_free(exr_planes *e);

#endif
