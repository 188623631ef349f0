#include "image/oiio_backend.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SO_NAME "libceladon-oiio.so"

/* Defined here only where a build links the shim in (the fuzzers, whose
 * coverage must see it). */
extern const oiio_backend celadon_oiio_backend __attribute__((weak));

static pthread_once_t once = PTHREAD_ONCE_INIT;
static const oiio_backend *backend;
static char failure[512];

/* Tries one path; 1 when the backend is loaded from it. */
static int load_from(const char *path)
{
    void *so = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!so) {
        snprintf(failure, sizeof failure, "%s", dlerror());
        return 0;
    }
    backend = (const oiio_backend *)dlsym(so, OIIO_BACKEND_SYMBOL);
    if (!backend)
        snprintf(failure, sizeof failure, "%s has no %s", path, OIIO_BACKEND_SYMBOL);
    return backend != NULL;
}

static void load(void)
{
    if (&celadon_oiio_backend) {
        backend = &celadon_oiio_backend;
        return;
    }
    const char *env = getenv("CELADON_OIIO_BACKEND");
    if (env && *env) {
        load_from(env);
        return;
    }
    Dl_info info;
    if (dladdr((void *)oiio_backend_get, &info) && info.dli_fname) {
        const char *slash = strrchr(info.dli_fname, '/');
        int dirlen = slash ? (int)(slash - info.dli_fname) : 1;
        const char *dir = slash ? info.dli_fname : ".";
        static const char *const beside[] = {"/" SO_NAME, "/celadon/" SO_NAME, "/../lib/celadon/" SO_NAME};
        for (size_t i = 0; i < sizeof beside / sizeof *beside; i++) {
            char path[4200];
            snprintf(path, sizeof path, "%.*s%s", dirlen, dir, beside[i]);
            if (load_from(path))
                return;
        }
    }
#ifdef CELADON_OIIO_BACKEND_BUILT
    if (load_from(CELADON_OIIO_BACKEND_BUILT))
        return;
#endif
}

const oiio_backend *oiio_backend_get(char *err, size_t errlen)
{
    pthread_once(&once, load);
    if (!backend && err && errlen)
        snprintf(err, errlen, "the image library (" SO_NAME ") cannot be loaded: %s", failure);
    return backend;
}
