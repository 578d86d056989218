/*
 * utf8.h - the one UTF-8 check that offbench's JSON reader (metajson.c)
 * and writer (ob_json_string, output.c) share, so that whatever one writes
 * the other takes back.
 */
#ifndef OB_UTF8_H
#define OB_UTF8_H

/* Length of the valid UTF-8 sequence at s (1..4; s < end), or 0: a byte
 * that starts none, a sequence cut short by end or by a byte that does not
 * continue it, an overlong form, a surrogate or a code point past
 * U+10FFFF. */
int ob_utf8_len(const unsigned char *s, const unsigned char *end);

#endif
