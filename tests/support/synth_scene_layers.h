/* The layers of a synthetic scene (synth_scene.h), for synth_scene.c only:
 * each function computes its layer's weight per pixel (coverage, or the
 * darkening of a shadow) into a zeroed W x H buffer and paints it onto the
 * canvas. The compositor calls them bottom to top and keeps the weights for
 * the truth. */
#ifndef CELADON_TESTS_SYNTH_SCENE_LAYERS_H
#define CELADON_TESTS_SYNTH_SCENE_LAYERS_H

#include "synth_scene.h"

typedef struct {
    int width, height;
    float *rgb; /* width x height x 3, encoded values */
} scene_canvas;

void scene_backdrop(const synth_scene_params *p, scene_canvas *c);
void scene_cast_shadow(const synth_scene_params *p, scene_canvas *c, float *weight);
void scene_contact_shadow(const synth_scene_params *p, scene_canvas *c, float *weight);

/* The stand under vessels[0]. Returns 0, or -1 when out of memory. */
int scene_stand(const synth_scene_params *p, scene_canvas *c, float *weight);

/* vessels[index]'s body. Returns 0, or -1 when out of memory. */
int scene_vessel(const synth_scene_params *p, int index, scene_canvas *c, float *weight);

/* attachments[index] of vessels[0]. Returns 0, or -1 when out of memory. */
int scene_attachment(const synth_scene_params *p, int index, scene_canvas *c, float *weight);

void scene_caption(const synth_scene_params *p, scene_canvas *c, float *weight);
void scene_scale_bar(const synth_scene_params *p, scene_canvas *c, float *weight);
void scene_frame(const synth_scene_params *p, scene_canvas *c, float *weight);

/* The image y of the lowest point of vessels[0]'s outline (its foot). */
double scene_foot_y(const synth_scene_params *p);

#endif
