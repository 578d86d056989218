/*
 * fuzz_compare.c - libFuzzer target: the readers of `compare` (a run's
 * results.csv, its samples.csv and meta.json: host/io/results_csv.c,
 * host/io/metajson.c) on arbitrary bytes must return 0 or -1 with a NAME:LINE
 * message, never crash, overrun or leak.  The input is read as all three;
 * when it parses as a results table it is also attached to itself as
 * samples (the key lookups run on whatever parsed).
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "host/io/metajson.h"
#include "host/io/results_csv.h"

static void check_message(const char *err, const char *name)
{
    if (strncmp(err, name, strlen(name)) != 0)
        __builtin_trap();  /* every error names the input */
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *text = (const char *)data;
    ob_err err;
    ob_res_table t;
    err.msg[0] = '\0';
    if (ob_res_parse(text, size, "fuzz.csv", &t, &err) != 0) {
        check_message(err.msg, "fuzz.csv");
    } else {
        err.msg[0] = '\0';
        if (ob_res_attach_samples(&t, text, size, "fuzz-samples.csv", &err) != 0)
            check_message(err.msg, "fuzz-samples.csv");
        for (int i = 0; i < t.n; i++)
            if (ob_res_find(&t, &t.v[i]) == NULL)
                __builtin_trap();  /* every row is found by its own key */
    }
    ob_res_free(&t);
    ob_json_flat j;
    err.msg[0] = '\0';
    if (ob_json_flatten(text, size, "fuzz.json", &j, &err) != 0)
        check_message(err.msg, "fuzz.json");
    ob_json_free(&j);
    return 0;
}
