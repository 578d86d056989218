/*
 * where_out.c - the --per-piece and --draw files (where_out.h).
 */
#include "host/cli/where_out.h"

#include <string.h>
#include <sys/stat.h>

#include "host/diag.h"
#include "host/io/fsutil.h"
#include "host/view/draw_approx.h"

/* The directory of path (stat'ed into *st) and its last name; 0, or -1
 * when the directory cannot be stat'ed. */
static int dir_of(const char *path, struct stat *st, const char **base)
{
    char dir[4200];
    const char *slash = strrchr(path, '/');
    *base = slash ? slash + 1 : path;
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else
        snprintf(dir, sizeof dir, "%.*s", slash == path ? 1 : (int)(slash - path), path);
    return stat(dir, st);
}

/* Do a and b name one file (the same node, or, where neither exists yet,
 * the same name in the same directory)? */
static int same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    const int ea = stat(a, &sa) == 0, eb = stat(b, &sb) == 0;
    if (ea || eb)
        return ea && eb && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    const char *ba, *bb;
    return dir_of(a, &sa, &ba) == 0 && dir_of(b, &sb, &bb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino && strcmp(ba, bb) == 0;
}

int ob_where_check(const char *cmd, const ob_where_out *o, const char *const *in, int n)
{
    if (o->per_piece && ob_check_file_not_input(cmd, "--per-piece", o->per_piece, in, (size_t)n) != 0)
        return 2;
    if (o->draw && ob_check_file_not_input(cmd, o->draw_opt, o->draw, in, (size_t)n) != 0)
        return 2;
    if (o->per_piece && o->draw && same_file(o->per_piece, o->draw)) {
        ob_error("%s: %s %s and --per-piece %s are one file: choose another %s", cmd, o->draw_opt, o->draw,
                 o->per_piece, o->draw_opt);
        return 2;
    }
    return 0;
}

typedef struct {
    const ob_pp_file *files;
    int n;
} csv_ctx;

static int write_csv(FILE *f, const void *ctx)
{
    const csv_ctx *c = ctx;
    return ob_perpiece_csv(f, c->files, c->n);
}

int ob_where_write(const ob_where_out *o, const ob_curve *c, double d, const ob_pp_file *files, int n)
{
    const csv_ctx cc = {files, n};
    if (o->per_piece && ob_pp_write("--per-piece", o->per_piece, write_csv, &cc) != 0)
        return 1;
    const ob_draw_approx dv = {c, d, files, n};
    if (o->draw && ob_pp_write(o->draw_opt, o->draw, ob_draw_approx_svg, &dv) != 0)
        return 1;
    return 0;
}
