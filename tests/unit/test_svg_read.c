/*
 * test_svg_read.c - the SVG reader of measure (host/io/approx_read_svg.c and
 * its parts svg_path.c, svg_frame.c):
 *   - elliptical arcs of radius 1e3 to 1e300 (near-straight: the centre
 *     far away), 0 (a line) and tiny (scaled up to the half circle on the
 *     chord), every flag combination: each piece's points on the circle SVG
 *     1.1 F.6.5 defines, by the analytic distance (no far centre in it),
 *     to 1e-14 of the arc's size, the ends bit for bit;
 *   - NaN, inf and out-of-range numbers in path data: an error naming the
 *     file, the line and the element;
 *   - the XML (a real parser): an attribute's name inside another's value,
 *     '>' in a value, comments, CDATA and entity references.
 * With `--dump FILE` it prints the pieces the reader makes of FILE (one
 * line each: degree, then x y w per control point, %.17g) and exits: the
 * C side of tests/e2e/e2e_svg_xml.sh, which compares them with
 * scripts/svg2curves.py's.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "host/io/approx_read.h"
#include "host/io/slurp.h"

static int read_text(const char *text, ob_approx *ap, ob_err *err)
{
    memset(ap, 0, sizeof *ap);
    return ob_approx_read_svg(text, strlen(text), "t.svg", ap, err);
}

/* The signed distance of P (reader coordinates: y up) from the circle of
 * radius R through (0, 0) and (1, 0) (SVG coordinates) whose centre is at
 * SVG (0.5, sgn h), h = sqrt(R^2 - 1/4): (|P - C|^2 - R^2) / (2R) written
 * without the far centre, in long double (R^2 overflows a double). */
static long double circle_dist(double x, double y, double R, double sgn)
{
    const long double px = (long double)x - 0.5L, py = -(long double)y; /* SVG y, from the midpoint */
    const long double s = 0.5L, hr = sqrtl((1.0L - s / R) * (1.0L + s / R)); /* h / R */
    return (px * px + py * py - s * s) / (2.0L * R) - hr * (long double)sgn * py;
}

/* One arc from (0,0) to (1,0) of radius R and flags: every piece's sampled
 * points within 1e-14 of the arc's size of the circle, the ends exact. */
static void check_arc(double R, int large, int sweep)
{
    char svg[256];
    snprintf(svg, sizeof svg, "<svg><path d=\"M0 0 A %.17g %.17g 0 %d %d 1 0\"/></svg>", R, R, large, sweep);
    ob_approx ap;
    ob_err err;
    const int rc = read_text(svg, &ap, &err);
    CHECK(rc == 0 && ap.n >= 1, "R %g flags %d%d: %s", R, large, sweep, rc ? err.msg : "no piece");
    if (rc || ap.n < 1)
        return;
    const double Re = R < 0.5 ? 0.5 : R; /* too small: scaled up (F.6.6) */
    const double sgn = R < 0.5 ? 0.0 : large != sweep ? 1.0 : -1.0;
    const double size = large || R < 0.5 ? Re : 1.0;
    double worst = 0.0, p0[2], p1[2];
    ob_bez_ctrl(&ap.v[0].approx, 0, p0);
    ob_bez_ctrl(&ap.v[ap.n - 1].approx, ap.v[ap.n - 1].approx.deg, p1);
    for (int k = 0; k < ap.n; k++)
        for (int i = 0; i <= 16; i++) {
            double o[1][2];
            ob_bez_eval(&ap.v[k].approx, i / 16.0, 0, o);
            const double d = (double)fabsl(circle_dist(o[0][0], o[0][1], Re, sgn));
            worst = isfinite(d) && d > worst ? d : isfinite(d) ? worst : INFINITY;
        }
    CHECK(worst <= 1e-14 * size, "R %g flags large %d sweep %d: %d pieces, %.3g from the circle (size %g)", R,
          large, sweep, ap.n, worst, size);
    CHECK(p0[0] == 0.0 && p0[1] == 0.0 && p1[0] == 1.0 && p1[1] == 0.0,
          "R %g flags %d%d: ends (%.17g %.17g) (%.17g %.17g)", R, large, sweep, p0[0], p0[1], p1[0], p1[1]);
    /* the arc's side: sweep 1 runs clockwise on screen, so from (0,0) to
     * (1,0) the small arc bulges up in SVG's y (down): y < 0 there, > 0 here */
    double mid[1][2];
    ob_bez_eval(&ap.v[(ap.n - 1) / 2].approx, ap.n % 2 ? 0.5 : 1.0, 0, mid);
    const int up = mid[0][1] > 0.0;
    CHECK(R > 1e15 || up == (sweep != 0), "R %g flags %d%d: the arc on the wrong side (mid y %.3g)", R, large,
          sweep, mid[0][1]);
    ob_approx_free(&ap);
}

static void test_arcs(void)
{
    static const double radii[] = {0.5, 0.7, 1e3, 1e8, 1e12, 1e16, 1e20, 1e300, 1e-3, 1e-300};
    for (size_t r = 0; r < sizeof radii / sizeof *radii; r++)
        for (int f = 0; f < 4; f++)
            check_arc(radii[r], f >> 1, f & 1);
    /* radius 0: a line (SVG 1.1 F.6.2), whatever the other radius and flags */
    for (int f = 0; f < 4; f++) {
        char svg[128];
        snprintf(svg, sizeof svg, "<svg><path d=\"M0 0 A 0 %d 0 %d %d 1 0\"/></svg>", f * 7, f >> 1, f & 1);
        ob_approx ap;
        ob_err err;
        const int rc = read_text(svg, &ap, &err);
        CHECK(rc == 0 && ap.n == 1 && ap.v[0].approx.deg == 1, "radius 0 (%s): one line: rc %d, %d pieces", svg,
              rc, ap.n);
        ob_approx_free(&ap);
    }
}

/* An error that names the file, the line and the element. */
static void check_error(const char *svg, const char *want)
{
    ob_approx ap;
    ob_err err;
    const int rc = read_text(svg, &ap, &err);
    CHECK(rc != 0 && strstr(err.msg, want), "%s: want an error with '%s', got %d '%s'", svg, want, rc,
          rc ? err.msg : "");
    ob_approx_free(&ap);
}

static void test_bad_numbers(void)
{
    check_error("<svg>\n<path d=\"M0 0 A NaN 1 0 0 1 1 0\"/></svg>", "t.svg:2: <path>: d: at character 8");
    check_error("<svg>\n\n<path d=\"M0 0 A inf 1 0 0 1 1 0\"/></svg>", "t.svg:3: <path>: d: at character 8");
    check_error("<svg>\n<path d=\"M0 0 A 1e999 1 0 0 1 1 0\"/></svg>", "t.svg:2: <path>: d: at character 8");
    check_error("<svg>\n<path d=\"M0 0 L 1 -Infinity\"/></svg>", "t.svg:2: <path>: d: at character 10");
    check_error("<svg>\n<circle r=\"nan\"/></svg>", "t.svg:2: <circle>: r");
}

/* The pieces of svg (reader coordinates) against want[n][2] lines' ends. */
static void check_lines(const char *what, const char *svg, int n, const double (*want)[4])
{
    ob_approx ap;
    ob_err err;
    const int rc = read_text(svg, &ap, &err);
    CHECK(rc == 0 && ap.n == n, "%s: rc %d, %d pieces (want %d): %s", what, rc, ap.n, n, rc ? err.msg : "");
    for (int k = 0; rc == 0 && k < n && k < ap.n; k++) {
        double a[2], b[2];
        ob_bez_ctrl(&ap.v[k].approx, 0, a);
        ob_bez_ctrl(&ap.v[k].approx, ap.v[k].approx.deg, b);
        CHECK(fabs(a[0] - want[k][0]) + fabs(a[1] - want[k][1]) + fabs(b[0] - want[k][2]) +
                      fabs(b[1] - want[k][3]) <= 1e-12,
              "%s: piece %d (%g %g)-(%g %g), want (%g %g)-(%g %g)", what, k, a[0], a[1], b[0], b[1], want[k][0],
              want[k][1], want[k][2], want[k][3]);
    }
    ob_approx_free(&ap);
}

static void test_xml(void)
{
    static const double one[][4] = {{0, 0, 1, 0}};
    static const double moved[][4] = {{10, 0, 11, 0}};
    check_lines("an attribute name in another's value",
                "<svg><path id=\" d='M 5 5 L 9 9'\" d=\"M0 0 L1 0\"/></svg>", 1, one);
    check_lines("'>' in a value, then a transform",
                "<svg><path class=\"a>b\" d=\"M0 0 L1 0\" transform=\"translate(10)\"/></svg>", 1, moved);
    check_lines("a comment, CDATA and an entity",
                "<!DOCTYPE svg [<!ENTITY p \"M0 0 L1 0\">]><svg><!-- <path d=\"M 7 7 L 8 8\"/> -->"
                "<desc><![CDATA[<path d=\"M 7 7 L 8 8\"/>]]></desc><path d=\"&p;\"/></svg>",
                1, one);
    check_lines("a character reference", "<svg><path d=\"M0&#x20;0 L1 0\"/></svg>", 1, one);
    check_error("<svg>\n<path d=\"M0 0 L1 0\"></svg>", "t.svg:2");
}

static int dump(const char *path)
{
    ob_approx ap = {0};
    ob_err err;
    size_t len;
    char *text = NULL;
    if (ob_slurp(path, &text, &len, &err) != 0 || ob_approx_read_svg(text, len, path, &ap, &err) != 0) {
        fprintf(stderr, "%s\n", err.msg);
        free(text);
        ob_approx_free(&ap);
        return 2;
    }
    for (int k = 0; k < ap.n; k++) {
        const ob_bez *b = &ap.v[k].approx;
        printf("%d", b->deg);
        for (int i = 0; i <= b->deg; i++) {
            double p[2];
            ob_bez_ctrl(b, i, p);
            printf(" %.17g %.17g %.17g", p[0], p[1], ob_bez_weight(b, i));
        }
        printf("\n");
    }
    for (int i = 0; i < ap.nskipped_types; i++)
        fprintf(stderr, "skipped %d %s (line %d)\n", ap.skipped[i].count, ap.skipped[i].type, ap.skipped[i].line);
    free(text);
    ob_approx_free(&ap);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 3 && !strcmp(argv[1], "--dump"))
        return dump(argv[2]);
    test_arcs();
    test_bad_numbers();
    test_xml();
    return check_done();
}
