/* The museum's catalogue: a CSV file that gives each photographed vessel its
 * label and its real size (docs/museum.md, "Catalogue").
 *
 *   file,title,date,height_cm,diameter_cm,description
 *   photos/maebyeong.jpg,Maebyeong with cranes,12th century,31.5,,"Inlaid celadon, ..."
 *
 * The first row names the columns, in any order; `file` is required, the
 * others optional, no other name allowed. `file` is relative to the CSV's own
 * folder (or absolute) and must exist. Quoting follows RFC 4180. */
#ifndef CELADON_MUSEUM_CATALOGUE_H
#define CELADON_MUSEUM_CATALOGUE_H

#include <limits.h>
#include <stddef.h>

typedef struct {
    char path[PATH_MAX];     /* the photo as the catalogue names it, resolved against the CSV's folder */
    char real[PATH_MAX];     /* realpath() of path: what photos are matched by */
    char *title, *date, *description; /* NULL when the row or the column has none */
    double height_cm, diameter_cm; /* 0 when not given */
} catalogue_entry;

typedef struct {
    catalogue_entry *entries;
    int n;
} catalogue_t;

/* Reads and checks the whole catalogue. Returns 0, or -1 with one line
 * "PATH: row N: problem" (or "PATH: problem") in err. */
int catalogue_read(const char *path, catalogue_t *cat, char *err, size_t errlen);

/* catalogue_read on the file's text, read already; path names it in
 * messages and is the folder the rows' photos are relative to. */
int catalogue_parse(const char *path, const char *text, size_t len, catalogue_t *cat, char *err, size_t errlen);

/* The entry for the photo at path (matched by realpath), or NULL. */
const catalogue_entry *catalogue_find(const catalogue_t *cat, const char *photo_path);

void catalogue_free(catalogue_t *cat);

#endif
