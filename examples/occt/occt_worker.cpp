// occt_worker.cpp - OpenCASCADE's offset as an offbench external method
// (docs/external-methods.md, protocol 1; docs/cad-example.md):
//
//     ./offbench run --external occt=build/occt_worker --methods occt,tiller
//
// Each request is one Bezier piece of the base: it becomes a
// Geom2d_BezierCurve (rational when a weight is not 1), its offset a
// Geom2d_OffsetCurve at d (OCCT's sign: occt_common.hpp), and that is
// approximated by Geom2dConvert_ApproxCurve(offset, tol, continuity, max
// segments, max degree), occt_offset.cpp's construction and defaults (C2,
// degree at most 8).  The B-spline is cut into its Bezier pieces
// (Geom2dConvert_BSplineCurveToBezierCurve), each raised to the declared
// degree (the protocol's pieces all have the hello's degree; OCCT may
// choose a lower one), and answered with the spans' base parameters and
// the B-spline's pole count as ctrl_points (a B-spline method's count, as
// for bspline-lsq and sisl).
//
// The reader takes exactly the request's shape and answers anything else
// with an error line, never a crash: a worker run by hand must survive a
// typo.  OCCT's exceptions are answers too.
//
// Options: --continuity C1|C2 (default C2), --max-degree N (default 8; 3
// with C1 is occt_table.py's occt-c1), --max-segments N (default 64, the
// protocol's most pieces).  Build: make occt-worker.
#include "occt_common.hpp"
#include "../workers/protocol.hpp"

#include <Geom2dConvert_ApproxCurve.hxx>
#include <Geom2dConvert_BSplineCurveToBezierCurve.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <Standard_Failure.hxx>
#include <Standard_Version.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>

#include <cctype>
#include <cstdio>
#include <exception>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

using occt_common::num;
using namespace ob_worker;

namespace {

// ------------------------------------------------------------ the fit

struct Opts {
    GeomAbs_Shape order = GeomAbs_C2;
    int max_degree = 8, max_segments = 64;
};

// The request's piece as OCCT holds it: the same control points and
// weights over [0, 1], so the same curve, parameter for parameter.
Handle(Geom2d_BezierCurve) base_of(const Request &r)
{
    const occt_common::Poles p(r.x, r.y, r.w);
    if (p.rational)
        return new Geom2d_BezierCurve(p.points, p.weights);
    return new Geom2d_BezierCurve(p.points);
}

// One answered piece: its poles (weights only when rational: OCCT's
// approximation is polynomial, so normally none).
std::string piece_json(const Handle(Geom2d_BezierCurve) &b)
{
    std::string s = "{\"degree\":" + std::to_string(b->Degree()) + ",\"points\":[";
    for (int i = 1; i <= b->NbPoles(); i++)
        s += (i > 1 ? ",[" : "[") + num(b->Pole(i).X()) + "," + num(b->Pole(i).Y()) + "]";
    s += "]";
    if (b->IsRational()) {
        s += ",\"weights\":[";
        for (int i = 1; i <= b->NbPoles(); i++)
            s += (i > 1 ? "," : "") + num(b->Weight(i));
        s += "]";
    }
    return s + "}";
}

// The answer to one request: the approximation's Bezier pieces at the
// declared degree, or an error.  OCCT's MaxError above the tolerance (its
// MaxSegments stopped the cutting, IsDone notwithstanding: occt_offset.cpp)
// is retry_smaller: the driver halves the piece, as for any method whose
// fit does not reach the tolerance.
std::string fit(const Opts &o, const Request &r)
{
    Handle(Geom2d_OffsetCurve) off = occt_common::offset_of(base_of(r), r.d);
    Geom2dConvert_ApproxCurve ap(off, r.tol, o.order, o.max_segments, o.max_degree);
    if (!ap.HasResult())
        return error_json(r.id, "Geom2dConvert_ApproxCurve: no result");
    if (!ap.IsDone() || ap.MaxError() > r.tol)
        return error_json(r.id, "OCCT's MaxError " + num(ap.MaxError()) + " is above the tolerance",
                          "retry_smaller");
    const Handle(Geom2d_BSplineCurve) a = ap.Curve();
    Geom2dConvert_BSplineCurveToBezierCurve cut(a);
    TColStd_Array1OfReal knots(1, cut.NbArcs() + 1);
    cut.Knots(knots);
    const double t0 = knots(1), t1 = knots(knots.Upper());
    std::string ps, ts;
    for (int i = 1; i <= cut.NbArcs(); i++) {
        Handle(Geom2d_BezierCurve) b = cut.Arc(i);
        if (b->Degree() < o.max_degree)
            b->Increase(o.max_degree);   // the hello's degree, the same curve
        ps += (i > 1 ? "," : "") + piece_json(b);
    }
    // The spans' parameters, as the offset's (the base's, [0, 1]): the
    // approximation keeps its curve's parameter range.
    for (int i = 1; i <= knots.Upper(); i++)
        ts += (i > 1 ? "," : "") + num(i == 1 ? 0.0 : i == knots.Upper() ? 1.0 : (knots(i) - t0) / (t1 - t0));
    return "{\"id\":" + std::to_string(r.id) + ",\"pieces\":[" + ps + "],\"t\":[" + ts +
           "],\"ctrl_points\":" + std::to_string(a->NbPoles()) + "}";
}

// One line in, one line out: every failure an error answer.
std::string answer(const Opts &o, const std::string &line)
{
    Request r;
    try {
        request_of(Reader(line).whole(), r, 25);   // Geom2d_BezierCurve's MaxDegree
        if (!r.params.obj.empty())                 // the hello declares no parameters
            throw BadRequest{"\"params\" is not {} (this method has no parameters)"};
        return fit(o, r);
    } catch (const BadRequest &e) {
        return error_json(r.id, "bad request: " + e.why);
    } catch (const Standard_Failure &e) {
        return error_json(r.id, std::string(e.DynamicType()->Name()) + ": " +
                                    (e.GetMessageString() ? e.GetMessageString() : ""));
    } catch (const std::exception &e) {
        return error_json(r.id, e.what());
    }
}

// ------------------------------------------------------------ the hello

// G1: AdvApprox makes each span meet the offset's value and derivatives
// at its ends (up to the continuity's order), so the pieces of one answer
// are C1 or C2 and neighbouring answers meet at the exact offset's point
// and tangent (the rows' max_kink is some 1e-13).
// The tolerance is OCCT's own: Geom2dConvert_ApproxCurve's Tol2d bounds
// the error AdvApprox estimates on its own samples (MaxError), not
// offbench's measured max_err: offbench measures every row itself.
std::string hello(const Opts &o)
{
    const char *c = o.order == GeomAbs_C1 ? "C1" : "C2";
    return std::string("{\"protocol\":1,\"citation\":\"OpenCASCADE ") + OCC_VERSION_COMPLETE +
           ": Geom2dConvert_ApproxCurve of a Geom2d_OffsetCurve (" + c + ", degree <= " +
           std::to_string(o.max_degree) + ", <= " + std::to_string(o.max_segments) +
           " spans a piece)\",\"degree\":" + std::to_string(o.max_degree) +
           ",\"continuity\":\"G1\",\"caps\":[\"poly_out\",\"rational_in\",\"tol_driven\"],\"uses_tol\":true,"
           "\"version\":1,\"params\":[]}";
}

[[noreturn]] void usage_error(const std::string &why)
{
    std::fprintf(stderr, "occt_worker: %s\nusage: occt_worker [--continuity C1|C2] [--max-degree N] "
                         "[--max-segments N]\n", why.c_str());
    std::exit(2);
}

Opts parse(int argc, char **argv)
{
    Opts o;
    for (int i = 1; i < argc; i++) {
        const std::string a = argv[i], v = i + 1 < argc ? argv[i + 1] : "";
        i++;
        const int n = std::atoi(v.c_str());
        if (a == "--continuity" && (v == "C1" || v == "C2"))
            o.order = v == "C1" ? GeomAbs_C1 : GeomAbs_C2;
        else if (a == "--max-degree" && n >= 1 && n <= 25)
            o.max_degree = n;
        else if (a == "--max-segments" && n >= 1 && n <= 64)   // the protocol's most pieces
            o.max_segments = n;
        else
            usage_error(a + " " + v + ": unknown option or bad value");
    }
    return o;
}

}  // namespace

int main(int argc, char **argv)
{
    const Opts o = parse(argc, argv);
    std::ios::sync_with_stdio(false);
    std::cout << hello(o) << '\n' << std::flush;
    for (std::string line; std::getline(std::cin, line);)
        std::cout << answer(o, line) << '\n' << std::flush;
    return 0;
}
