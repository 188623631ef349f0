/* A reconstruction held by pointer, its options by name, and what its
 * profile gives: for language bindings. See include/celadon/reconstruct.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/reconstruct.h"

/* A whole decimal number in [lo, hi]. */
static int parse_number(const char *s, double lo, double hi, double *out)
{
    char *end;
    *out = strtod(s, &end);
    return end != s && !*end && *out >= lo && *out <= hi ? 0 : -1;
}

static int parse_integer(const char *s, int lo, int hi, int *out)
{
    double v;
    if (parse_number(s, lo, hi, &v) != 0 || v != (int)v)
        return -1;
    *out = (int)v;
    return 0;
}

/* Up to RECONSTRUCT_MAX_LODS comma-separated segment counts. */
static int parse_lods(const char *s, reconstruct_options *opt)
{
    char buf[256];
    if (strlen(s) >= sizeof buf)
        return -1;
    snprintf(buf, sizeof buf, "%s", s);
    opt->n_lods = 0;
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (opt->n_lods == RECONSTRUCT_MAX_LODS || parse_integer(tok, 3, 100000, &opt->lods[opt->n_lods]) != 0)
            return -1;
        opt->n_lods++;
    }
    return opt->n_lods > 0 ? 0 : -1;
}

/* The index of value in the NULL-terminated words, or -1. */
static int word_index(const char *value, const char *const *words)
{
    for (int i = 0; words[i]; i++)
        if (!strcmp(value, words[i]))
            return i;
    return -1;
}

static int flag_value(const char *value, int *out)
{
    if (strcmp(value, "0") && strcmp(value, "1"))
        return -1;
    *out = value[0] == '1';
    return 0;
}

int reconstruct_option_set(reconstruct_options *opt, const char *name, const char *value, char *err,
                           size_t errlen)
{
    static const char *const sides[] = {"left", "right", "auto", NULL};
    static const recon_side side_of[] = {RECON_SIDE_LEFT, RECON_SIDE_RIGHT, RECON_SIDE_AUTO};
    static const char *const segmenters[] = {"classic", "learned", "auto", NULL};
    static const reconstruct_segmenter segmenter_of[] = {RECONSTRUCT_SEGMENTER_CLASSIC, RECONSTRUCT_SEGMENTER_LEARNED,
                                                         RECONSTRUCT_SEGMENTER_AUTO};
    const char *wants = NULL;
    int k;
    if (!strcmp(name, "threshold")) {
        if (parse_integer(value, 0, 255, &opt->recon.threshold) != 0)
            wants = "an integer 0..255";
    } else if (!strcmp(name, "side")) {
        if ((k = word_index(value, sides)) < 0)
            wants = "left, right or auto";
        else
            opt->recon.side = side_of[k];
    } else if (!strcmp(name, "segmenter")) {
        if ((k = word_index(value, segmenters)) < 0)
            wants = "classic, learned or auto";
        else
            opt->segmenter = segmenter_of[k];
    } else if (!strcmp(name, "segments")) {
        if (parse_integer(value, 3, 100000, &opt->segments) != 0)
            wants = "an integer 3..100000";
    } else if (!strcmp(name, "lod")) {
        if (parse_lods(value, opt) != 0)
            wants = "up to 8 comma-separated integers 3..100000";
    } else if (!strcmp(name, "smoothing")) {
        if (parse_number(value, 0.01, 100.0, &opt->smoothing_px) != 0)
            wants = "pixels between 0.01 and 100";
    } else if (!strcmp(name, "fov")) {
        if (parse_number(value, 1.0, 150.0, &opt->camera.fov_deg) != 0)
            wants = "degrees between 1 and 150";
    } else if (!strcmp(name, "force")) {
        if (flag_value(value, &opt->force) != 0)
            wants = "1 or 0";
    } else if (!strcmp(name, "mouth-cap")) {
        if (flag_value(value, &opt->mouth_cap) != 0)
            wants = "1 or 0";
    } else {
        snprintf(err, errlen,
                 "unknown option '%s' (threshold, side, segmenter, segments, lod, smoothing, fov, force, mouth-cap)",
                 name);
        return -1;
    }
    if (wants) {
        snprintf(err, errlen, "%s wants %s, not '%s'", name, wants, value);
        return -1;
    }
    return 0;
}

reconstruction *reconstruction_create(const char *path, const image_t *photo, const char *const *names,
                                      const char *const *values, int n, int *status, char *err, size_t errlen)
{
    reconstruct_options opt = reconstruct_options_default();
    *status = 2;
    for (int i = 0; i < n; i++)
        if (reconstruct_option_set(&opt, names[i], values[i], err, errlen) != 0)
            return NULL;
    reconstruction *r = malloc(sizeof *r);
    if (!r) {
        *status = 1;
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    *status = path ? reconstruct_photo(path, &opt, r, err, errlen) : reconstruct_image(photo, &opt, r, err, errlen);
    if (*status != 0) {
        reconstruction_destroy(r);
        return NULL;
    }
    return r;
}

void reconstruction_destroy(reconstruction *r)
{
    if (!r)
        return;
    reconstruction_free(r);
    free(r);
}

char *reconstruction_profile_text(const reconstruction *r, const char *source, char *err, size_t errlen)
{
    profile_t p;
    reconstruction_profile(r, source, &p);
    return profile_json_text(&p, err, errlen);
}

int reconstruction_radius(const reconstruction *r, double h, double *radius)
{
    profile_t p;
    reconstruction_profile(r, "", &p);
    return profile_radius(&p, h, radius);
}

int reconstruction_mesh(const reconstruction *r, int segments, unsigned caps, mesh_t *m)
{
    profile_t p;
    reconstruction_profile(r, "", &p);
    const double *domains;
    int n_domains;
    const bspline_t *shape = profile_shape(&p, &domains, &n_domains);
    return mesh_revolve(shape, domains, n_domains, 1.0, segments, caps, m);
}
