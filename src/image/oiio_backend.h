/* The OpenImageIO backend (image_backend.h): the one C++ file
 * (oiio_shim.cpp), built as its own shared object (libceladon-oiio.so) and
 * loaded on the first image it reads or writes. OpenImageIO as Debian
 * builds it brings about 270 shared libraries (codecs, OpenCV, GDAL, ...)
 * whose loading and relocation cost 0.4-0.5 s of CPU in every process that
 * loads it (0.75 s under ASan): a render to EXR, a mesh or a merge never
 * pays it, nor does a PNG (png_backend.h) (docs/BENCHMARKS.md, "Test
 * suite"). It declines nothing. */
#ifndef CELADON_IMAGE_OIIO_BACKEND_H
#define CELADON_IMAGE_OIIO_BACKEND_H

#include "image/image_backend.h"

/* The symbol the shared object exports: renamed with every incompatible
 * change of image_backend, so that a stale libceladon-oiio.so fails to
 * load (one line) instead of being called the old way. */
#define OIIO_BACKEND_SYMBOL "celadon_oiio_image_backend"

/* The backend, loaded by the first call (thread-safe; backend_library.h
 * says where it is looked for, $CELADON_OIIO_BACKEND first); NULL with one
 * line in err when it cannot be loaded. */
const image_backend *oiio_backend_get(char *err, size_t errlen);

#endif
