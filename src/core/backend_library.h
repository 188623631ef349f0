/* Backends in shared objects of their own, loaded at their first use: a
 * library that brings hundreds of others (OpenImageIO as Debian builds it,
 * OpenCV's DNN) would otherwise cost every process its loading and
 * relocation at start, whether it uses them or not (0.45 s of CPU for
 * OpenImageIO's; docs/BENCHMARKS.md, "Test suite"). */
#ifndef CELADON_CORE_BACKEND_LIBRARY_H
#define CELADON_CORE_BACKEND_LIBRARY_H

#include <stddef.h>

/* Loads the shared object so_name (RTLD_NOW | RTLD_LOCAL) and returns its
 * symbol, looked for in order at $env_var (a full path; then nowhere else),
 * beside the program or library that holds this code (DIR/so_name,
 * DIR/celadon/so_name, DIR/../lib/celadon/so_name: the build tree and an
 * installed prefix) and at built_path (where the build put it; may be
 * NULL). NULL with the last loader's reason in err. Not cached: callers
 * load once (pthread_once). */
void *backend_library_symbol(const char *so_name, const char *env_var, const char *built_path, const char *symbol,
                             char *err, size_t errlen);

#endif
