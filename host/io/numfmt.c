/*
 * numfmt.c - see numfmt.h.  The C locale is never changed by offbench, so
 * printf and strtod use '.' decimals.
 */
#include "host/io/numfmt.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void ob_fmt_double(char *buf, size_t len, double x)
{
    if (isnan(x)) {
        snprintf(buf, len, "nan");
        return;
    }
    if (isinf(x)) {
        snprintf(buf, len, x > 0 ? "inf" : "-inf");
        return;
    }
    /* the shortest text that reads back exactly; between 1e-4 and 1e16 without
     * an exponent (20, not 2e+01), as %g would print it */
    const int plain = fabs(x) >= 1e-4 && fabs(x) < 1e16;
    for (int p = 1; p <= 17; p++) {
        snprintf(buf, len, "%.*g", p, x);
        if (strtod(buf, NULL) == x && !(plain && strchr(buf, 'e')))
            return;
    }
    snprintf(buf, len, "%.17g", x);
}

int ob_parse_double(const char *s, double *out)
{
    char *end;
    if (!s || !*s)
        return -1;
    double v = strtod(s, &end);
    if (*end != '\0' || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

void ob_fmt_bound(char *buf, size_t len, double x, int dir)
{
    if (!(x > 0) || !isfinite(x)) {
        snprintf(buf, len, isinf(x) ? "inf" : "%g", x);
        return;
    }
    snprintf(buf, len, "%.3g", x);
    const double w = strtod(buf, NULL);
    if (dir > 0 ? w < x : w > x) {  /* the third digit one step outward */
        const double e = pow(10.0, floor(log10(x)) - 2);
        snprintf(buf, len, "%.3g", (dir > 0 ? floor(x / e) + 1 : ceil(x / e) - 1) * e);
    }
}
