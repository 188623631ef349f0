/* "%.*g" for floats without printf: the value scaled by a power of ten and
 * rounded in double gives the significant digits as an integer. A float has
 * 24 significant bits, so the scaled value (< 10^9) carries a relative error
 * of at most a few units of 2^-53 (< 10^-6 absolute); only when it lies that
 * close to a rounding tie (x.5) could the double rounding differ from the
 * exact one, and then snprintf decides. */
#include "mesh/format_float.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const double POW10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                               1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

int format_uint(char *out, unsigned v)
{
    char tmp[10];
    int n = 0;
    do {
        tmp[n++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    for (int i = 0; i < n; i++)
        out[i] = tmp[n - 1 - i];
    return n;
}

/* x * 10^k with k in [-44, 44], each factor exact (10^k for |k| <= 22). */
static double scale10(double x, int k)
{
    while (k > 22) {
        x *= 1e22;
        k -= 22;
    }
    while (k < -22) {
        x /= 1e22;
        k += 22;
    }
    return k >= 0 ? x * POW10[k] : x / POW10[-k];
}

int format_float_g(char *out, float v, int precision)
{
    double x = v;
    if (!isfinite(x) || precision < 1 || precision > 9)
        return snprintf(out, 16, "%.*g", precision, x);
    int n = 0;
    if (signbit(x)) {
        out[n++] = '-';
        x = -x;
    }
    if (x == 0) {
        out[n++] = '0';
        return n;
    }
    /* digits = x / 10^(e - p + 1) rounded, in [10^(p-1), 10^p). */
    int k2;
    frexp(x, &k2); /* x in [2^(k2-1), 2^k2): e is this estimate or one more */
    int e = (int)floor((k2 - 1) * 0.30102999566398120);
    double s = scale10(x, precision - 1 - e);
    if (s >= POW10[precision]) { /* the estimate was one low */
        e++;
        s = scale10(x, precision - 1 - e);
    } else if (s < POW10[precision - 1]) {
        e--;
        s = scale10(x, precision - 1 - e);
    }
    if (fabs(s - floor(s) - 0.5) < 1e-6)
        return n + snprintf(out + n, 16, "%.*g", precision, x);
    double r = rint(s);
    if (r >= POW10[precision]) { /* rounding carried into a new digit: 9.99.. -> 10.0 */
        r /= 10;
        e++;
    }
    char dig[10];
    int nd = format_uint(dig, (unsigned)r);
    while (nd > 1 && dig[nd - 1] == '0') /* %g drops trailing zeros */
        nd--;
    if (e < -4 || e >= precision) {
        out[n++] = dig[0];
        if (nd > 1) {
            out[n++] = '.';
            memcpy(out + n, dig + 1, (size_t)nd - 1);
            n += nd - 1;
        }
        out[n++] = 'e';
        out[n++] = e < 0 ? '-' : '+';
        int ae = e < 0 ? -e : e;
        if (ae < 10)
            out[n++] = '0';
        n += format_uint(out + n, (unsigned)ae);
    } else if (e >= 0) {
        /* integer part: digits 0..e (zeros past the significant ones) */
        for (int i = 0; i <= e; i++)
            out[n++] = i < nd ? dig[i] : '0';
        if (nd > e + 1) {
            out[n++] = '.';
            memcpy(out + n, dig + e + 1, (size_t)(nd - e - 1));
            n += nd - e - 1;
        }
    } else {
        out[n++] = '0';
        out[n++] = '.';
        for (int i = 0; i < -e - 1; i++)
            out[n++] = '0';
        memcpy(out + n, dig, (size_t)nd);
        n += nd;
    }
    return n;
}
