/* render_image: a render developed into memory. See
 * include/celadon/render_image.h. */
#include "celadon/render_image.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/render_loop.h"

struct render_image {
    int width, height, channels;
    char **names;
    float *pixels;
    render_stats stats;
};

scene_options render_image_scene_options(const render_image_options *opt)
{
    scene_options so = scene_options_default();
    so.width = opt->width, so.height = opt->height;
    so.spp = opt->spp;
    so.seed = opt->seed;
    so.mesh_segments = opt->mesh_segments;
    return so;
}

/* The scene with the defines, and $spp = opt->spp as a fallback as the CLI
 * sets it (cmd_render.c) unless a define names spp. */
static scene_t *load(const char *path, const scene_define *defs, int ndefs, const render_image_options *opt,
                     char *err, size_t errlen)
{
    scene_define *all = malloc(sizeof *all * (size_t)(ndefs + 1));
    if (!all) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    int n = 0, has_spp = 0;
    for (int i = 0; i < ndefs; i++) {
        all[n++] = defs[i];
        has_spp |= !strcmp(defs[i].name, "spp");
    }
    char spp[16];
    snprintf(spp, sizeof spp, "%d", opt->spp);
    if (opt->spp > 0 && !has_spp)
        all[n++] = (scene_define){"spp", spp, true};
    scene_options so = render_image_scene_options(opt);
    scene_t *s = scene_create_from_file(path, all, n, &so, err, errlen);
    free(all);
    return s;
}

static render_image_t *developed(const film_t *film, const render_stats *st)
{
    render_image_t *im = calloc(1, sizeof *im);
    const char **names = malloc(sizeof *names * (size_t)(film->nchannels + FILM_EXR_EXTRA_MAX));
    if (!im || !names) {
        free(im);
        free(names);
        return NULL;
    }
    im->width = film->width, im->height = film->height, im->stats = *st;
    im->pixels = film_develop_exr(film, &im->channels, names);
    im->names = calloc((size_t)im->channels, sizeof *im->names);
    for (int c = 0; im->names && c < im->channels; c++)
        if (!(im->names[c] = strdup(names[c]))) {
            render_image_destroy(im);
            im = NULL;
            break;
        }
    free(names);
    if (im && !im->names) {
        render_image_destroy(im);
        im = NULL;
    }
    return im;
}

render_image_t *render_image_create(const char *scene_path, const scene_define *defs, int ndefs,
                                    const render_image_options *opt, int *status, char *err, size_t errlen)
{
    *status = 2;
    scene_t *scene = load(scene_path, defs, ndefs, opt, err, errlen);
    if (!scene)
        return NULL;
    *status = 1;
    render_options ro = {.threads = opt->threads, .aovs = opt->aovs};
    film_t film;
    render_stats st;
    render_image_t *im = NULL;
    if (render_scene(scene, &ro, &film, &st, err, errlen) == 0) {
        im = developed(&film, &st);
        if (!im)
            snprintf(err, errlen, "out of memory");
        film_free(&film);
    }
    scene_destroy(scene);
    if (im)
        *status = 0;
    return im;
}

void render_image_destroy(render_image_t *im)
{
    if (!im)
        return;
    for (int c = 0; im->names && c < im->channels; c++)
        free(im->names[c]);
    free(im->names);
    free(im->pixels);
    free(im);
}

void render_image_size(const render_image_t *im, int *width, int *height, int *channels)
{
    *width = im->width, *height = im->height, *channels = im->channels;
}

const char *render_image_channel(const render_image_t *im, int c) { return im->names[c]; }
const float *render_image_pixels(const render_image_t *im) { return im->pixels; }
const render_stats *render_image_stats(const render_image_t *im) { return &im->stats; }

void render_image_cancel_stop(void) { render_stop_clear(); }
