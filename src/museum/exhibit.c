/* See exhibit.h. */
#include "museum/exhibit.h"

#include <stdlib.h>
#include <string.h>

void museum_exhibit_free(museum_exhibit *e)
{
    free(e->title);
    free(e->date);
    free(e->description);
    bspline_free(&e->curve);
    lod_free(e->lods, e->n_lods);
    free(e->texture_jpg);
    free(e->label_png);
    free(e->sign_png);
    memset(e, 0, sizeof *e);
}
