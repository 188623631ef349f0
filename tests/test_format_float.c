/* format_float_g against glibc's snprintf("%.*g") (byte for byte) and the
 * strtof round trip, on random bit patterns, random values in mesh-like
 * ranges, powers of ten and exact decimal ties. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/format_float.h"

static uint64_t rng = 0x9e3779b97f4a7c15u;
static uint32_t next_u32(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (uint32_t)(rng >> 16);
}

static int check(float v, int prec)
{
    char ours[32], ref[32];
    int n = format_float_g(ours, v, prec);
    ours[n] = 0;
    snprintf(ref, sizeof ref, "%.*g", prec, (double)v);
    cr_expect_str_eq(ours, ref, "%.9g at precision %d", (double)v, prec);
    /* at 9 digits every float reads back exactly */
    if (prec == 9 && isfinite(v))
        cr_expect_eq(strtof(ours, NULL), v, "%s does not read back", ours);
    return strcmp(ours, ref) == 0;
}

Test(format_float, random_bit_patterns)
{
    int bad = 0;
    for (int i = 0; i < 200000 && bad < 5; i++) {
        uint32_t b = next_u32();
        float v;
        memcpy(&v, &b, sizeof v);
        bad += !check(v, 7) + !check(v, 6) + !check(v, 9);
    }
}

Test(format_float, mesh_ranges)
{
    int bad = 0;
    for (int i = 0; i < 200000 && bad < 5; i++) {
        double scale = pow(10, (int)(next_u32() % 9) - 4);
        float v = (float)(((double)next_u32() / 4294967296.0 * 2 - 1) * scale);
        bad += !check(v, 7) + !check(v, 6);
    }
}

Test(format_float, powers_of_ten_ties_and_specials)
{
    for (int k = -40; k <= 38; k++) {
        float p = (float)pow(10, k);
        for (int prec = 1; prec <= 9; prec++) {
            check(p, prec);
            check(nextafterf(p, 0), prec);
            check(nextafterf(p, INFINITY), prec);
        }
    }
    /* exact binary values on decimal ties: glibc rounds them to even */
    const float ties[] = {0.5f, 1.5f, 2.5f, 0.125f, 1234567.5f, 1234568.5f, 9999999.5f, 0.0009765625f, 8388607.5f};
    for (size_t i = 0; i < sizeof ties / sizeof ties[0]; i++)
        for (int prec = 1; prec <= 9; prec++) {
            check(ties[i], prec);
            check(-ties[i], prec);
        }
    const float specials[] = {0.0f, -0.0f, INFINITY, -INFINITY, NAN, 1e-45f, 3.4028235e38f, 1.0f, 100.0f, 1e6f,
                              1e7f, 0.0001f, 0.00001f};
    for (size_t i = 0; i < sizeof specials / sizeof specials[0]; i++)
        for (int prec = 1; prec <= 9; prec++)
            check(specials[i], prec);
}
