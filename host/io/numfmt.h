/*
 * numfmt.h - numbers in output files: '.' decimals, shortest text that reads
 * back as the same double (so full precision, like %.17g, without noise).
 */
#ifndef OB_NUMFMT_H
#define OB_NUMFMT_H

#include <stddef.h>

/* Writes the shortest round-trip form of x ("nan"/"inf" spelled so) into buf. */
void ob_fmt_double(char *buf, size_t len, double x);

/* Writes a bound x > 0 at 3 significant digits, rounded outward (up for an
 * upper bound, dir > 0; down for a lower one, dir < 0), so that what is
 * shown is still a bound; "inf" for +inf, x itself (%g) for x <= 0 or nan. */
void ob_fmt_bound(char *buf, size_t len, double x, int dir);

/* Parses a whole string as a finite double; 0 on success, -1 otherwise. */
int ob_parse_double(const char *s, double *out);

#endif
