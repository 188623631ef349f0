/* Writing a JSON document to a file whole or not at all (atomic_file.h). */
#ifndef CELADON_JSON_FILE_H
#define CELADON_JSON_FILE_H

#include <stddef.h>

struct json_t; /* jansson's */

/* Dumps root with jansson's flags plus a final newline, through a temporary
 * file renamed into place. Returns 0, or -1 with "cannot write PATH: reason". */
int json_write_file_atomic(const char *path, const struct json_t *root, size_t flags, char *err, size_t errlen);

#endif
