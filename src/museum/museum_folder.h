/* The museum's output folder: built beside its final place, then swapped in
 * whole. A folder may receive a museum when it is missing, empty, or holds a
 * museum and nothing else (its museum.json lists every file in it); anything
 * else is the user's and is never touched. */
#ifndef CELADON_MUSEUM_FOLDER_H
#define CELADON_MUSEUM_FOLDER_H

#include <limits.h>
#include <stddef.h>

#define MUSEUM_MANIFEST "museum.json"

/* Returns 0 when dir may receive a museum, or -1 with "DIR: why not". */
int museum_folder_check(const char *dir, char *err, size_t errlen);

/* Creates dir's missing parents and a fresh, empty temporary folder beside
 * dir. Returns 0, or -1 with a reason. */
int museum_folder_begin(const char *dir, char *tmp, size_t len, char *err, size_t errlen);

/* Puts tmp in dir's place (dir: missing, empty or an old museum, which is
 * then deleted). Returns 0, or -1 with a reason (tmp is left as it was). */
int museum_folder_publish(const char *tmp, const char *dir, char *err, size_t errlen);

/* Deletes a folder tree made by this process (a temporary or replaced museum). */
void museum_folder_remove(const char *dir);

/* Creates the subfolder name inside dir (and its parents). Returns 0 or -1. */
int museum_folder_sub(const char *dir, const char *name);

#endif
