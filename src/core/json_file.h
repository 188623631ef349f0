/* Writing a JSON document to a file whole or not at all (atomic_file.h). */
#ifndef CELADON_JSON_FILE_H
#define CELADON_JSON_FILE_H

#include <stddef.h>

struct json_t; /* jansson's */

/* Dumps root with jansson's flags plus a final newline, through a temporary
 * file renamed into place. Returns 0, or -1 with "cannot write PATH: reason". */
int json_write_file_atomic(const char *path, const struct json_t *root, size_t flags, char *err, size_t errlen);

/* A file name (any bytes but NUL) as JSON text, which must be UTF-8: s itself
 * when it is, else a copy in buf (len >= 4) with each byte that is not part
 * of a valid UTF-8 sequence replaced by U+FFFD, cut at a whole character
 * when buf is too small. For people to read: the file is found by its
 * bytes, not by this text. */
const char *json_text(const char *s, char *buf, size_t len);

#endif
