/* Parts of a render and their merge (parts.h). */
#include "celadon/parts.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/exr_read.h"

#define WEIGHT_CHANNEL "celadon.weight"
/* film_t.samples: each pixel's own sample count, luminance sum and sum of
 * squares, after the weight. */
static const char *const SAMPLE_CHANNELS[3] = {"celadon.samples", "celadon.luminance", "celadon.luminance2"};
/* film_t.ids: the object and material numbers of sample 0 (0 in the other
 * parts, so the sum keeps them). */
static const char *const ID_CHANNELS[2] = {"celadon.object", "celadon.material"};
enum { PART_EXTRA = 6 }; /* the weight, the sample counts and the ids */

enum { MAX_CHANNELS = 64, ATTR_LEN = 1024 };

/* A part's pixels as its EXR holds them: the film's channels, then the
 * weight and the sample counts, interleaved. */
typedef struct {
    int nch;
    float *px;
    const char **names;
} part_pixels;

static part_pixels part_pixels_alloc(const film_t *film)
{
    part_pixels pp = {film->nchannels + PART_EXTRA, NULL, NULL};
    pp.px = malloc(sizeof *pp.px * (size_t)film->width * (size_t)film->height * (size_t)pp.nch);
    pp.names = malloc(sizeof *pp.names * (size_t)pp.nch);
    if (!pp.px || !pp.names)
        abort();
    for (int c = 0; c < film->nchannels; c++)
        pp.names[c] = film->names[c];
    pp.names[film->nchannels] = WEIGHT_CHANNEL;
    for (int i = 0; i < 3; i++)
        pp.names[film->nchannels + 1 + i] = SAMPLE_CHANNELS[i];
    for (int i = 0; i < 2; i++)
        pp.names[film->nchannels + 4 + i] = ID_CHANNELS[i];
    return pp;
}

static void part_pixels_free(part_pixels *pp)
{
    free(pp->px);
    free(pp->names);
}

int render_part_parse(const char *text, render_part *out)
{
    int k, n, len = 0;
    if (sscanf(text, "%d/%d%n", &k, &n, &len) != 2 || text[len] || text[0] < '0' || text[0] > '9' || k < 1 ||
        k > n || n > RENDER_PARTS_MAX)
        return -1;
    *out = (render_part){k, n};
    return 0;
}

int render_part_samples(render_part p, int spp, int *s0, int *s1)
{
    *s0 = (int)((long long)(p.k - 1) * spp / p.n);
    *s1 = (int)((long long)p.k * spp / p.n);
    return *s1 > *s0 ? 0 : -1;
}

/* ------------------------------------------------------------- writing */

int render_part_write(const film_t *film, const scene_t *s, render_part p, int complete, const char *path, char *err,
                      size_t errlen)
{
    int spp = scene_spp(s), s0, s1;
    render_part_samples(p, spp, &s0, &s1);
    char part[32], spps[16], samples[32], seed[32], digest[32], channels[ATTR_LEN] = "";
    char extras[16];
    snprintf(extras, sizeof extras, "%u", film->extras);
    snprintf(part, sizeof part, "%d/%d", p.k, p.n);
    snprintf(spps, sizeof spps, "%d", spp);
    snprintf(samples, sizeof samples, "%d-%d", s0, s1 - 1);
    snprintf(seed, sizeof seed, "%" PRIu64, scene_seed(s));
    snprintf(digest, sizeof digest, "%016" PRIx64, scene_digest(s));
    for (int c = 0; c < film->nchannels; c++)
        snprintf(channels + strlen(channels), sizeof channels - strlen(channels), "%s%s", c ? "," : "",
                 film->names[c]);
    const film_attr attrs[] = {
        {"celadon.part", part},         {"celadon.spp", spps},           {"celadon.samples", samples},
        {"celadon.seed", seed},         {"celadon.scene", digest},       {"celadon.channels", channels},
        {"celadon.complete", complete ? "yes" : "no"},
        {"celadon.format", film_format_name(film->format)}, {"celadon.extras", extras},
    };
    part_pixels pp = part_pixels_alloc(film);
    int nch = pp.nch;
    size_t npix = (size_t)film->width * film->height;
    for (size_t i = 0; i < npix; i++) {
        double w = film->weight[i];
        for (int c = 0; c < film->nchannels; c++)
            pp.px[i * nch + c] = w > 0 ? (float)(film->sum[i * film->nchannels + c] / w) : 0.0f;
        pp.px[i * nch + film->nchannels] = (float)w;
        for (int k = 0; k < 3; k++)
            pp.px[i * nch + film->nchannels + 1 + k] = (float)film->samples[3 * i + k];
        for (int k = 0; k < 2; k++)
            pp.px[i * nch + film->nchannels + 4 + k] = (float)film->ids[2 * i + k];
    }
    int rc = exr_write_float_attrs(path, film->width, film->height, nch, pp.names, pp.px, &film->meta, attrs,
                                   (int)(sizeof attrs / sizeof attrs[0]), err, errlen);
    part_pixels_free(&pp);
    return rc;
}

/* ------------------------------------------------------------- reading */

/* What a part's header says. */
typedef struct {
    const char *path;
    render_part part;
    int spp, s0, s1, width, height, complete;
    char seed[32], scene[32], channels[ATTR_LEN];
    film_pixel_format format;
    film_metadata meta; /* of the EXR header written by film_write */
    unsigned extras;    /* the film's FILM_EXTRA_* */
} part_info;

static const char *attr_or_empty(const exr_in *e, const char *name)
{
    const char *v = exr_in_attr(e, name);
    return v ? v : "";
}

/* Reads and checks one part's header: -2 with the reason when it is not a
 * whole part of a celadon render. */
static int read_info(const char *path, part_info *pi, char *err, size_t errlen)
{
    memset(pi, 0, sizeof *pi);
    pi->path = path;
    exr_in *e = exr_in_open(path, err, errlen);
    if (!e)
        return -2;
    int rc = -2;
    const char *part = exr_in_attr(e, "celadon.part");
    int first = -1, last = -1, len = 0;
    const char *samples = attr_or_empty(e, "celadon.samples");
    exr_in_size(e, &pi->width, &pi->height);
    snprintf(pi->seed, sizeof pi->seed, "%s", attr_or_empty(e, "celadon.seed"));
    snprintf(pi->scene, sizeof pi->scene, "%s", attr_or_empty(e, "celadon.scene"));
    snprintf(pi->channels, sizeof pi->channels, "%s", attr_or_empty(e, "celadon.channels"));
    pi->spp = atoi(attr_or_empty(e, "celadon.spp"));
    pi->complete = !strcmp(attr_or_empty(e, "celadon.complete"), "yes");
    pi->extras = (unsigned)strtoul(attr_or_empty(e, "celadon.extras"), NULL, 10);
    int format_ok = film_format_parse(attr_or_empty(e, "celadon.format"), &pi->format) == 0;
    exr_in_metadata(e, &pi->meta);
    if (!part)
        snprintf(err, errlen, "%s: not a part of a celadon render (its header has no celadon.part)", path);
    else if (render_part_parse(part, &pi->part) != 0 || pi->spp < 1 || !format_ok || !pi->seed[0] || !pi->scene[0] ||
             !pi->channels[0] || sscanf(samples, "%d-%d%n", &first, &last, &len) != 2 || samples[len] ||
             render_part_samples(pi->part, pi->spp, &pi->s0, &pi->s1) != 0 || first != pi->s0 ||
             last != pi->s1 - 1 || !exr_in_has_channel(e, WEIGHT_CHANNEL) ||
             !exr_in_has_channel(e, SAMPLE_CHANNELS[0]) || !exr_in_has_channel(e, ID_CHANNELS[0]))
        snprintf(err, errlen, "%s: its celadon.* header is damaged or not this version's", path);
    else if (!pi->complete)
        snprintf(err, errlen, "%s: part %d/%d is incomplete (its render was interrupted): render it again", path,
                 pi->part.k, pi->part.n);
    else
        rc = 0;
    exr_in_close(e);
    return rc;
}

/* -2 with the reason when b is not of the render a is of. */
static int same_render(const part_info *a, const part_info *b, char *err, size_t errlen)
{
    char what[2 * ATTR_LEN + 64] = "";
    if (strcmp(a->scene, b->scene))
        snprintf(what, sizeof what, "its scene digest is %s, not %s (another scene, or other files or options)",
                 b->scene, a->scene);
    else if (strcmp(a->seed, b->seed))
        snprintf(what, sizeof what, "its seed is %s, not %s", b->seed, a->seed);
    else if (a->part.n != b->part.n || a->spp != b->spp)
        snprintf(what, sizeof what, "it is a part of %d of %d spp, not of %d of %d spp", b->part.n, b->spp,
                 a->part.n, a->spp);
    else if (a->width != b->width || a->height != b->height)
        snprintf(what, sizeof what, "it is %dx%d, not %dx%d", b->width, b->height, a->width, a->height);
    else if (strcmp(a->channels, b->channels))
        snprintf(what, sizeof what, "its channels are %s, not %s", b->channels, a->channels);
    else if (a->format != b->format)
        snprintf(what, sizeof what, "its pixel format is %s, not %s", film_format_name(b->format),
                 film_format_name(a->format));
    else
        return 0;
    snprintf(err, errlen, "%s: not a part of the render %s belongs to: %s", b->path, a->path, what);
    return -2;
}

/* The film's AOVs from the channel list "R,G,B,Z,N.X,N.Y,..." (with
 * an A after B for the alpha formats), its pixel format and metadata. */
static int film_for(const part_info *pi, film_t *film, char *err, size_t errlen)
{
    char buf[ATTR_LEN], *names[MAX_CHANNELS], *save;
    snprintf(buf, sizeof buf, "%s", pi->channels);
    int n = 0;
    for (char *t = strtok_r(buf, ",", &save); t && n < MAX_CHANNELS; t = strtok_r(NULL, ",", &save))
        names[n++] = t;
    film_aov aovs[MAX_CHANNELS];
    const char *suffixes[MAX_CHANNELS]; /* each channel's, so an AOV's are consecutive */
    int naov = 0;
    for (int c = 3 + film_format_has_alpha(pi->format); c < n; c++) {
        char *dot = strrchr(names[c], '.'); /* "Z": an AOV of one channel with no suffix */
        suffixes[c] = dot ? dot + 1 : "";
        if (dot)
            *dot = '\0';
        if (naov > 0 && !strcmp(aovs[naov - 1].name, names[c]))
            aovs[naov - 1].channels++;
        else
            aovs[naov++] = (film_aov){names[c], 1, &suffixes[c]};
    }
    if (film_init_format(film, pi->width, pi->height, pi->format, aovs, naov, err, errlen) != 0)
        return -1;
    film->meta = pi->meta;
    film->extras = pi->extras;
    int ok = film->nchannels == n;
    snprintf(buf, sizeof buf, "%s", pi->channels);
    char *t = strtok_r(buf, ",", &save);
    for (int c = 0; ok && c < n; c++, t = strtok_r(NULL, ",", &save))
        ok = t && !strcmp(t, film->names[c]);
    if (ok)
        return 0;
    film_free(film);
    snprintf(err, errlen, "%s: its channels %s are not a film's (R, G, B, A in an alpha format, then AOVs)", pi->path, pi->channels);
    return -2;
}

/* Adds one part's averages times its weights into film: -2 when its
 * pixels cannot be read (a damaged or truncated part is bad input). */
static int add_part(const part_info *pi, film_t *film, char *err, size_t errlen)
{
    exr_in *e = exr_in_open(pi->path, err, errlen);
    if (!e)
        return -2;
    part_pixels pp = part_pixels_alloc(film);
    int nch = pp.nch;
    size_t npix = (size_t)film->width * film->height;
    int rc = exr_in_read(e, nch, pp.names, pp.px, err, errlen) == 0 ? 0 : -2;
    for (size_t i = 0; rc == 0 && i < npix; i++) {
        double w = pp.px[i * nch + film->nchannels];
        for (int c = 0; c < film->nchannels; c++)
            film->sum[i * film->nchannels + c] += w * pp.px[i * nch + c];
        film->weight[i] += w;
        for (int k = 0; k < 3; k++)
            film->samples[3 * i + k] += pp.px[i * nch + film->nchannels + 1 + k];
        for (int k = 0; k < 2; k++)
            film->ids[2 * i + k] += pp.px[i * nch + film->nchannels + 4 + k];
    }
    part_pixels_free(&pp);
    exr_in_close(e);
    return rc;
}

/* "3/8, 5/8": the shares nobody gave, into out. */
static void list_missing(const int *given, int n, char *out, size_t outlen)
{
    out[0] = '\0';
    int listed = 0;
    for (int k = 1; k <= n; k++) {
        if (given[k] >= 0)
            continue;
        size_t len = strlen(out);
        if (listed == 8) {
            snprintf(out + len, outlen - len, ", ...");
            return;
        }
        snprintf(out + len, outlen - len, "%s%d/%d", listed ? ", " : "", k, n);
        listed++;
    }
}

/* -2 with the reason when the part is not of a render of s. */
static int of_scene(const part_info *pi, const scene_t *s, char *err, size_t errlen)
{
    char digest[32], seed[32];
    snprintf(digest, sizeof digest, "%016" PRIx64, scene_digest(s));
    snprintf(seed, sizeof seed, "%" PRIu64, scene_seed(s));
    if (!strcmp(digest, pi->scene) && !strcmp(seed, pi->seed))
        return 0;
    snprintf(err, errlen, "%s: a part of another render (scene digest %s, seed %s) than this one's (%s, %s)",
             pi->path, pi->scene, pi->seed, digest, seed);
    return -2;
}

int render_parts_merge(const char *const *paths, int n, const scene_t *of, film_t *film, char *err, size_t errlen)
{
    memset(film, 0, sizeof *film);
    if (n < 1) {
        snprintf(err, errlen, "no parts to merge");
        return -2;
    }
    part_info *pi = calloc((size_t)n, sizeof *pi);
    if (!pi)
        abort();
    int rc = 0, *given = NULL;
    for (int i = 0; i < n && rc == 0; i++) {
        rc = read_info(paths[i], &pi[i], err, errlen);
        if (rc == 0 && i > 0)
            rc = same_render(&pi[0], &pi[i], err, errlen);
        if (rc == 0 && i == 0 && of)
            rc = of_scene(&pi[0], of, err, errlen);
    }
    int nparts = pi[0].part.n;
    if (rc == 0) {
        given = malloc(sizeof *given * ((size_t)nparts + 1));
        if (!given)
            abort();
        for (int k = 0; k <= nparts; k++)
            given[k] = -1;
    }
    for (int i = 0; i < n && rc == 0; i++) {
        int k = pi[i].part.k;
        if (given[k] >= 0) {
            snprintf(err, errlen, "%s: part %d/%d is given twice (also as %s)", paths[i], k, nparts, paths[given[k]]);
            rc = -2;
        }
        given[k] = i;
    }
    if (rc == 0 && n < nparts) {
        char missing[256];
        list_missing(given, nparts, missing, sizeof missing);
        snprintf(err, errlen, "the render %s belongs to has %d parts; %d %s missing: %s", paths[0], nparts,
                 nparts - n, nparts - n == 1 ? "is" : "are", missing);
        rc = -2;
    }
    if (rc == 0)
        rc = film_for(&pi[0], film, err, errlen);
    for (int k = 1; k <= nparts && rc == 0; k++) /* in share order: the sum does not depend on the argument order */
        rc = add_part(&pi[given[k]], film, err, errlen);
    if (rc != 0 && film->sum)
        film_free(film);
    free(given);
    free(pi);
    return rc;
}
