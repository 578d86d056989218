/*
 * test_ext_json.c - the strict one-line JSON reader of the external-method
 * supervisor (methods/external/json.h): an answer's shape read back, every
 * double printed with %.17g read back to the same bits, and what a broken
 * worker may send refused with a reason (NaN, an infinity, trailing
 * commas, text after the value, a lone surrogate, too deep), never a crash.
 */
#include <stdio.h>
#include <string.h>

#include "tests/check.h"
#include "methods/external/json.h"

static int refused(const char *s, const char *why)
{
    char err[160];
    obj_node *v = obj_parse(s, strlen(s), err, sizeof err);
    const int ok = !v && strstr(err, why) != NULL;
    if (!ok)
        fprintf(stderr, "  '%s': got '%s', want '%s'\n", s, v ? "(parsed)" : err, why);
    obj_free(v);
    return ok;
}

int main(void)
{
    const char *ans = "{\"id\": 3, \"pieces\": [{\"degree\": 1, \"points\": [[0, -1.5e-3], [2, 4]]}], "
                      "\"s\": \"a\\u00e9\\ud83d\\ude00\\n\", \"ok\": true, \"no\": null}";
    char err[160];
    obj_node *v = obj_parse(ans, strlen(ans), err, sizeof err);
    CHECK(v && v->type == OBJ_OBJ && v->n == 5, "an answer parses: %s", v ? "" : err);
    const obj_node *ps = obj_get(v, "pieces"), *p0 = ps && ps->n ? ps->kids[0] : NULL;
    const obj_node *pts = obj_get(p0, "points");
    CHECK(obj_get(v, "id")->num == 3 && pts && pts->n == 2 && pts->kids[0]->kids[1]->num == -1.5e-3,
          "its members by name");
    CHECK(strcmp(obj_get(v, "s")->str, "a\xc3\xa9\xf0\x9f\x98\x80\n") == 0, "escapes and a surrogate pair as UTF-8");
    CHECK(obj_get(v, "ok")->type == OBJ_BOOL && obj_get(v, "no")->type == OBJ_NULL && !obj_get(v, "x"),
          "true, null, a missing key");
    obj_free(v);

    /* %.17g round trip: the numbers of a request come back as the same doubles */
    const double xs[] = {0.1, 1.0 / 3.0, -2.2250738585072014e-308, 4.9e-324, 1.7976931348623157e308, 123456.789e-7};
    int same = 1;
    for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++) {
        char t[64];
        snprintf(t, sizeof t, "%.17g", xs[i]);
        obj_node *n = obj_parse(t, strlen(t), err, sizeof err);
        same &= n && memcmp(&n->num, &xs[i], sizeof(double)) == 0;
        obj_free(n);
    }
    CHECK(same, "%%.17g reads back to the same bits");

    CHECK(refused("{\"x\": NaN}", "not a JSON value"), "NaN");
    CHECK(refused("[1e999]", "out of the double range"), "an infinity");
    CHECK(refused("[1, 2,]", "not a JSON value"), "a trailing comma");
    CHECK(refused("{\"a\": 1} x", "text after the value"), "text after the value");
    CHECK(refused("\"\\ud800\"", "malformed string"), "a lone surrogate");
    CHECK(refused("\"\\u0000\"", "malformed string"), "\\u0000");
    CHECK(refused("[[[[[[[[[[1]]]]]]]]]]", "nested too deep"), "too deep");
    CHECK(refused("{1: 2}", "quoted key"), "an unquoted key");
    CHECK(refused("", "missing"), "nothing");
    CHECK(refused("01", "text after the value"), "a leading zero");
    return check_done();
}
