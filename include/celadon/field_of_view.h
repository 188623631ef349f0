/* Mitsuba 3's field-of-view conventions, shared by the cameras and the
 * projector light: a field of view given in degrees along one image axis,
 * or a 35 mm focal length, turned into the half extents tan_x, tan_y of the
 * image plane at distance 1 for an image of aspect width / height. */
#ifndef CELADON_FIELD_OF_VIEW_H
#define CELADON_FIELD_OF_VIEW_H

#include <stddef.h>

/* The diagonal field of view (degrees) of a lens of focal length mm on
 * 35 mm film (36 x 24 mm): Mitsuba's `focal_length`. */
double fov_of_focal_length(double mm);

/* Half extents of an image of aspect width / height whose field of view
 * fov_deg (in (0, 180)) spans axis: "x", "y", "diagonal", "smaller" (the
 * shorter side: x when the image is square) or "larger". When fov_deg is
 * NaN the field of view comes from focal_length instead ("50mm", or a bare
 * number of millimetres; NULL: Mitsuba's default 50mm) along the diagonal.
 * Returns 0, or -1 with a reason in err. */
int fov_half_extents(double fov_deg, const char *axis, const char *focal_length, double aspect, double *tan_x,
                     double *tan_y, char *err, size_t errlen);

#endif
