/* The PNG backend (image_backend.h) over libpng: see png_backend.c for
 * what it decodes itself and what it leaves to OpenImageIO. */
#ifndef CELADON_IMAGE_PNG_BACKEND_H
#define CELADON_IMAGE_PNG_BACKEND_H

#include "image/image_backend.h"

extern const image_backend png_backend;

#endif
