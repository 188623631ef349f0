/* The view transforms of display-referred outputs (film.h: film_view).
 *
 * `filmic` (hand-written, docs/hand-written.md): each channel's exposure
 * relative to middle grey, e = log2(v / 0.18), is mapped linearly from
 * [-10, +6.5] stops (the range of Blender's Filmic and AgX) to t in
 * [0, 1], then through a logistic sigmoid centred on middle grey and
 * rescaled to pass through (0, 0) and (1, 1). The result is the display's
 * code value. Middle grey lands near 0.5, a value 6.5 stops above it at
 * 1, and channels approach 1 together, so saturated highlights move
 * towards white instead of clipping to a hue. */
#include "celadon/film.h"

#include <math.h>
#include <string.h>

#include "celadon/color.h"

static const double MIDDLE_GREY = 0.18, STOPS_BELOW = 10.0, STOPS_ABOVE = 6.5;
/* The sigmoid's steepness over t: 0.15 code values per stop at middle grey
 * (the standard view's is 0.17). */
static const double STEEPNESS = 10.0;

int film_view_parse(const char *name, film_view *v)
{
    if (!strcmp(name, "standard"))
        *v = FILM_VIEW_STANDARD;
    else if (!strcmp(name, "filmic"))
        *v = FILM_VIEW_FILMIC;
    else
        return -1;
    return 0;
}

static double logistic(double t, double t0) { return 1.0 / (1.0 + exp(-STEEPNESS * (t - t0))); }

static double filmic(double v)
{
    double t0 = STOPS_BELOW / (STOPS_BELOW + STOPS_ABOVE); /* middle grey */
    double e = log2(fmax(v, 1e-30) / MIDDLE_GREY);
    double t = fmin(fmax((e + STOPS_BELOW) / (STOPS_BELOW + STOPS_ABOVE), 0.0), 1.0);
    double lo = logistic(0.0, t0), hi = logistic(1.0, t0);
    return (logistic(t, t0) - lo) / (hi - lo);
}

double film_view_encode(film_view view, double v)
{
    if (!(v > 0)) /* also NaN */
        return 0.0;
    if (view == FILM_VIEW_FILMIC)
        return filmic(v);
    return v >= 1 ? 1.0 : linear_to_srgb(v);
}
