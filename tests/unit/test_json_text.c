/*
 * test_json_text.c - every string offbench writes into JSON (meta.json's
 * host name, CPU model, paths, argv: issue 48, item 12) comes out as valid
 * UTF-8 JSON that offbench's own reader takes back: bytes that are not
 * UTF-8 become U+FFFD, control characters are escaped, valid text is kept
 * byte for byte.
 */
#include "tests/check.h"

#include <stdlib.h>
#include <string.h>

#include "host/io/metajson.h"
#include "host/io/output.h"

/* s as ob_json_string writes it, into buf (quotes included). */
static const char *json_of(const char *s, char *buf, size_t len)
{
    FILE *f = tmpfile();
    if (!f)
        return "";
    ob_json_string(f, s);
    rewind(f);
    const size_t n = fread(buf, 1, len - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* 1 when {"k": <s as written>} parses and gives back want. */
static int reads_back(const char *s, const char *want)
{
    char js[256], text[300];
    snprintf(text, sizeof text, "{\"k\": %s}", json_of(s, js, sizeof js));
    ob_json_flat flat = {0};
    ob_err err;
    int ok = ob_json_flatten(text, strlen(text), "test", &flat, &err) == 0 && flat.n == 1 &&
             strcmp(flat.v[0].value, want) == 0;
    if (!ok)
        fprintf(stderr, "reads_back: %s: %s\n", text, err.msg);
    ob_json_free(&flat);
    return ok;
}

int main(void)
{
    char b[256];
    /* valid text, ASCII and multi-byte, is kept as it is */
    CHECK(strcmp(json_of("host-1", b, sizeof b), "\"host-1\"") == 0, "%s", b);
    CHECK(strcmp(json_of("Maschine \xc3\xbc \xe2\x82\xac \xf0\x9f\x98\x80", b, sizeof b),
                 "\"Maschine \xc3\xbc \xe2\x82\xac \xf0\x9f\x98\x80\"") == 0, "%s", b);
    CHECK(strcmp(json_of("a\"b\\c", b, sizeof b), "\"a\\\"b\\\\c\"") == 0, "%s", b);
    /* a byte that is no UTF-8: U+FFFD, one per byte */
    CHECK(strcmp(json_of("a\377b", b, sizeof b), "\"a\\ufffdb\"") == 0, "%s", b);
    CHECK(strcmp(json_of("/tmp/d\377\376ir", b, sizeof b), "\"/tmp/d\\ufffd\\ufffdir\"") == 0, "%s", b);
    /* a sequence cut short (the end, or an ASCII byte after its lead) */
    CHECK(strcmp(json_of("x\xc3", b, sizeof b), "\"x\\ufffd\"") == 0, "%s", b);
    CHECK(strcmp(json_of("\xe2\x82z", b, sizeof b), "\"\\ufffd\\ufffdz\"") == 0, "%s", b);
    /* overlong forms and surrogates are not UTF-8 either */
    CHECK(strcmp(json_of("\xc0\x80", b, sizeof b), "\"\\ufffd\\ufffd\"") == 0, "%s", b);
    CHECK(strcmp(json_of("\xed\xa0\x80", b, sizeof b), "\"\\ufffd\\ufffd\\ufffd\"") == 0, "%s", b);
    /* control characters, DEL included, escaped */
    CHECK(strcmp(json_of("a\tb\033c\177", b, sizeof b), "\"a\\u0009b\\u001bc\\u007f\"") == 0, "%s", b);
    /* and offbench's own reader takes each back */
    CHECK(reads_back("a\377b", "a\xef\xbf\xbd" "b"), "invalid byte");
    CHECK(reads_back("x\xc3", "x\xef\xbf\xbd"), "cut sequence");
    CHECK(reads_back("\xed\xa0\x80", "\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd"), "surrogate");
    CHECK(reads_back("a\tb\033c", "a\tb\033c"), "control characters");
    CHECK(reads_back("Maschine \xc3\xbc", "Maschine \xc3\xbc"), "valid UTF-8");
    return check_done();
}
