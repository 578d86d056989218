// lib2geom_worker.cpp - Inkscape's geometry library's offset as an offbench
// external method (docs/external-methods.md, protocol 1; docs/cad-example.md
// "A graphics library's offset: lib2geom"):
//
//     ./offbench run --external lib2geom=build/lib2geom_worker --methods lib2geom,tiller
//
// lib2geom 1.2 (Debian's lib2geom-dev) has no offset or stroke function of
// its own: Inkscape's stroker (half_outline, geom-pathstroke.cpp) lives in
// Inkscape, not in the library.  What the library offers is its s-power
// basis calculus, and the offset built from it is the one its own toys and
// its users write:
//
//     O = B + d * rot90(unitVector(derivative(B)))
//
// B the piece as a D2<SBasis> (exact: a polynomial Bezier is a polynomial
// in the s-power basis), unitVector lib2geom's piecewise s-power
// approximation of the unit tangent (cut until its own error estimate is
// below its tol), rot90 the left normal (lib2geom's rot90 is (-y, x), the
// normal offbench's d > 0 takes).  The result is a Piecewise<D2<SBasis>>,
// which graphics code turns into cubic Beziers with path_from_piecewise:
// an s-power piece whose tail past its first three terms is below tol
// (tail_error(s, 3)) becomes one cubic (sbasis_to_cubic_bezier: the
// piece's end points and end tangent directions, the tangents' lengths
// fitted), otherwise it is halved and each half tried again.
// This worker runs that same rule itself (cubics_of) rather than calling
// path_from_piecewise, because a Path does not say at which base parameter
// each cubic starts, and the driver needs that parameter (the answer's
// "t"); the cubics are path_from_piecewise's, control point for control
// point (--check-path compares them on a request read from stdin).
//
// Tolerance: half of the job's tol goes to the normal (unitVector's tol is
// tol / (2|d|), its error times |d|) and half to the cubic conversion.
// Both are lib2geom's own estimates, not a distance guarantee: offbench
// measures every row's max_err itself.
//
// Rational pieces are refused (status skip): the s-power basis holds
// polynomials only, and the hello does not claim rational_in, so the
// driver does not send them.
//
// Options: --order N (unitVector's order, default 3, lib2geom's default).
// Build: make lib2geom-worker.
#include "../workers/protocol.hpp"

#include <2geom/bezier-to-sbasis.h>
#include <2geom/d2.h>
#include <2geom/exception.h>
#include <2geom/pathvector.h>
#include <2geom/piecewise.h>
#include <2geom/sbasis-geometric.h>
#include <2geom/sbasis-to-bezier.h>

#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

using namespace ob_worker;

namespace {

struct Opts {
    unsigned order = 3;
};

// A number as offbench writes it: the shortest %g that reads back as the
// same double, so that the answer's points are exactly lib2geom's.
std::string num(double x)
{
    char buf[64];
    for (int p = 1; p <= 17; p++) {
        std::snprintf(buf, sizeof buf, "%.*g", p, x);
        if (std::strtod(buf, nullptr) == x)
            return buf;
    }
    return buf;
}

// The cubics of one s-power piece s over base parameters [lo, hi], by
// path_from_piecewise's rule in lib2geom 1.2 (build_from_sbasis): a piece
// whose tail past three terms is below ctol (or that is a cubic) becomes
// one cubic by sbasis_to_cubic_bezier; otherwise each half is tried.
// --check-path confirms the rule: the same cubics, point for point.
// Appends the cubics' control points (4 each) to pts and their start
// parameters to ts.
// depth bounds the halving (a piece that needs 2^24 cubics is no answer).
void cubics_of(const Geom::D2<Geom::SBasis> &s, double lo, double hi, double ctol, int depth,
               std::vector<Geom::Point> &pts, std::vector<double> &ts)
{
    if (!s.isFinite())
        throw std::runtime_error("lib2geom's offset is not finite on [" + num(lo) + ", " + num(hi) + "]");
    if (Geom::tail_error(s, 3) < ctol || Geom::sbasis_size(s) == 2) {
        std::vector<Geom::Point> bez;
        Geom::sbasis_to_cubic_bezier(bez, s);
        pts.insert(pts.end(), bez.begin(), bez.end());
        ts.push_back(lo);
        return;
    }
    if (depth >= 24)
        throw std::runtime_error("the cubic conversion halved 24 times without reaching the tolerance");
    const double mid = lo + 0.5 * (hi - lo);
    cubics_of(Geom::compose(s, Geom::Linear(0, 0.5)), lo, mid, ctol, depth + 1, pts, ts);
    cubics_of(Geom::compose(s, Geom::Linear(0.5, 1)), mid, hi, ctol, depth + 1, pts, ts);
}

// The request's piece as lib2geom's s-power basis, exactly.
Geom::D2<Geom::SBasis> base_of(const Request &r)
{
    std::vector<Geom::Point> p;
    for (size_t i = 0; i < r.x.size(); i++)
        p.emplace_back(r.x[i], r.y[i]);
    Geom::D2<Geom::SBasis> b;
    Geom::bezier_to_sbasis(b, p);
    return b;
}

// lib2geom's offset of the piece, as a Piecewise of s-power pieces.
Geom::Piecewise<Geom::D2<Geom::SBasis>> offset_of(const Opts &o, const Request &r)
{
    const Geom::D2<Geom::SBasis> b = base_of(r);
    const double uvtol = r.tol / (2 * std::fabs(r.d));
    Geom::Piecewise<Geom::D2<Geom::SBasis>> n = Geom::rot90(Geom::unitVector(Geom::derivative(b), uvtol, o.order));
    return Geom::Piecewise<Geom::D2<Geom::SBasis>>(b) + n * r.d;
}

std::string point_json(const Geom::Point &p)
{
    return "[" + num(p[Geom::X]) + "," + num(p[Geom::Y]) + "]";
}

// The answer to one request: the cubics and where they start on the base.
std::string fit(const Opts &o, const Request &r)
{
    for (double w : r.w)
        if (w != 1.0)
            return error_json(r.id, "lib2geom's s-power basis holds polynomials only: a rational piece", "skip");
    const Geom::Piecewise<Geom::D2<Geom::SBasis>> off = offset_of(o, r);
    std::vector<Geom::Point> pts;
    std::vector<double> ts;
    for (unsigned i = 0; i < off.size(); i++)
        cubics_of(off.segs[i], off.cuts[i], off.cuts[i + 1], 0.5 * r.tol, 0, pts, ts);
    const size_t n = ts.size();
    if (n > 64)   // the protocol's most pieces an answer
        return error_json(r.id, std::to_string(n) + " cubics, more than an answer holds", "retry_smaller");
    std::string ps, tt = "0";
    for (size_t i = 0; i < n; i++) {
        ps += std::string(i ? "," : "") + "{\"degree\":3,\"points\":[" + point_json(pts[4 * i]) + "," +
              point_json(pts[4 * i + 1]) + "," + point_json(pts[4 * i + 2]) + "," + point_json(pts[4 * i + 3]) + "]}";
        if (i > 0)
            tt += "," + num(ts[i]);
    }
    return "{\"id\":" + std::to_string(r.id) + ",\"pieces\":[" + ps + "],\"t\":[" + tt + ",1]}";
}

// One line in, one line out: every failure an error answer.
std::string answer(const Opts &o, const std::string &line)
{
    Request r;
    try {
        request_of(Reader(line).whole(), r, 64);
        if (!r.params.obj.empty())   // the hello declares no parameters
            throw BadRequest{"\"params\" is not {} (this method has no parameters)"};
        if (!(r.d != 0))
            throw BadRequest{"\"d\" is 0"};
        return fit(o, r);
    } catch (const BadRequest &e) {
        return error_json(r.id, "bad request: " + e.why);
    } catch (const Geom::Exception &e) {
        return error_json(r.id, std::string("lib2geom: ") + e.what());
    } catch (const std::exception &e) {
        return error_json(r.id, e.what());
    }
}

// G0: the cubics of one s-power piece meet with one tangent direction
// (sbasis_to_cubic_bezier keeps the end tangents' directions), but where
// unitVector cut the normal the offset's pieces meet in position only, so
// G0 is what every joint has.
std::string hello(const Opts &o)
{
    return "{\"protocol\":1,\"citation\":\"lib2geom " + std::string(LIB2GEOM_VERSION) +
           ": B + d rot90(unitVector(B')) in the s-power basis (order " + std::to_string(o.order) +
           "), cubics by path_from_piecewise's rule\",\"degree\":3,\"continuity\":\"G0\","
           "\"caps\":[\"poly_out\",\"tol_driven\"],\"uses_tol\":true,\"version\":1,\"params\":[]}";
}

// --check-path: for the request on stdin, whether cubics_of gives
// path_from_piecewise's cubics, point for point (exit 0) or not (exit 1).
int check_path(const Opts &o)
{
    std::string line;
    std::getline(std::cin, line);
    Request r;
    request_of(Reader(line).whole(), r, 64);
    const Geom::Piecewise<Geom::D2<Geom::SBasis>> off = offset_of(o, r);
    std::vector<Geom::Point> pts;
    std::vector<double> ts;
    for (unsigned i = 0; i < off.size(); i++)
        cubics_of(off.segs[i], off.cuts[i], off.cuts[i + 1], 0.5 * r.tol, 0, pts, ts);
    const Geom::PathVector paths = Geom::path_from_piecewise(off, 0.5 * r.tol, true);
    std::vector<Geom::Point> lib;
    for (const Geom::Path &p : paths)
        for (const Geom::Curve &c : p) {
            const auto *cb = dynamic_cast<const Geom::CubicBezier *>(&c);
            if (!cb)
                return std::printf("path_from_piecewise gave a curve that is not a cubic\n"), 1;
            for (unsigned k = 0; k < 4; k++)
                lib.push_back((*cb)[k]);
        }
    const bool same = lib == pts;
    std::printf("%zu cubics here, %zu from path_from_piecewise: %s\n", pts.size() / 4, lib.size() / 4,
                same ? "the same points" : "different");
    return same ? 0 : 1;
}

[[noreturn]] void usage_error(const std::string &why)
{
    std::fprintf(stderr, "lib2geom_worker: %s\nusage: lib2geom_worker [--order N] [--check-path]\n", why.c_str());
    std::exit(2);
}

}  // namespace

int main(int argc, char **argv)
{
    Opts o;
    bool check = false;
    for (int i = 1; i < argc; i++) {
        const std::string a = argv[i];
        if (a == "--check-path")
            check = true;
        else if (a == "--order" && i + 1 < argc && std::atoi(argv[i + 1]) >= 1 && std::atoi(argv[i + 1]) <= 12)
            o.order = (unsigned)std::atoi(argv[++i]);
        else
            usage_error(a + ": unknown option or bad value");
    }
    if (check)
        return check_path(o);
    std::ios::sync_with_stdio(false);
    std::cout << hello(o) << '\n' << std::flush;
    for (std::string line; std::getline(std::cin, line);)
        std::cout << answer(o, line) << '\n' << std::flush;
    return 0;
}
