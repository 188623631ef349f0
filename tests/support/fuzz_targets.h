/* The fuzz targets (issue 15, docs/faults.md): each runs one input, given
 * as bytes, through the library the way a user's file goes, and must return
 * without crashing, hanging or leaking whatever the bytes are. The libFuzzer
 * harness (fuzz/harness.c) and the regression cases of
 * tests/test_fuzz_regressions.c share them. Inputs that need a file are
 * written into a private scratch folder (removed at exit). */
#ifndef CELADON_TEST_FUZZ_TARGETS_H
#define CELADON_TEST_FUZZ_TARGETS_H

#include <stddef.h>
#include <stdint.h>

/* Each returns 0 when the library accepted the input, 1 when it refused it. */
typedef int (*fuzz_target_fn)(const uint8_t *data, size_t size);

/* profile.json -> read -> revolved mesh -> SOR -> rays intersected. */
int fuzz_profile(const uint8_t *data, size_t size);
/* scene XML (anchored in scenes/showcase/, so its vessels resolve) -> scene
 * build -> an 8x6 render at one sample per pixel. */
int fuzz_scene(const uint8_t *data, size_t size);
/* image file of any format -> reconstruct_photo (decode, image stages,
 * B-spline, texture). */
int fuzz_image(const uint8_t *data, size_t size);
/* a Mitsuba .serialized file -> <shape type="serialized"> (its meshes 0 and
 * 1) as an area light -> scene build -> a 8x6 render at one sample per pixel. */
int fuzz_serialized(const uint8_t *data, size_t size);
/* the museum's catalogue CSV (rows may name photo.png and b.jpg, which
 * exist beside it). */
int fuzz_catalogue(const uint8_t *data, size_t size);

typedef struct {
    const char *name; /* also the folder of its seeds and regressions */
    fuzz_target_fn run;
} fuzz_target;

/* Every target, ended by {NULL, NULL}. */
extern const fuzz_target fuzz_target_table[];

#endif
