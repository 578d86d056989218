/*
 * test_strmap.c - the string map behind the readers' duplicate checks and
 * look-ups (host/io/strmap.h): put, get, a key given twice, keys that are
 * prefixes of each other or hold any bytes, growth over many keys, free.
 */
#include <stdio.h>
#include <string.h>

#include "tests/check.h"
#include "host/io/strmap.h"

int main(void)
{
    ob_strmap m = {0};
    CHECK(ob_strmap_get(&m, "a") == -1, "empty map: nothing found");
    CHECK(ob_strmap_put(&m, "a", 7) == -1 && ob_strmap_get(&m, "a") == 7, "put, get");
    CHECK(ob_strmap_put(&m, "a", 9) == 7 && ob_strmap_get(&m, "a") == 7, "a key twice: the first value stays");
    CHECK(ob_strmap_put(&m, "ab", 1) == -1 && ob_strmap_put(&m, "", 2) == -1, "prefix and empty keys");
    CHECK(ob_strmap_get(&m, "ab") == 1 && ob_strmap_get(&m, "") == 2 && ob_strmap_get(&m, "b") == -1,
          "prefix and empty keys found apart");
    CHECK(ob_strmap_putn(&m, "x\0y", 3, 3) == -1 && ob_strmap_getn(&m, "x\0y", 3) == 3 &&
              ob_strmap_getn(&m, "x\0z", 3) == -1 && ob_strmap_get(&m, "x") == -1,
          "keys with a NUL byte, by length");
    /* many keys: the table grows several times; every key keeps its value */
    char key[32];
    int bad = 0;
    for (long i = 0; i < 100000; i++) {
        snprintf(key, sizeof key, "k%ld", i);
        bad += ob_strmap_put(&m, key, i) != -1;
    }
    for (long i = 0; i < 100000; i++) {
        snprintf(key, sizeof key, "k%ld", i);
        bad += ob_strmap_get(&m, key) != i;
        bad += ob_strmap_put(&m, key, 0) != i;
    }
    CHECK(bad == 0 && m.n == 100004, "100000 keys: %d wrong, %zu in the map", bad, m.n);
    CHECK(ob_strmap_get(&m, "a") == 7, "the first keys survive the growth");
    ob_strmap_free(&m);
    CHECK(m.n == 0 && ob_strmap_get(&m, "a") == -1, "free empties the map");
    ob_strmap_free(&m);
    CHECK(ob_strmap_put(&m, "again", 1) == -1 && ob_strmap_get(&m, "again") == 1, "usable after free");
    ob_strmap_free(&m);
    return check_done();
}
