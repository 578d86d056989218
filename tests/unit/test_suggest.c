/*
 * test_suggest.c - "did you mean" (host/cli/suggest.h): the edit distance,
 * the choice of the closest name, the commands read from a usage text, and
 * the four places that use it, through their own parsers: an unknown option
 * (cliopts), an unknown method (--methods, --param), an unknown curve id
 * (--curve) and an unknown `list` subject.  The unknown command is main.c's
 * and is checked end to end (tests/e2e/e2e_didyoumean.sh).
 */
#include <string.h>

#include "tests/check.h"
#include "host/cli/cliopts.h"
#include "host/cli/commands.h"
#include "host/cli/suggest.h"
#include "host/diag.h"
#include "host/run/options.h"
#include "host/run/plan.h"

static char last_error[1024];
static void capture(const char *m) { snprintf(last_error, sizeof last_error, "%s", m); }

static void test_distance(void)
{
    CHECK(ob_edit_distance("tiller", "tiller", 2) == 0, "equal: 0");
    CHECK(ob_edit_distance("tiler", "tiller", 2) == 1, "one deletion: 1");
    CHECK(ob_edit_distance("tilelr", "tiller", 2) == 1, "adjacent transposition: 1");
    CHECK(ob_edit_distance("tullar", "tiller", 2) == 2, "two substitutions: 2");
    CHECK(ob_edit_distance("TILLER", "tiller", 2) == 0, "case is not a difference");
    CHECK(ob_edit_distance("", "abc", 5) == 3, "from empty: the length");
    CHECK(ob_edit_distance("abcdef", "uvwxyz", 2) == 3, "beyond the cap: cap + 1");
    CHECK(ob_edit_distance("a", "abcdefgh", 2) == 3, "length difference beyond the cap: cap + 1");
    char longw[600];
    memset(longw, 'x', sizeof longw - 1);
    longw[sizeof longw - 1] = '\0';
    CHECK(ob_edit_distance(longw, "x", 2) == 3, "a very long word: beyond the cap, no overflow");
}

static void test_choice(void)
{
    static const char *const methods[] = {"tiller", "cobb", "coquillart", "zhao", "zhao-rational", "cubic-opt"};
    const int n = (int)(sizeof methods / sizeof methods[0]);
    const char *s = ob_suggest("tiler", methods, n);
    CHECK(s && strcmp(s, "tiller") == 0, "tiler -> tiller: %s", s ? s : "(none)");
    s = ob_suggest("cobx", methods, n);
    CHECK(s && strcmp(s, "cobb") == 0, "cobx -> cobb: %s", s ? s : "(none)");
    s = ob_suggest("zhao-rationl", methods, n);
    CHECK(s && strcmp(s, "zhao-rational") == 0, "zhao-rationl -> zhao-rational: %s", s ? s : "(none)");
    s = ob_suggest("cubic", methods, n);
    CHECK(s && strcmp(s, "cubic-opt") == 0, "cubic: the one name it begins: %s", s ? s : "(none)");
    s = ob_suggest("zha", methods, n);
    CHECK(s && strcmp(s, "zhao") == 0, "zha: the closest of two it begins: %s", s ? s : "(none)");
    CHECK(ob_suggest("frobnicate", methods, n) == NULL, "nothing close: no suggestion");
    CHECK(ob_suggest("x", methods, n) == NULL, "one letter: no suggestion");
    CHECK(ob_suggest("", methods, n) == NULL, "empty: no suggestion");
    CHECK(ob_suggest("tiler", NULL, 0) == NULL, "no names: no suggestion");
    static const char *const tie[] = {"abcd", "abce"};
    s = ob_suggest("abcf", tie, 2);
    CHECK(s && strcmp(s, "abcd") == 0, "a tie: the first in the list: %s", s ? s : "(none)");

    char note[128];
    CHECK(strcmp(ob_suggest_note("tiler", methods, n, note, sizeof note), " (did you mean 'tiller'?)") == 0,
          "the note: '%s'", note);
    CHECK(strcmp(ob_suggest_note("frobnicate", methods, n, note, sizeof note), "") == 0, "no note: '%s'", note);
    CHECK(strcmp(ob_suggest_method_note("tiler", note, sizeof note), " (did you mean 'tiller'?)") == 0,
          "over the registered methods: '%s'", note);
}

static void test_usage_commands(void)
{
    static const char usage[] = "usage:\n"
                                "  ./offbench run    [--curves FILE]\n"
                                "                    [--tols ...]\n"
                                "  ./offbench compare BASE NEW\n"
                                "  ./offbench list   methods|curves\n"
                                "  ./offbench --version   (the build)\n"
                                "Every command takes --help.\n";
    char note[128];
    CHECK(strcmp(ob_suggest_command(usage, "rn", note, sizeof note), " (did you mean 'run'?)") == 0,
          "rn -> run: '%s'", note);
    CHECK(strcmp(ob_suggest_command(usage, "compar", note, sizeof note), " (did you mean 'compare'?)") == 0,
          "compar -> compare: '%s'", note);
    CHECK(strcmp(ob_suggest_command(usage, "lsit", note, sizeof note), " (did you mean 'list'?)") == 0,
          "lsit -> list: '%s'", note);
    CHECK(strcmp(ob_suggest_command(usage, "--versoin", note, sizeof note), " (did you mean '--version'?)") == 0,
          "--versoin -> --version: '%s'", note);
    CHECK(strcmp(ob_suggest_command(usage, "hepl", note, sizeof note), " (did you mean 'help'?)") == 0,
          "hepl -> help (always a command): '%s'", note);
    CHECK(strcmp(ob_suggest_command(usage, "frobnicate", note, sizeof note), "") == 0, "frobnicate: none: '%s'",
          note);
}

/* The run options of argv (NULL-terminated after "run"); 0 or the parser's status. */
static int parse_run(char **argv)
{
    int argc = 0;
    while (argv[argc])
        argc++;
    ob_run_opts o;
    last_error[0] = '\0';
    int rc = ob_run_opts_parse(argc, argv, &o);
    ob_run_opts_free(&o);
    return rc;
}

static void test_callers(void)
{
    ob_error_handler old = ob_set_error_handler(capture);

    char *a1[] = {"run", "--metod", "x", NULL};
    CHECK(parse_run(a1) != 0 && strcmp(last_error, "run: unknown option '--metod' (did you mean '--methods'?)") == 0,
          "unknown option: '%s'", last_error);
    char *a2[] = {"run", "--thread", "2", NULL}; /* an abbreviation: getopt takes it */
    CHECK(parse_run(a2) == 0, "an unambiguous abbreviation is still taken: '%s'", last_error);
    /* one or two letters are no abbreviation: `--d` is measure's offset, and
     * run's only option beginning with d is --device */
    char *a2b[] = {"run", "--d", "-1", NULL};
    CHECK(parse_run(a2b) != 0 && strcmp(last_error, "run: '--d' is too short to abbreviate --device (an abbreviation "
                                                    "needs three letters): write --device") == 0,
          "a one-letter abbreviation is refused: '%s'", last_error);
    char *a2c[] = {"run", "--th=2", NULL};
    CHECK(parse_run(a2c) != 0 && strstr(last_error, "'--th' is too short to abbreviate --threads"),
          "a two-letter one too, also as --name=value: '%s'", last_error);
    char *a2d[] = {"run", "--thr", "2", NULL};
    CHECK(parse_run(a2d) == 0, "three letters are an abbreviation: '%s'", last_error);
    char *a3[] = {"run", "--threds", "2", NULL};
    CHECK(parse_run(a3) != 0 && strcmp(last_error, "run: unknown option '--threds' (did you mean '--threads'?)") == 0,
          "unknown option: '%s'", last_error);
    char *a4[] = {"run", "--methods", "tiller,tiler", NULL};
    CHECK(parse_run(a4) != 0 &&
              strcmp(last_error, "--methods: unknown method 'tiler' (see './offbench list methods') "
                                 "(did you mean 'tiller'?)") == 0,
          "unknown method in --methods: '%s'", last_error);
    char *a5[] = {"run", "--param", "zhoa.degree=3", NULL};
    CHECK(parse_run(a5) != 0 && strcmp(last_error, "--param: unknown method 'zhoa' (did you mean 'zhao'?)") == 0,
          "unknown method in --param: '%s'", last_error);
    char *a6[] = {"run", "--methods", "frobnicate", NULL};
    CHECK(parse_run(a6) != 0 &&
              strcmp(last_error, "--methods: unknown method 'frobnicate' (see './offbench list methods')") == 0,
          "nothing close: the message as before: '%s'", last_error);

    /* an unknown curve id, among the curves loaded */
    char *a7[] = {"run", "--curve", "liu2002_ex3", NULL};
    ob_run_opts o;
    CHECK(ob_run_opts_parse(3, a7, &o) == 0, "run --curve liu2002_ex3 parses");
    ob_curveset set = {0};
    char where[4096];
    last_error[0] = '\0';
    CHECK(ob_load_run_curves(&o, &set, where, sizeof where) != 0 &&
              strstr(last_error, "--curve: no curve 'liu2002_ex3' in ") == last_error &&
              strstr(last_error, "(see './offbench list curves') (did you mean 'liu2002_ex1'?)"),
          "unknown curve id: '%s'", last_error);
    ob_curveset_free(&set);
    ob_run_opts_free(&o);

    /* an unknown subject of list */
    char *l1[] = {"list", "methds", NULL};
    last_error[0] = '\0';
    CHECK(ob_cmd_list(2, l1) == 2 && strstr(last_error, "list: unknown subject 'methds'") == last_error &&
              strstr(last_error, "(did you mean 'methods'?)"),
          "unknown list subject: '%s'", last_error);
    ob_set_error_handler(old);
}

int main(void)
{
    test_distance();
    test_choice();
    test_usage_commands();
    test_callers();
    return check_done();
}
