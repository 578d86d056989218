/*
 * export_dxf.c - a job's approximation as DXF SPLINE entities (export.h).
 *
 * R12 has no SPLINE, so this is the smallest AC1015 (AutoCAD 2000) file
 * that CAD readers take: a HEADER with $ACADVER and an ENTITIES section
 * (ezdxf reads and audits it without a fix: tests/e2e/e2e_export.sh).  One
 * SPLINE per Bézier piece: degree p, knots p + 1 zeros and p + 1 ones,
 * the Euclidean control points (group codes 10/20/30), and for a rational
 * piece its weights (41; flag 4).  One entity per piece keeps every piece
 * exact and in its own parameter, also where pieces do not meet (open
 * joints) or change degree; a CAD system joins them as it likes.
 *
 * A 999 comment before each entity says which base piece it approximates
 * (approx.h), in the form `measure` reads back:
 *   offbench piece K base segment S span A B fit T0 T1 same_param 0|1
 */
#include "host/io/export.h"

static void code(FILE *f, int c, const char *v) { fprintf(f, "%d\n%s\n", c, v); }

/* A run of fixed group codes and values. */
typedef struct {
    int code;
    const char *value;
} dxf_pair;

static void codes(FILE *f, const dxf_pair *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        code(f, v[i].code, v[i].value);
}

/* The HEADER (version, unitless) and the opening of ENTITIES. */
static const dxf_pair file_head[] = {
    {0, "SECTION"}, {2, "HEADER"}, {9, "$ACADVER"}, {1, "AC1015"}, {9, "$INSUNITS"}, {70, "0"},
    {0, "ENDSEC"},  {0, "SECTION"}, {2, "ENTITIES"},
};

/* What follows a SPLINE's handle: its layer and the plane's normal (0,0,1). */
static const dxf_pair spline_head[] = {
    {100, "AcDbEntity"}, {8, "OFFBENCH"}, {100, "AcDbSpline"}, {210, "0"}, {220, "0"}, {230, "1"},
};

static void codenum(FILE *f, int c, double x)
{
    fprintf(f, "%d\n", c);
    ob_export_num(f, x, 0);
    fputc('\n', f);
}

static void spline(FILE *f, const ob_apiece *p, int k, int same_param, unsigned handle)
{
    const ob_bez *b = &p->approx;
    fprintf(f, "999\noffbench piece %d base segment %d ", k, p->seg);
    ob_export_span(f, p);
    fprintf(f, " same_param %d\n", same_param);
    code(f, 0, "SPLINE");
    fprintf(f, "5\n%X\n", handle);
    codes(f, spline_head, sizeof spline_head / sizeof spline_head[0]);
    fprintf(f, "70\n%d\n71\n%d\n72\n%d\n73\n%d\n74\n0\n", 8 | (b->rational ? 4 : 0), b->deg, 2 * (b->deg + 1),
            b->deg + 1);
    code(f, 42, "1e-10");
    code(f, 43, "1e-10");
    for (int i = 0; i < 2 * (b->deg + 1); i++)
        code(f, 40, i > b->deg ? "1" : "0");
    if (b->rational)
        for (int i = 0; i <= b->deg; i++)
            codenum(f, 41, b->h[i][2]);
    for (int i = 0; i <= b->deg; i++) {
        double q[2];
        ob_bez_ctrl(b, i, q);
        codenum(f, 10, q[0]);
        codenum(f, 20, q[1]);
        code(f, 30, "0");
    }
}

int ob_export_write_dxf(FILE *f, const ob_job *j, const ob_approx *a)
{
    char stem[400];
    ob_export_stem(stem, sizeof stem, j);
    fprintf(f, "999\noffbench export: the approximation of job %s, max_err ", stem);
    ob_export_num(f, j->max_err, 0);
    fputc('\n', f);
    codes(f, file_head, sizeof file_head / sizeof file_head[0]);
    for (int i = 0; i < a->n; i++)
        spline(f, &a->v[i], i, a->same_param, 0x100u + (unsigned)i);
    code(f, 0, "ENDSEC");
    code(f, 0, "EOF");
    return ferror(f) ? -1 : 0;
}
