/* Folders that appear whole or not at all: the outputs of one job are written
 * into a temporary folder and published into their final folder at the end. */
#ifndef CELADON_CORE_FOLDER_H
#define CELADON_CORE_FOLDER_H

#include <limits.h>
#include <stddef.h>

/* Creates path and its missing parents. The folders it made are recorded,
 * outermost first, in made[0..*n_made) (up to max_made), so that a run that
 * produced nothing can remove them again. Returns 0, or -1 (errno set; ENOTDIR
 * when path exists and is not a folder). */
int folder_make(const char *path, char made[][PATH_MAX], int max_made, int *n_made);

/* Creates a fresh, empty temporary folder for the outputs that will go into
 * final: inside final when it exists, else beside it. Returns 0 or -1. */
int folder_make_temp(const char *final, char *tmp, size_t len);

/* Removes the files of a folder this process made, then the folder. */
void folder_remove(const char *dir);

/* Moves files[0..n) from tmp into final: one rename of the folder when final
 * does not exist, else file by file (undone when one fails; tmp is removed
 * when it succeeds). Returns 0 or -1 (errno set). */
int folder_publish(const char *tmp, const char *final, const char *const *files, int n);

#endif
