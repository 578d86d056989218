// occt_trimmed.cpp - OpenCASCADE's trimmed offset of one Bezier curve or
// one polyline, as a DXF for `offbench measure --trimmed`
// (docs/export-measure.md "The trimmed offset";
// tests/e2e/e2e_occt_trimmed.sh):
//
//     occt_trimmed --d D --points "x0,y0 x1,y1 ..." --out FILE.dxf [--chords N]
//                  [--shape bezier|polyline]
//
// The curve is a Geom_BezierCurve in the plane z = 0 (--shape bezier, the
// default), its edge one wire, or (--shape polyline) the wire of line
// edges through the points (BRepBuilderAPI_MakePolygon: a corner at each
// inner point, which GeomAbs_Arc fills with a circle arc on its convex
// side); BRepOffsetAPI_MakeOffset(wire, GeomAbs_Arc, IsOpenResult = true)
// offsets it to one side: the offset a CAD kernel ships, its loops trimmed
// (OCCT's sign: occt_common.hpp, so OCCT is given -d).  Each edge of the
// result is written as it is: a line as one LINE, any other curve as N
// chords (LINEs) between points OCCT evaluates on it, whose chord error
// is printed (the largest distance of the edge from its chords, sampled 16
// times a chord) so that a measure can tell OCCT's error from ours.
// Prints, one line each: the edges by type, and "chord_error E".
// Exit status: 0; 1 OCCT gives no result (not done, or an empty shape);
// 2 bad arguments.  Build: make occt-trimmed.
#include <BRepAdaptor_Curve.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepOffsetAPI_MakeOffset.hxx>
#include <Geom_BezierCurve.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Wire.hxx>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Args {
    double d = 0;
    std::vector<gp_Pnt> points;
    std::string out;
    int chords = 2000;
    bool polyline = false;
};

[[noreturn]] void usage(const std::string &why)
{
    std::fprintf(stderr, "occt_trimmed: %s\nusage: occt_trimmed --d D --points \"x0,y0 x1,y1 ...\" --out FILE.dxf "
                         "[--chords N] [--shape bezier|polyline]\n", why.c_str());
    std::exit(2);
}

std::vector<gp_Pnt> points_of(const std::string &s)
{
    std::vector<gp_Pnt> v;
    std::istringstream in(s);
    std::string w;
    while (in >> w) {
        double x, y;
        char comma, rest;
        std::istringstream p(w);
        if (!(p >> x >> comma >> y) || comma != ',' || (p >> rest) || !std::isfinite(x) || !std::isfinite(y))
            usage("--points: '" + w + "' is not x,y");
        v.emplace_back(x, y, 0.0);
    }
    if (v.size() < 2 || v.size() > 26)
        usage("--points: 2 to 26 control points");
    return v;
}

Args parse(int argc, char **argv)
{
    Args a;
    bool have_d = false;
    for (int i = 1; i < argc; i++) {
        const std::string k = argv[i];
        if (i + 1 >= argc)
            usage(k + ": no value");
        const std::string v = argv[++i];
        char *end = nullptr;
        if (k == "--d") {
            a.d = std::strtod(v.c_str(), &end);
            if (*end || !std::isfinite(a.d) || a.d == 0)
                usage("--d: '" + v + "' is not a nonzero number");
            have_d = true;
        } else if (k == "--points") {
            a.points = points_of(v);
        } else if (k == "--out") {
            a.out = v;
        } else if (k == "--chords") {
            a.chords = std::atoi(v.c_str());
            if (a.chords < 1 || a.chords > 1000000)
                usage("--chords: 1 to 1000000");
        } else if (k == "--shape") {
            if (v != "bezier" && v != "polyline")
                usage("--shape: bezier or polyline, not '" + v + "'");
            a.polyline = v == "polyline";
        } else {
            usage("unknown option " + k);
        }
    }
    if (!have_d || a.points.empty() || a.out.empty())
        usage("--d, --points and --out are needed");
    return a;
}

void line(FILE *f, const gp_Pnt &p, const gp_Pnt &q)
{
    std::fprintf(f, "0\nLINE\n8\n0\n10\n%.17g\n20\n%.17g\n11\n%.17g\n21\n%.17g\n", p.X(), p.Y(), q.X(), q.Y());
}

// One edge as LINEs; the largest distance of the edge from its chords.
double write_edge(FILE *f, const BRepAdaptor_Curve &c, int chords)
{
    const double a = c.FirstParameter(), b = c.LastParameter();
    if (c.GetType() == GeomAbs_Line) {
        line(f, c.Value(a), c.Value(b));
        return 0.0;
    }
    double err = 0.0;
    for (int i = 0; i < chords; i++) {
        const double u0 = a + (b - a) * i / chords, u1 = a + (b - a) * (i + 1) / chords;
        const gp_Pnt p = c.Value(u0), q = c.Value(u1);
        line(f, p, q);
        const gp_Vec pq(p, q);
        for (int k = 1; k < 16; k++) {
            const gp_Vec pr(p, c.Value(u0 + (u1 - u0) * k / 16));
            const double s = pq.SquareMagnitude() > 0 ? std::fmin(1.0, std::fmax(0.0, pr.Dot(pq) / pq.SquareMagnitude())) : 0;
            err = std::fmax(err, (pr - s * pq).Magnitude());
        }
    }
    return err;
}

TopoDS_Wire bezier_wire(const std::vector<gp_Pnt> &points)
{
    TColgp_Array1OfPnt poles(1, (int)points.size());
    for (size_t i = 0; i < points.size(); i++)
        poles((int)i + 1) = points[i];
    Handle(Geom_BezierCurve) b = new Geom_BezierCurve(poles);
    return BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(b));
}

// An open polyline through the points, one line edge each.
TopoDS_Wire polyline_wire(const std::vector<gp_Pnt> &points)
{
    BRepBuilderAPI_MakePolygon poly;
    for (const gp_Pnt &p : points)
        poly.Add(p);
    return poly.Wire();
}

}  // namespace

int main(int argc, char **argv)
{
    const Args a = parse(argc, argv);
    try {
        const TopoDS_Wire w = a.polyline ? polyline_wire(a.points) : bezier_wire(a.points);
        BRepOffsetAPI_MakeOffset mo(w, GeomAbs_Arc, Standard_True);
        mo.Perform(-a.d);  // OCCT's side is offbench's other one (occt_common.hpp)
        if (!mo.IsDone()) {
            std::fprintf(stderr, "occt_trimmed: BRepOffsetAPI_MakeOffset is not done\n");
            return 1;
        }
        FILE *f = std::fopen(a.out.c_str(), "w");
        if (!f)
            usage("--out: cannot write " + a.out);
        std::fprintf(f, "0\nSECTION\n2\nENTITIES\n");
        int edges = 0, lines = 0;
        double err = 0.0;
        for (TopExp_Explorer x(mo.Shape(), TopAbs_EDGE); x.More(); x.Next(), edges++) {
            const BRepAdaptor_Curve c(TopoDS::Edge(x.Current()));
            lines += c.GetType() == GeomAbs_Line;
            err = std::fmax(err, write_edge(f, c, a.chords));
        }
        std::fprintf(f, "0\nENDSEC\n0\nEOF\n");
        std::fclose(f);
        std::printf("edges %d (lines %d, other curves %d)\nchord_error %.17g\n", edges, lines, edges - lines, err);
        if (edges == 0) {
            std::fprintf(stderr, "occt_trimmed: BRepOffsetAPI_MakeOffset gave no edge\n");
            return 1;
        }
    } catch (const Standard_Failure &e) {
        std::fprintf(stderr, "occt_trimmed: %s: %s\n", e.DynamicType()->Name(),
                     e.GetMessageString() ? e.GetMessageString() : "");
        return 1;
    }
    return 0;
}
