#include "core/backend_library.h"

#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The symbol from path; NULL with the reason in err. */
static void *symbol_from(const char *path, const char *symbol, char *err, size_t errlen)
{
    void *so = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!so) {
        snprintf(err, errlen, "%s", dlerror());
        return NULL;
    }
    void *sym = dlsym(so, symbol);
    if (!sym) {
        snprintf(err, errlen, "%s has no %s", path, symbol);
        dlclose(so);
    }
    return sym;
}

void *backend_library_symbol(const char *so_name, const char *env_var, const char *built_path, const char *symbol,
                             char *err, size_t errlen)
{
    const char *env = getenv(env_var);
    if (env && *env)
        return symbol_from(env, symbol, err, errlen);
    Dl_info info;
    if (dladdr((void *)backend_library_symbol, &info) && info.dli_fname) {
        const char *slash = strrchr(info.dli_fname, '/');
        int dirlen = slash ? (int)(slash - info.dli_fname) : 1;
        const char *dir = slash ? info.dli_fname : ".";
        static const char *const beside[] = {"/", "/celadon/", "/../lib/celadon/"};
        for (size_t i = 0; i < sizeof beside / sizeof *beside; i++) {
            char path[4200];
            snprintf(path, sizeof path, "%.*s%s%s", dirlen, dir, beside[i], so_name);
            void *sym = symbol_from(path, symbol, err, errlen);
            if (sym)
                return sym;
        }
    }
    return built_path ? symbol_from(built_path, symbol, err, errlen) : NULL;
}
