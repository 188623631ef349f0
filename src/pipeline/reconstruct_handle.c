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

int reconstruct_option_set(reconstruct_options *opt, const char *name, const char *value, char *err,
                           size_t errlen)
{
    double v;
    if (!strcmp(name, "threshold")) {
        if (parse_number(value, 0, 255, &v) != 0 || v != (int)v) {
            snprintf(err, errlen, "threshold wants an integer 0..255, not '%s'", value);
            return -1;
        }
        opt->recon.threshold = (int)v;
    } else if (!strcmp(name, "side")) {
        if (!strcmp(value, "left"))
            opt->recon.side = RECON_SIDE_LEFT;
        else if (!strcmp(value, "right"))
            opt->recon.side = RECON_SIDE_RIGHT;
        else if (!strcmp(value, "auto"))
            opt->recon.side = RECON_SIDE_AUTO;
        else {
            snprintf(err, errlen, "side wants left, right or auto, not '%s'", value);
            return -1;
        }
    } else if (!strcmp(name, "smoothing")) {
        if (parse_number(value, 0.01, 100.0, &opt->smoothing_px) != 0) {
            snprintf(err, errlen, "smoothing wants pixels between 0.01 and 100, not '%s'", value);
            return -1;
        }
    } else if (!strcmp(name, "fov")) {
        if (parse_number(value, 1.0, 150.0, &opt->camera.fov_deg) != 0) {
            snprintf(err, errlen, "fov wants degrees between 1 and 150, not '%s'", value);
            return -1;
        }
    } else if (!strcmp(name, "force")) {
        if (strcmp(value, "0") && strcmp(value, "1")) {
            snprintf(err, errlen, "force wants 1 or 0, not '%s'", value);
            return -1;
        }
        opt->force = value[0] == '1';
    } else {
        snprintf(err, errlen, "unknown option '%s' (threshold, side, smoothing, fov, force)", name);
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
