/* A small static file server for a museum folder on 127.0.0.1
 * (libmicrohttpd), so the page loads its files over http as browsers need. */
#ifndef CELADON_MUSEUM_SERVE_H
#define CELADON_MUSEUM_SERVE_H

#include <stddef.h>

/* Serves the files under dir on 127.0.0.1:port (0: any free port) until
 * SIGINT or SIGTERM; GET and HEAD only, no listing, nothing outside dir.
 * Prints "celadon: serving DIR at http://127.0.0.1:PORT/" on stdout (and
 * flushes it) once it listens. Returns 0 after a signal, or -1 with a
 * reason when it cannot listen. */
int museum_serve(const char *dir, int port, char *err, size_t errlen);

#endif
