/* A small museum for the museum tests: drawn vessel photos with known
 * geometry built into a museum by the CLI under test, and a reader of the
 * museum.glb it writes (the GLB container and its JSON, with jansson). */
#ifndef CELADON_TEST_MUSEUM_FIXTURE_H
#define CELADON_TEST_MUSEUM_FIXTURE_H

#include <jansson.h>
#include <stddef.h>
#include <stdint.h>

#include "celadon/vecmath.h"
#include "cli_run.h"

/* Draws n photos (vase, bowl, bottle, jar, ...: 240 x 320 px) as
 * dir/vessel-K.png and writes dir/catalogue.csv giving each a title and a
 * height. paths[k] receives photo k's path. */
void museum_fixture_photos(const char *dir, int n, char paths[][512]);

/* Removes the folder tree at path (a test's scratch folder). */
void museum_fixture_remove_tree(const char *path);

/* Runs `celadon museum` with args (NULL-terminated) in scratch dir. */
cli_result museum_fixture_run(const char *dir, const char *const *args);

typedef struct {
    json_t *doc;        /* the JSON chunk */
    uint8_t *file;      /* the whole file */
    const uint8_t *bin; /* the BIN chunk */
    size_t bin_len;
} glb_file;

/* Reads and checks the container (magic, version, lengths, chunk types);
 * fails the test when it is malformed. */
void glb_read(const char *path, glb_file *g);
void glb_close(glb_file *g);

/* The floats of a tightly packed FLOAT accessor (count * components). */
const float *glb_floats(const glb_file *g, int accessor, int *count);

/* The vertex positions of a POSITION accessor in its node's frame (count *
 * 3 doubles, malloc'd): floats as they are, or KHR_mesh_quantization's
 * 16-bit integers through the node's translation and uniform scale (*step
 * receives that scale: the quantization step; 0 for floats). */
double *glb_positions(const glb_file *g, int accessor, int node, int *count, double *step);

/* The node's translation added up along the path from the scene's root
 * (the museum uses no rotations or scales above vessels). */
vec3 glb_node_world_translation(const glb_file *g, int node);

/* The pixel of world point p seen by the glTF's first camera (a node with a
 * camera) on a width x height image; 0, or -1 when behind the camera. */
int glb_project(const glb_file *g, vec3 p, int width, int height, double *px, double *py);

/* Indices of the exhibit nodes (extras.title), in extras.index order; the
 * vessel child (extras.lod) of each. Returns the count (at most max). */
int glb_exhibits(const glb_file *g, int *exhibit, int *vessel, int max);

#endif
