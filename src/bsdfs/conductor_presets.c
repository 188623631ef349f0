/* RGB complex indices of refraction for Mitsuba's conductor presets, as
 * Mitsuba 3's RGB variants make them (its ior_from_file): the tabulated
 * spectral n and k (data/ior/NAME.{eta,k}.spd of mitsuba-renderer/mitsuba-data,
 * from the Luxpop database, after Palik, Handbook of Optical Constants of
 * Solids, 1998; a-C concatenates the LLNL CXRO, Windt 1988 and Palik data)
 * integrated against the CIE 1931 colour matching functions *without* the
 * D65 weighting that XML spectra get, then taken from XYZ to linear sRGB,
 * negative values clamped to 0: the conversion of
 * src/scene_xml/spectrum.c (spectrum_list_xyz with d65 = false, then
 * spectrum_xyz_to_rgb). A flat spectrum c thus becomes about
 * (1.20, 0.95, 0.91) c, which is why a-C's nearly flat n of 1.8-2.4 is warm
 * (red eta 2.94, blue 1.97). tests/test_bsdf_models.c recomputes a-C from
 * its table.
 * "none" is Mitsuba's idealised mirror: eta = 0, k = 1 gives F = 1 at every angle. */
#include <string.h>

#include "bsdfs/bsdf_impl.h"

static const char *const names[] = {"none", "Ag", "Al", "Au", "Cu", "a-C", NULL};
static const rgb etas[] = {
    {0.0, 0.0, 0.0},
    {0.155276, 0.116728, 0.138388},
    {1.657502, 0.880405, 0.521245},
    {0.143036, 0.375307, 1.442046},
    {0.201006, 0.923750, 1.102216},
    {2.944047, 2.227138, 1.968163},
};
static const rgb ks[] = {
    {1.0, 1.0, 1.0},
    {4.828357, 3.122224, 2.146902},
    {9.223816, 6.269505, 4.837006},
    {3.982999, 2.385558, 1.603360},
    {3.913264, 2.453046, 2.142091},
    {0.887465, 0.799299, 0.815290},
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
