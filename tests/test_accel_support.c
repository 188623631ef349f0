/* Random rays for the accel tests (splitmix64: small, seedable, portable). */
#include "test_accel_support.h"

double test_rng_uniform(test_rng *r)
{
    uint64_t z = (r->s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1.0p-53;
}

vec3 test_rng_unit_vector(test_rng *r)
{
    double z = 2.0 * test_rng_uniform(r) - 1.0, phi = 2.0 * M_PI * test_rng_uniform(r), s = sqrt(1.0 - z * z);
    return v3(s * cos(phi), s * sin(phi), z);
}

static vec3 point_in_box(test_rng *r, vec3 lo, vec3 hi)
{
    return v3(lo.x + test_rng_uniform(r) * (hi.x - lo.x), lo.y + test_rng_uniform(r) * (hi.y - lo.y),
              lo.z + test_rng_uniform(r) * (hi.z - lo.z));
}

static double random_length(test_rng *r) { return 0.5 + 1.5 * test_rng_uniform(r); }

ray3 test_ray_toward_box(test_rng *r, vec3 lo, vec3 hi)
{
    vec3 c = v3_scale(v3_add(lo, hi), 0.5);
    double radius = 1.5 * 0.5 * v3_len(v3_sub(hi, lo));
    vec3 o = v3_add(c, v3_scale(test_rng_unit_vector(r), radius));
    vec3 d = v3_sub(point_in_box(r, lo, hi), o);
    return (ray3){o, v3_scale(v3_norm(d), random_length(r))};
}

ray3 test_ray_inside_box(test_rng *r, vec3 lo, vec3 hi)
{
    return (ray3){point_in_box(r, lo, hi), v3_scale(test_rng_unit_vector(r), random_length(r))};
}
