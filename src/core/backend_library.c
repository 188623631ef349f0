#include "core/backend_library.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;

/* The table from path, or NULL with the reason in b->failure. */
static const void *table_from(backend_library *b, const char *path)
{
    void *so = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!so) {
        snprintf(b->failure, sizeof b->failure, "%s", dlerror());
        return NULL;
    }
    const void *table = dlsym(so, b->symbol);
    if (!table) {
        snprintf(b->failure, sizeof b->failure, "%s has no %s", path, b->symbol);
        dlclose(so);
    }
    return table;
}

static const void *search(backend_library *b)
{
    const char *env = getenv(b->env_var);
    if (env && *env)
        return table_from(b, env);
    Dl_info info;
    if (dladdr((void *)backend_library_get, &info) && info.dli_fname) {
        const char *slash = strrchr(info.dli_fname, '/');
        int dirlen = slash ? (int)(slash - info.dli_fname) : 1;
        const char *dir = slash ? info.dli_fname : ".";
        static const char *const beside[] = {"/", "/celadon/", "/../lib/celadon/"};
        for (size_t i = 0; i < sizeof beside / sizeof *beside; i++) {
            char path[4200];
            snprintf(path, sizeof path, "%.*s%s%s", dirlen, dir, beside[i], b->so_name);
            const void *table = table_from(b, path);
            if (table)
                return table;
        }
    }
#ifdef CELADON_BACKEND_DIR
    char built[4200];
    snprintf(built, sizeof built, "%s/%s", CELADON_BACKEND_DIR, b->so_name);
    return table_from(b, built);
#else
    return NULL;
#endif
}

const void *backend_library_get(backend_library *b, const void *linked_in, char *err, size_t errlen)
{
    pthread_mutex_lock(&lock);
    if (!b->tried) {
        b->table = linked_in ? linked_in : search(b);
        b->tried = 1;
    }
    const void *table = b->table;
    pthread_mutex_unlock(&lock);
    if (!table && err && errlen)
        snprintf(err, errlen, "%s (%s) cannot be loaded: %s", b->what, b->so_name, b->failure);
    return table;
}
