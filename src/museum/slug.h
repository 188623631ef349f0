/* The file-name form of an exhibit's title (vessels/SLUG/, labels/SLUG.png):
 * the title in Unicode NFC, its letters, digits and combining marks kept in
 * any script (lower-cased), every other run of characters one '-', no '-'
 * at either end, at most SLUG_MAX_BYTES bytes cut between characters;
 * "vessel" when nothing is left. "Vase des âges" -> "vase-des-âges". So a
 * slug is valid UTF-8 and never holds '/', '.', a space or a control
 * character. */
#ifndef CELADON_MUSEUM_SLUG_H
#define CELADON_MUSEUM_SLUG_H

#include <stddef.h>

enum { SLUG_MAX_BYTES = 60 };

/* The slug of title (valid UTF-8) into out (len > SLUG_MAX_BYTES + 8),
 * made unique against taken[0..n_taken) by -2, -3, ... */
void slug_make(const char *title, const char *const *taken, int n_taken, char *out, size_t len);

#endif
