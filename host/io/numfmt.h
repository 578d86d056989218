/*
 * numfmt.h - numbers in output files: '.' decimals, shortest text that reads
 * back as the same double (so full precision, like %.17g, without noise).
 */
#ifndef OB_NUMFMT_H
#define OB_NUMFMT_H

#include <stddef.h>

/* Writes the shortest round-trip form of x ("nan"/"inf" spelled so) into buf. */
void ob_fmt_double(char *buf, size_t len, double x);

/* Parses a whole string as a finite double; 0 on success, -1 otherwise. */
int ob_parse_double(const char *s, double *out);

#endif
