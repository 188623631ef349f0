/* Named indices of refraction accepted by Mitsuba 3's dielectric plugins
 * (its documentation's IOR table: values near 589 nm, mostly from Hecht,
 * Optics, 4th ed.). */
#include <string.h>
#include <strings.h>

#include "bsdfs/bsdf_impl.h"

/* The names, in the order of ior_values. */
const char bsdf_ior_names[] = "vacuum|helium|hydrogen|air|carbon dioxide|water|acetone|ethanol|"
                              "carbon tetrachloride|glycerol|benzene|silicone oil|bromine|water ice|"
                              "fused quartz|pyrex|acrylic glass|polypropylene|bk7|sodium chloride|amber|pet|diamond";
static const double ior_values[] = {
    1.0,   1.000036, 1.000132, 1.000277, 1.00045, 1.3330, 1.36,  1.361, 1.461, 1.4729, 1.501, 1.52045,
    1.661, 1.31,     1.458,    1.470,    1.49,    1.49,   1.5046, 1.544, 1.55, 1.5750, 2.419,
};

int bsdf_ior_lookup(const char *name, double *ior)
{
    size_t n = strlen(name);
    const char *word = bsdf_ior_names;
    for (size_t i = 0; i < sizeof ior_values / sizeof ior_values[0]; i++) {
        size_t len = strcspn(word, "|");
        if (len == n && strncasecmp(word, name, n) == 0) {
            *ior = ior_values[i];
            return 0;
        }
        word += len + (word[len] == '|');
    }
    return -1;
}
