/*
 * utf8.c - see utf8.h.
 */
#include "host/io/utf8.h"

int ob_utf8_len(const unsigned char *s, const unsigned char *end)
{
    int n;
    unsigned min;
    if (*s < 0x80)
        return 1;
    if (*s >= 0xc2 && *s <= 0xdf)
        n = 2, min = 0x80;
    else if (*s >= 0xe0 && *s <= 0xef)
        n = 3, min = 0x800;
    else if (*s >= 0xf0 && *s <= 0xf4)
        n = 4, min = 0x10000;
    else
        return 0;
    if (end - s < n)
        return 0;
    unsigned cp = *s & (0x7f >> n);
    for (int i = 1; i < n; i++) {
        if ((s[i] & 0xc0) != 0x80)
            return 0;
        cp = cp << 6 | (s[i] & 0x3f);
    }
    return cp < min || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff) ? 0 : n;
}
