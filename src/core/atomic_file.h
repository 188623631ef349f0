/* Output files appear whole or not at all: write to a temporary name in the
 * destination folder, rename over the final name when complete. */
#ifndef CELADON_ATOMIC_FILE_H
#define CELADON_ATOMIC_FILE_H

#include <stdio.h>
#include <stddef.h>

/* Builds a temporary sibling of final_path that keeps its extension (so
 * format-by-extension writers still work): "dir/.name.tmp-PID-N.ext". It is
 * tracked and held (temp_files.h) until atomic_temp_done: call that once
 * the temporary is renamed into place or removed, on every path. */
void atomic_temp_name(const char *final_path, char *tmp, size_t tmplen);
void atomic_temp_done(const char *tmp);

typedef struct {
    FILE *fp;
    char final_path[4096];
    char temp_path[4200];
} atomic_file;

/* Opens the temporary file for writing ("wb"). Returns 0 or -1 (errno set). */
int atomic_file_open(atomic_file *af, const char *final_path);
/* Flushes, closes and renames; on any failure removes the temporary file. */
int atomic_file_commit(atomic_file *af);
/* Closes and removes the temporary file. */
void atomic_file_abort(atomic_file *af);

#endif
