#include "image/oiio_backend.h"

#include <pthread.h>
#include <stdio.h>

#include "core/core.h"

#ifndef CELADON_OIIO_BACKEND_BUILT
#define CELADON_OIIO_BACKEND_BUILT NULL
#endif

/* Defined here only where a build links the shim in (the fuzzers, whose
 * coverage must see it). */
extern const oiio_backend celadon_oiio_backend __attribute__((weak));

static pthread_once_t once = PTHREAD_ONCE_INIT;
static const oiio_backend *backend;
static char failure[512];

static void load(void)
{
    if (&celadon_oiio_backend)
        backend = &celadon_oiio_backend;
    else
        backend = backend_library_symbol("libceladon-oiio.so", "CELADON_OIIO_BACKEND", CELADON_OIIO_BACKEND_BUILT,
                                         OIIO_BACKEND_SYMBOL, failure, sizeof failure);
}

const oiio_backend *oiio_backend_get(char *err, size_t errlen)
{
    pthread_once(&once, load);
    if (!backend && err && errlen)
        snprintf(err, errlen, "the image library (libceladon-oiio.so) cannot be loaded: %s", failure);
    return backend;
}
