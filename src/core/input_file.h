/* Inputs are read only from regular files of a bounded size: a folder, a
 * device (/dev/zero), a FIFO or a socket is refused before a byte is read,
 * and so is a file larger than the limit its kind sets. Every reader of a
 * user's file (scenes and their includes, profiles, meshes, images,
 * catalogues) goes through here (docs/faults.md). */
#ifndef CELADON_INPUT_FILE_H
#define CELADON_INPUT_FILE_H

#include <stdio.h>
#include <stddef.h>

/* Text documents: scene XML, profile.json, the museum's catalogue. */
#define INPUT_MAX_TEXT_BYTES (64ll << 20)
/* Binary data: meshes, images, textures. */
#define INPUT_MAX_DATA_BYTES (4ll << 30)

/* Checks path without keeping it open (for libraries that open the file
 * themselves). Returns 0 with the size in *size (may be NULL), or -1 with a
 * one-line reason without the file name in why ("is a folder, not a file",
 * "not a regular file (a device, FIFO or socket)", "too large: ...",
 * "cannot open: ..."). */
int input_check(const char *path, long long max_bytes, long long *size, char *why, size_t whylen);

/* Opens a regular file of at most max_bytes for reading ("rb"); never
 * blocks on a FIFO. NULL with a reason as input_check's. */
FILE *input_open(const char *path, long long max_bytes, long long *size, char *why, size_t whylen);

/* The whole file in *buf (malloc'd, NUL-terminated; *len excludes the NUL).
 * Returns 0, or -1 with a reason as input_check's. */
int input_read_all(const char *path, long long max_bytes, char **buf, size_t *len, char *why, size_t whylen);

#endif
