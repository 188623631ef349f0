/* A film's metadata (film.h: film_metadata) and the counts of its pixels'
 * samples as name/value strings: the "celadon/..." attributes of an EXR
 * header, and the text chunks of a PNG or the comment of a JPEG. Private
 * to src/render/. */
#ifndef CELADON_FILM_INFO_H
#define CELADON_FILM_INFO_H

#include "celadon/film.h"

enum { FILM_INFO_MAX = 24, FILM_INFO_LEN = 2200 };

typedef struct {
    int n;
    film_attr attr[FILM_INFO_MAX];  /* names and values, pointing into text */
    char text[FILM_INFO_MAX][FILM_INFO_LEN];
    char summary[1600];             /* one line: what, how many samples, how long */
} film_info;

/* Fills info from f's metadata and sample counts: "celadon/version",
 * "celadon/scene", "celadon/sceneDigest", "celadon/commandLine",
 * "celadon/seed", "celadon/sampler", "celadon/integrator",
 * "celadon/sppRequested", "celadon/sppDone" ("64", or "17-64" when the
 * pixels' counts differ), "celadon/passes", "celadon/renderSeconds",
 * "celadon/interrupted" ("yes"/"no"), "celadon/threads", "celadon/ranks",
 * "celadon/timeBudget" (with --time), "celadon/crop" ("X,Y,W,H of WxH",
 * for a crop window), "celadon/denoised" (what denoised it, denoise.h);
 * empty values (and passes, time, threads and ranks that are 0: a merge of
 * parts) are left out. Nothing when f has no metadata. */
void film_info_collect(const film_t *f, film_info *info);

#endif
