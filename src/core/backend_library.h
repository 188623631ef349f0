/* Backends in shared objects of their own, loaded at their first use: a
 * library that brings hundreds of others (OpenImageIO as Debian builds it,
 * OpenCV's DNN) would otherwise cost every process its loading and
 * relocation at start, whether it uses them or not (0.45 s of CPU for
 * OpenImageIO's; docs/BENCHMARKS.md, "Test suite"). A backend is a table of
 * functions that its shared object exports under one symbol. */
#ifndef CELADON_CORE_BACKEND_LIBRARY_H
#define CELADON_CORE_BACKEND_LIBRARY_H

#include <stddef.h>

typedef struct {
    const char *so_name; /* "libceladon-NAME.so" */
    const char *env_var; /* a full path that overrides the search */
    const char *symbol;  /* the table's name in the shared object */
    const char *what;    /* for messages: "the image library" */
    int tried;
    const void *table;
    char failure[512];
} backend_library;

#define BACKEND_LIBRARY(so_name, env_var, symbol, what) {so_name, env_var, symbol, what, 0, NULL, ""}

/* The backend's table, loaded by the first call (thread-safe) and kept:
 * linked_in when the program links the backend itself (the fuzzers, whose
 * coverage must see it: the address of a weak declaration, NULL
 * otherwise), else from the shared object found at $env_var (then nowhere
 * else), beside the program or library that holds this code (DIR/so_name,
 * DIR/celadon/so_name, DIR/../lib/celadon/so_name: the build tree and an
 * installed prefix), or where the build put it. NULL with one line in err
 * when it cannot be loaded. */
const void *backend_library_get(backend_library *b, const void *linked_in, char *err, size_t errlen);

#endif
