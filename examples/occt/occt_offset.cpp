// occt_offset.cpp - OpenCASCADE's offsets of offbench's base curves, as DXF
// files that `offbench measure` reads (docs/cad-example.md).
//
// For each curve of a .curves file (docs/curves.md), each offset d and each
// tolerance: the base curve as a Geom2d_BSplineCurve (the file's own
// control points, weights and knots: the exact curve offbench measures
// against), its offset as a Geom2d_OffsetCurve, and that approximated by
// Geom2dConvert_ApproxCurve (tolerance, continuity, most segments, highest
// degree).  The approximation is written as DXF SPLINE entities; what OCCT
// says of it (IsDone, HasResult, MaxError) goes to a CSV, one row per job,
// a failure as a row with its message, never a crash.
//
// Sign: OCCT is given -d (occt_common.hpp: its normal is the right one,
// offbench's the left).  The same construction, one Bezier piece at a time,
// is an external method: occt_worker.cpp.
//
// Build: make occt-example (Debian: libocct-foundation-dev,
// libocct-modeling-data-dev, g++).  Usage: occt_offset --help.
#include "occt_common.hpp"

#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_OffsetCurve.hxx>
#include <Geom2dConvert_ApproxCurve.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <exception>
#include <string>
#include <vector>

namespace {

using occt_common::num;

// ------------------------------------------------------------ .curves input

struct Curve {
    std::string id, where;                  // where: FILE:LINE of its `curve` line
    int deg = 0;
    bool bspline = false;
    std::vector<double> knots;              // bspline: the file's knot vector
    std::vector<double> x, y, w;            // control points, Euclidean, weights
    std::vector<double> offsets;
};

[[noreturn]] void die(const std::string &msg)
{
    std::fprintf(stderr, "occt_offset: %s\n", msg.c_str());
    std::exit(2);
}

// The curve blocks of a .curves file.  The format's own reader
// (host/io/curvefile.c) checks far more; this one trusts files offbench
// reads and only refuses what it cannot use, naming FILE:LINE.
std::vector<Curve> read_curves(const std::string &path)
{
    std::ifstream in(path);
    if (!in)
        die(path + ": cannot open");
    std::vector<Curve> out;
    Curve *c = nullptr;
    std::string line;
    for (int n = 1; std::getline(in, line); n++) {
        line = line.substr(0, line.find('#'));
        std::istringstream s(line);
        std::string kw;
        if (!(s >> kw))
            continue;
        const std::string at = path + ":" + std::to_string(n);
        auto nums = [&] {
            std::vector<double> v;
            std::string tok;
            while (s >> tok) {
                char *e;
                v.push_back(std::strtod(tok.c_str(), &e));
                if (*e)
                    die(at + ": '" + tok + "' is not a number");
            }
            return v;
        };
        if (kw == "curve") {
            out.emplace_back();
            c = &out.back();
            s >> c->id;
            c->where = at;
        } else if (!c) {
            die(at + ": '" + kw + "' outside a curve block");
        } else if (kw == "bezier" || kw == "bspline") {
            c->bspline = kw == "bspline";
            s >> c->deg;
        } else if (kw == "knots") {
            for (double k : nums())
                c->knots.push_back(k);
        } else if (kw == "point" || kw == "hpoint") {
            std::vector<double> v = nums();
            if (v.size() < 2 || v.size() > 3 || (kw == "hpoint" && v.size() != 3))
                die(at + ": " + kw + " takes X Y [W] (hpoint: WX WY W)");
            const double w = v.size() == 3 ? v[2] : 1.0;
            const double h = kw == "hpoint" ? w : 1.0;   // hpoint: homogeneous
            c->x.push_back(v[0] / h);
            c->y.push_back(v[1] / h);
            c->w.push_back(w);
        } else if (kw == "offset") {
            for (double d : nums())
                c->offsets.push_back(d);
        } else if (kw == "end") {
            c = nullptr;
        } else if (kw != "source" && kw != "family") {
            die(at + ": unknown keyword '" + kw + "'");
        }
    }
    for (const Curve &k : out) {
        const size_t np = k.x.size();
        if (k.deg < 1 || np < (size_t)k.deg + 1 || (!k.bspline && np != (size_t)k.deg + 1) ||
            (k.bspline && k.knots.size() != np + k.deg + 1))
            die(k.where + ": curve " + k.id + ": degree, control points and knots do not fit");
    }
    return out;
}

// ------------------------------------------------------------ the base curve

// The distinct knots of the curve's domain [K_deg, K_points] (where
// offbench cuts it into Bézier segments, docs/curves.md).  A Bézier curve
// is one segment over [0, 1].
std::vector<double> domain_knots(const Curve &c)
{
    if (!c.bspline)
        return {0.0, 1.0};
    std::vector<double> u;
    for (size_t i = c.deg; i <= c.x.size(); i++)
        if (u.empty() || c.knots[i] > u.back())
            u.push_back(c.knots[i]);
    return u;
}

// The base curve as OCCT holds it: the same control points, weights and
// knots, so the same curve, parameter for parameter.
Handle(Geom2d_BSplineCurve) base_curve(const Curve &c)
{
    const occt_common::Poles p(c.x, c.y, c.w);
    std::vector<double> k;
    std::vector<int> m;
    if (!c.bspline) {
        k = {0.0, 1.0};
        m = {c.deg + 1, c.deg + 1};
    } else {
        for (double v : c.knots) {
            if (!k.empty() && v == k.back())
                m.back()++;
            else
                k.push_back(v), m.push_back(1);
        }
    }
    TColStd_Array1OfReal K(1, (int)k.size());
    TColStd_Array1OfInteger M(1, (int)k.size());
    for (size_t i = 0; i < k.size(); i++)
        K((int)i + 1) = k[i], M((int)i + 1) = m[i];
    if (p.rational)
        return new Geom2d_BSplineCurve(p.points, p.weights, K, M, c.deg);
    return new Geom2d_BSplineCurve(p.points, K, M, c.deg);
}

// Where the base is only C0 (an interior knot of multiplicity >= degree:
// the corners of an SVG path, svg2curves.py writes them so), split it:
// Geom2d_OffsetCurve refuses a C0 basis, and the offset of a corner is no
// curve anyway (offbench does not measure across it either).  The runs
// between such knots are offset and approximated one by one.
std::vector<double> c1_breaks(const Curve &c, const std::vector<double> &u)
{
    std::vector<double> b = {u.front()};
    for (size_t i = 1; i + 1 < u.size(); i++)
        if (std::count(c.knots.begin(), c.knots.end(), u[i]) >= c.deg)
            b.push_back(u[i]);
    b.push_back(u.back());
    return b;
}

// ------------------------------------------------------------ DXF output

// The smallest AC1015 (R2000: R12 has no SPLINE) file CAD readers take, as
// offbench's own export writes it (host/io/export_dxf.c): a HEADER with the
// version and an ENTITIES section.
struct Dxf {
    std::string text;
    unsigned handle = 0x100;
    void pair(int code, const std::string &v) { text += std::to_string(code) + "\n" + v + "\n"; }
    // One SPLINE entity: flat knots, poles, weights (empty: polynomial).
    void spline(int deg, const std::vector<double> &knots, const TColgp_Array1OfPnt2d &p,
                const std::vector<double> &w)
    {
        char h[16];
        std::snprintf(h, sizeof h, "%X", handle++);
        pair(0, "SPLINE");
        pair(5, h);
        pair(100, "AcDbEntity");
        pair(8, "OCCT");
        pair(100, "AcDbSpline");
        pair(210, "0"), pair(220, "0"), pair(230, "1");
        pair(70, std::to_string(8 | (w.empty() ? 0 : 4)));     // planar, rational
        pair(71, std::to_string(deg));
        pair(72, std::to_string(knots.size()));
        pair(73, std::to_string(p.Length()));
        pair(74, "0");
        for (double k : knots)
            pair(40, num(k));
        for (double x : w)
            pair(41, num(x));
        for (int i = p.Lower(); i <= p.Upper(); i++) {
            pair(10, num(p(i).X()));
            pair(20, num(p(i).Y()));
            pair(30, "0");
        }
    }
};

// OCCT's B-spline of one run as it is: one SPLINE, its knots and poles,
// what a CAD system would exchange.  No link to the base (measure matches
// each Bézier piece to the base by projecting its ends, and cuts a piece
// that runs over a joint of the base where it crosses the joint's normal).
void write_bspline(Dxf &f, const Handle(Geom2d_BSplineCurve) &c)
{
    TColStd_Array1OfReal flat(1, c->NbPoles() + c->Degree() + 1);
    c->KnotSequence(flat);
    TColgp_Array1OfPnt2d poles(1, c->NbPoles());
    c->Poles(poles);
    std::vector<double> w;
    if (c->IsRational())
        for (int i = 1; i <= c->NbPoles(); i++)
            w.push_back(c->Weight(i));
    f.spline(c->Degree(), std::vector<double>(flat.begin(), flat.end()), poles, w);
}

// ------------------------------------------------------------ one job

struct Opts {
    std::string curves, out, csv;
    std::vector<std::string> ids;
    std::vector<double> ds, tols;
    GeomAbs_Shape order = GeomAbs_C2;
    int max_degree = 8, max_segments = 1000;
    std::string method = "occt";
};

struct Row {
    std::string status = "ok", message, file;
    bool done = true, has_result = true;
    double max_error = 0.0;
    int runs = 0, degree = 0, poles = 0, spans = 0;
};

std::string stem_of(const Opts &o, const Curve &c, double d, double tol)
{
    std::string id = c.id;
    std::replace(id.begin(), id.end(), '/', '~');   // as offbench's export stems
    return id + "__d" + num(d) + "__" + o.method + "__tol" + num(tol);
}

Row job(const Opts &o, const Curve &c, double d, double tol)
{
    Row r;
    const std::string stem = stem_of(o, c, d, tol);
    Dxf f;
    f.pair(999, "occt_offset: the approximation of job " + stem);  // measure warns on another --curve/--d
    f.pair(0, "SECTION"), f.pair(2, "HEADER"), f.pair(9, "$ACADVER"), f.pair(1, "AC1015");
    f.pair(0, "ENDSEC"), f.pair(0, "SECTION"), f.pair(2, "ENTITIES");
    try {
        const Handle(Geom2d_BSplineCurve) base = base_curve(c);
        const std::vector<double> brk = c1_breaks(c, domain_knots(c));
        for (size_t i = 0; i + 1 < brk.size(); i++) {
            Handle(Geom2d_BSplineCurve) run = Handle(Geom2d_BSplineCurve)::DownCast(base->Copy());
            run->Segment(brk[i], brk[i + 1]);
            Handle(Geom2d_OffsetCurve) off = occt_common::offset_of(run, d);
            Geom2dConvert_ApproxCurve ap(off, tol, o.order, o.max_segments, o.max_degree);
            r.runs++;
            r.done &= ap.IsDone() != 0;
            r.has_result &= ap.HasResult() != 0;
            if (!ap.HasResult()) {
                r.status = "fail";
                r.message = "Geom2dConvert_ApproxCurve: no result";
                break;
            }
            const Handle(Geom2d_BSplineCurve) a = ap.Curve();
            r.max_error = std::max(r.max_error, ap.MaxError());
            r.degree = std::max(r.degree, a->Degree());
            r.poles += a->NbPoles();
            r.spans += a->NbKnots() - 1;
            write_bspline(f, a);
        }
    } catch (const Standard_Failure &e) {
        r.status = "fail";
        r.message = std::string(e.DynamicType()->Name()) + ": " + (e.GetMessageString() ? e.GetMessageString() : "");
    } catch (const std::exception &e) {
        r.status = "fail";
        r.message = e.what();
    }
    // IsDone() is no promise of the tolerance: when MaxSegments stops the
    // cutting, AdvApprox_ApproxAFunction keeps its error code 0 (the line
    // that would set -1 is commented out; 7.6 does so) and reports done with
    // a MaxError above it.  So the status reads OCCT's own MaxError too.
    if (r.status == "ok" && (!r.done || r.max_error > tol)) {
        r.status = "limit";
        r.message = "OCCT's MaxError " + num(r.max_error) + " is above the tolerance (IsDone " +
                    std::to_string(r.done) + ")";
    }
    if (r.status == "fail") {
        r.done = r.has_result = false;   // the job has no approximation, whatever a run had
        return r;
    }
    f.pair(0, "ENDSEC"), f.pair(0, "EOF");
    r.file = stem + ".dxf";   // beside the CSV: the directory moves as a whole
    const std::string path = o.out + "/" + r.file;
    std::ofstream out(path);
    if (!(out << f.text) || !(out.close(), out))
        die(path + ": cannot write");
    return r;
}

// ------------------------------------------------------------ command line

const char *usage =
    "usage: occt_offset --curves FILE --tols T,... --out DIR [--curve ID,...] [--d D,...]\n"
    "                   [--continuity C0|C1|C2] [--max-degree N] [--max-segments N]\n"
    "                   [--method NAME] [--csv FILE]\n"
    "\n"
    "OpenCASCADE's approximation (Geom2dConvert_ApproxCurve of a Geom2d_OffsetCurve) of\n"
    "each offset of each curve of FILE (offbench's .curves format), at each tolerance:\n"
    "DIR/CURVE__dD__NAME__tolT.dxf (NAME: --method, default occt) for\n"
    "`offbench measure --curve CURVE --d D --approx FILE`, and a CSV of what OCCT says\n"
    "(default DIR/NAME.csv: curve,d,tol,method,continuity,max_degree,max_segments,\n"
    "status,is_done,has_result,max_error,runs,degree,poles,spans,file,message).\n"
    "  --curve ID,...      only these curves (default: every curve of FILE)\n"
    "  --d D,...           these offsets (default: each curve's own offset lines)\n"
    "  --continuity        GeomAbs_C0, C1 or C2 of the approximation (default C2)\n"
    "  --max-degree N      its highest degree (default 8)\n"
    "  --max-segments N    its most spans (default 1000)\n"
    "The DXF file: one SPLINE per C1 run of the base (OCCT's B-spline as it is; a base\n"
    "that is only C0 at a knot, a corner, is offset run by run: OCCT refuses it whole).\n"
    "status: ok; limit (a result whose MaxError OCCT gives is above the tolerance, or\n"
    "IsDone false); fail (no result, or an OCCT exception: message).  file: the DXF's\n"
    "name in DIR.  Exit 0, 2 on bad input.\n";

std::vector<std::string> split(const std::string &s)
{
    std::vector<std::string> v;
    std::stringstream in(s);
    for (std::string t; std::getline(in, t, ',');)
        if (!t.empty())
            v.push_back(t);
    return v;
}

double number(const std::string &opt, const std::string &s)
{
    char *e;
    const double x = std::strtod(s.c_str(), &e);
    if (s.empty() || *e || !std::isfinite(x))
        die(opt + ": '" + s + "' is not a number");
    return x;
}

Opts parse(int argc, char **argv)
{
    Opts o;
    for (int i = 1; i < argc; i++) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            std::fputs(usage, stdout);
            std::exit(0);
        }
        if (i + 1 >= argc)
            die(a + ": unknown option or missing value (see --help)");
        const std::string v = argv[++i];
        if (a == "--curves")
            o.curves = v;
        else if (a == "--out")
            o.out = v;
        else if (a == "--csv")
            o.csv = v;
        else if (a == "--method")
            o.method = v;
        else if (a == "--curve")
            o.ids = split(v);
        else if (a == "--d")
            for (const std::string &t : split(v))
                o.ds.push_back(number(a, t));
        else if (a == "--tols")
            for (const std::string &t : split(v))
                o.tols.push_back(number(a, t));
        else if (a == "--continuity" && (v == "C0" || v == "C1" || v == "C2"))
            o.order = v == "C0" ? GeomAbs_C0 : v == "C1" ? GeomAbs_C1 : GeomAbs_C2;
        else if (a == "--max-degree")
            o.max_degree = (int)number(a, v);
        else if (a == "--max-segments")
            o.max_segments = (int)number(a, v);
        else
            die(a + " " + v + ": unknown option or bad value (see --help)");
    }
    if (o.curves.empty() || o.out.empty() || o.tols.empty())
        die("--curves, --tols and --out are required (see --help)");
    if (o.method.empty() || o.method.find("__") != std::string::npos ||
        o.method.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-") != std::string::npos)
        die("--method: lower-case letters, digits and '-' (it is part of the file names)");
    for (double t : o.tols)
        if (!(t > 0))
            die("--tols: a tolerance must be > 0");
    if (o.csv.empty())
        o.csv = o.out + "/" + o.method + ".csv";
    return o;
}

}  // namespace

int main(int argc, char **argv)
{
    const Opts o = parse(argc, argv);
    std::vector<Curve> all = read_curves(o.curves);
    for (const std::string &id : o.ids)
        if (std::none_of(all.begin(), all.end(), [&](const Curve &c) { return c.id == id; }))
            die("--curve: no curve '" + id + "' in " + o.curves);
    std::ofstream csv(o.csv);
    if (!csv)
        die(o.csv + ": cannot write (does " + o.out + " exist?)");
    csv << "curve,d,tol,method,continuity,max_degree,max_segments,status,is_done,has_result,max_error,"
           "runs,degree,poles,spans,file,message\n";
    const char *cont = o.order == GeomAbs_C0 ? "C0" : o.order == GeomAbs_C1 ? "C1" : "C2";
    for (const Curve &c : all) {
        if (!o.ids.empty() && std::find(o.ids.begin(), o.ids.end(), c.id) == o.ids.end())
            continue;
        for (double d : o.ds.empty() ? c.offsets : o.ds)
            for (double tol : o.tols) {
                const Row r = job(o, c, d, tol);
                std::string msg = r.message;
                std::replace(msg.begin(), msg.end(), '"', '\'');
                std::replace(msg.begin(), msg.end(), '\n', ' ');
                csv << c.id << ',' << num(d) << ',' << num(tol) << ',' << o.method << ',' << cont << ','
                    << o.max_degree << ',' << o.max_segments << ',' << r.status << ',' << r.done << ','
                    << r.has_result << ',' << (r.has_result ? num(r.max_error) : "") << ',' << r.runs << ','
                    << r.degree << ',' << r.poles << ',' << r.spans << ',' << r.file
                    << ",\"" << msg << "\"\n";
                std::fprintf(stderr, "occt_offset: %s d = %s tol = %s: %s, MaxError %s, %d poles\n",
                             c.id.c_str(), num(d).c_str(), num(tol).c_str(), r.status.c_str(),
                             num(r.max_error).c_str(), r.poles);
            }
    }
    if (!(csv.close(), csv))
        die(o.csv + ": cannot write");
    return 0;
}
