/* Slugs with GLib's Unicode tables (normalisation, character classes,
 * case). See slug.h. */
#include "museum/slug.h"

#include <glib.h>
#include <stdio.h>
#include <string.h>

static void slug_base(const char *title, char *base)
{
    char *nfc = g_utf8_normalize(title, -1, G_NORMALIZE_NFC);
    size_t n = 0;
    int dash = 0;
    for (const char *p = nfc; p && *p; p = g_utf8_next_char(p)) {
        gunichar c = g_utf8_get_char(p);
        if (!g_unichar_isalnum(c) && !g_unichar_ismark(c)) {
            dash = n > 0;
            continue;
        }
        char utf8[8];
        int k = g_unichar_to_utf8(g_unichar_tolower(c), utf8);
        if (n + (size_t)dash + (size_t)k > SLUG_MAX_BYTES)
            break;
        if (dash)
            base[n++] = '-';
        memcpy(base + n, utf8, (size_t)k);
        n += (size_t)k;
        dash = 0;
    }
    g_free(nfc);
    base[n] = 0;
    if (!n)
        snprintf(base, SLUG_MAX_BYTES + 1, "vessel");
}

void slug_make(const char *title, const char *const *taken, int n_taken, char *out, size_t len)
{
    char base[SLUG_MAX_BYTES + 1];
    slug_base(title, base);
    snprintf(out, len, "%s", base);
    for (int k = 2;; k++) {
        int clash = 0;
        for (int j = 0; j < n_taken && !clash; j++)
            clash = !strcmp(taken[j], out);
        if (!clash)
            return;
        snprintf(out, len, "%s-%d", base, k);
    }
}
