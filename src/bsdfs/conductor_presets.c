/* RGB complex indices of refraction for Mitsuba's conductor presets.
 *
 * Source: the tabulated spectral n, k data Mitsuba ships for these presets
 * (data/ior/{Ag,Al,Au,Cu}.{eta,k}.spd in mitsuba-renderer/mitsuba, from the
 * Luxpop database, after Palik, Handbook of Optical Constants of Solids, 1998).
 * Each channel is the mean of the piecewise-linear spectrum over a 100 nm band:
 * B = 400-500 nm, G = 500-600 nm, R = 600-700 nm (trapezoidal integration).
 * Mitsuba's RGB mode instead projects the spectra onto CIE colour matching
 * functions; the normal-incidence reflectances differ by a few percent.
 * Amorphous carbon "a-C" comes from the same database's a-C table (a
 * concatenation of the LLNL CXRO, Windt 1988 and Palik data; 310-886 nm),
 * reduced the same way.
 * "none" is Mitsuba's idealised mirror: eta = 0, k = 1 gives F = 1 at every angle. */
#include <string.h>

#include "bsdfs/bsdf_impl.h"

static const char *const names[] = {"none", "Ag", "Al", "Au", "Cu", "a-C", NULL};
static const rgb etas[] = {
    {0.0, 0.0, 0.0},
    {0.136293, 0.125141, 0.150100},
    {1.486911, 0.967191, 0.621731},
    {0.176072, 0.411782, 1.417957},
    {0.242674, 0.875739, 1.162401},
    {2.427512, 2.351768, 2.183657},
};
static const rgb ks[] = {
    {1.0, 1.0, 1.0},
    {4.127181, 3.336757, 2.462041},
    {7.795373, 6.679945, 5.470626},
    {3.302028, 2.595472, 1.880714},
    {3.604633, 2.644739, 2.380738},
    {0.729702, 0.832124, 0.888450},
};

int bsdf_conductor_preset(const char *name, rgb *eta, rgb *k)
{
    for (int i = 0; names[i]; i++)
        if (strcmp(name, names[i]) == 0) {
            *eta = etas[i];
            *k = ks[i];
            return 0;
        }
    return -1;
}
