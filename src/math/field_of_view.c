/* Mitsuba's field-of-view conventions (field_of_view.h). */
#include "celadon/field_of_view.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

double fov_of_focal_length(double mm)
{
    return 2.0 * atan(sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2.0 * mm)) * (180.0 / M_PI);
}

/* "50mm" or "50": the millimetres; -1 when it is not a positive number. */
static double parse_millimetres(const char *s)
{
    char *end;
    double v = strtod(s, &end);
    if (end == s || (strcmp(end, "mm") != 0 && *end != '\0') || !(v > 0.0) || !isfinite(v))
        return -1.0;
    return v;
}

int fov_half_extents(double fov_deg, const char *axis, const char *focal_length, double aspect, double *tan_x,
                     double *tan_y, char *err, size_t errlen)
{
    if (isnan(fov_deg)) {
        double mm = parse_millimetres(focal_length ? focal_length : "50mm");
        if (mm < 0.0) {
            snprintf(err, errlen, "focal_length '%s' is not a length in millimetres like '50mm'", focal_length);
            return -1;
        }
        fov_deg = fov_of_focal_length(mm);
        axis = "diagonal";
    }
    if (!(fov_deg > 0.0 && fov_deg < 180.0)) {
        snprintf(err, errlen, "fov %g is not between 0 and 180 degrees", fov_deg);
        return -1;
    }
    if (!(aspect > 0.0) || !isfinite(aspect)) {
        snprintf(err, errlen, "image aspect %g is not positive", aspect);
        return -1;
    }
    if (!axis)
        axis = "x";
    if (strcmp(axis, "smaller") == 0)
        axis = aspect > 1.0 ? "y" : "x";
    else if (strcmp(axis, "larger") == 0)
        axis = aspect > 1.0 ? "x" : "y";
    double t = tan(0.5 * fov_deg * (M_PI / 180.0));
    if (strcmp(axis, "x") == 0) {
        *tan_x = t;
        *tan_y = t / aspect;
    } else if (strcmp(axis, "y") == 0) {
        *tan_y = t;
        *tan_x = t * aspect;
    } else if (strcmp(axis, "diagonal") == 0) {
        /* t is the half diagonal: tan_x^2 + tan_y^2 = t^2, tan_x = aspect tan_y */
        *tan_x = t * aspect / sqrt(1.0 + aspect * aspect);
        *tan_y = *tan_x / aspect;
    } else {
        snprintf(err, errlen, "fov_axis '%s' is not one of x, y, diagonal, smaller, larger", axis);
        return -1;
    }
    return 0;
}
