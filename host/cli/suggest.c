/*
 * suggest.c - "did you mean".  See suggest.h.
 */
#include "host/cli/suggest.h"
#include "host/cli/methods_file.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "methods/method.h"

enum {
    SUGGEST_MAX_LEN = 256,     /* longer words get no suggestion */
    SUGGEST_CAP = 2,           /* the most edits a suggestion is away */
    SUGGEST_MAX_METHODS = 128, /* names taken from the registry */
    SUGGEST_MAX_COMMANDS = 64, /* and from the usage text */
    SUGGEST_COMMAND_LEN = 32,
};

static int same_char(char a, char b)
{
    return tolower((unsigned char)a) == tolower((unsigned char)b);
}

static int min3(int a, int b, int c)
{
    const int m = a < b ? a : b;
    return m < c ? m : c;
}

int ob_edit_distance(const char *a, const char *b, int cap)
{
    const int la = (int)strnlen(a, SUGGEST_MAX_LEN + 1), lb = (int)strnlen(b, SUGGEST_MAX_LEN + 1);
    if (la > SUGGEST_MAX_LEN || lb > SUGGEST_MAX_LEN || la - lb > cap || lb - la > cap)
        return cap + 1;
    /* three rows of the dynamic programme: i-2, i-1, i */
    int rows[3][SUGGEST_MAX_LEN + 1];
    int *pp = rows[0], *p = rows[1], *c = rows[2];
    for (int j = 0; j <= lb; j++)
        p[j] = j;
    for (int i = 1; i <= la; i++) {
        c[0] = i;
        int best = c[0];
        for (int j = 1; j <= lb; j++) {
            const int cost = same_char(a[i - 1], b[j - 1]) ? 0 : 1;
            c[j] = min3(p[j] + 1, c[j - 1] + 1, p[j - 1] + cost);
            if (i > 1 && j > 1 && same_char(a[i - 1], b[j - 2]) && same_char(a[i - 2], b[j - 1]) &&
                pp[j - 2] + 1 < c[j])
                c[j] = pp[j - 2] + 1;
            if (c[j] < best)
                best = c[j];
        }
        if (best > cap)
            return cap + 1;
        int *t = pp;
        pp = p;
        p = c;
        c = t;
    }
    return p[lb] > cap ? cap + 1 : p[lb];
}

/* Whether name begins with word, case ignored. */
static int begins_with(const char *name, const char *word)
{
    for (; *word; word++, name++)
        if (!*name || !same_char(*name, *word))
            return 0;
    return 1;
}

const char *ob_suggest(const char *word, const char *const *names, int n)
{
    const int len = (int)strnlen(word, SUGGEST_MAX_LEN + 1);
    const char *best = NULL, *prefixed = NULL;
    int best_d = SUGGEST_CAP + 1, nprefixed = 0;
    for (int i = 0; names && i < n; i++) {
        if (!names[i])
            continue;
        const int d = ob_edit_distance(word, names[i], SUGGEST_CAP);
        if (d < best_d && d < len) {
            best_d = d;
            best = names[i];
        }
        if (len >= 2 && begins_with(names[i], word) && nprefixed++ == 0)
            prefixed = names[i];
    }
    if (best)
        return best;
    return nprefixed == 1 ? prefixed : NULL;
}

const char *ob_suggest_note(const char *word, const char *const *names, int n, char *buf, size_t len)
{
    const char *s = ob_suggest(word, names, n);
    if (len > 0)
        buf[0] = '\0';
    if (s && len > 0)
        snprintf(buf, len, " (did you mean '%s'?)", s);
    return buf;
}

const char *ob_suggest_method_note(const char *name, char *buf, size_t len)
{
    if (ob_methods_file_note(name, buf, len))  /* named by a methods file, its program missing */
        return buf;
    const char *names[SUGGEST_MAX_METHODS];
    int n = 0;
    for (int i = 0; ob_methods[i] && n < (int)(sizeof names / sizeof names[0]); i++)
        names[n++] = ob_methods[i]->name;
    return ob_suggest_note(name, names, n, buf, len);
}

const char *ob_suggest_command(const char *usage, const char *word, char *buf, size_t len)
{
    static const char lead[] = "\n  ./offbench ";
    char store[SUGGEST_MAX_COMMANDS][SUGGEST_COMMAND_LEN];
    const char *names[SUGGEST_MAX_COMMANDS];
    int n = 0;
    names[n++] = "help";
    for (const char *p = usage; n < SUGGEST_MAX_COMMANDS && (p = strstr(p, lead)) != NULL;) {
        p += sizeof lead - 1;
        const size_t k = strcspn(p, " \n");
        if (k == 0 || k >= SUGGEST_COMMAND_LEN)
            continue;
        memcpy(store[n], p, k);
        store[n][k] = '\0';
        names[n] = store[n];
        n++;
    }
    return ob_suggest_note(word, names, n, buf, len);
}
