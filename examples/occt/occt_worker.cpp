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

namespace {

// ------------------------------------------------------------ the request

// A JSON value of the kinds a request holds: number, array, object.
// Strings, true, false and null never occur in a request, so they are
// refused as errors rather than parsed.
struct Value {
    enum Kind { NUM, ARR, OBJ } kind = NUM;
    double num = 0;
    std::vector<Value> arr;
    std::map<std::string, Value> obj;
};

struct BadRequest {
    std::string why;
};

// A strict recursive-descent reader of one line (RFC 8259 numbers, keys
// without escapes: a request's keys are plain names).
class Reader {
  public:
    explicit Reader(const std::string &s) : s_(s) {}
    Value whole()
    {
        Value v = value(0);
        space();
        if (i_ != s_.size())
            fail("text after the value");
        return v;
    }

  private:
    const std::string &s_;
    size_t i_ = 0;

    [[noreturn]] void fail(const std::string &why) const
    {
        throw BadRequest{why + " at byte " + std::to_string(i_)};
    }
    void space()
    {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\r' || s_[i_] == '\n'))
            i_++;
    }
    bool eat(char c)
    {
        space();
        if (i_ < s_.size() && s_[i_] == c)
            return ++i_, true;
        return false;
    }
    Value value(int depth)
    {
        if (depth > 4)   // a request nests 3 deep: points -> point -> number
            fail("nested too deep");
        space();
        if (eat('['))
            return array(depth);
        if (eat('{'))
            return object(depth);
        return number();
    }
    Value array(int depth)
    {
        Value v;
        v.kind = Value::ARR;
        if (eat(']'))
            return v;
        do
            v.arr.push_back(value(depth + 1));
        while (eat(','));
        if (!eat(']'))
            fail("expected ',' or ']'");
        return v;
    }
    std::string key()
    {
        if (!eat('"'))
            fail("expected a key");
        const size_t at = i_;
        while (i_ < s_.size() && (std::isalnum((unsigned char)s_[i_]) || s_[i_] == '_'))
            i_++;
        if (i_ >= s_.size() || s_[i_] != '"')
            fail("a key holds letters, digits and '_' only");
        return s_.substr(at, i_++ - at);
    }
    Value object(int depth)
    {
        Value v;
        v.kind = Value::OBJ;
        if (eat('}'))
            return v;
        do {
            const std::string k = key();
            if (!eat(':'))
                fail("expected ':'");
            if (!v.obj.emplace(k, value(depth + 1)).second)
                fail("key \"" + k + "\" twice");
        } while (eat(','));
        if (!eat('}'))
            fail("expected ',' or '}'");
        return v;
    }
    // JSON's number grammar exactly (no NaN, no hex, no leading '+'), read by strtod.
    Value number()
    {
        const size_t at = i_;
        auto digits = [&] {
            const size_t d = i_;
            while (i_ < s_.size() && std::isdigit((unsigned char)s_[i_]))
                i_++;
            return i_ > d;
        };
        if (i_ < s_.size() && s_[i_] == '-')
            i_++;
        if (i_ < s_.size() && s_[i_] == '0')
            i_++;
        else if (!digits())
            fail("not a number");
        if (i_ < s_.size() && s_[i_] == '.' && (++i_, !digits()))
            fail("no digits after '.'");
        if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
            i_++;
            if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-'))
                i_++;
            if (!digits())
                fail("no digits in the exponent");
        }
        Value v;
        v.num = std::strtod(s_.substr(at, i_ - at).c_str(), nullptr);
        if (!std::isfinite(v.num))
            fail("a number out of range");
        return v;
    }
};

struct Request {
    long id = -1;          // -1 until read: an error answer then says "id": null
    int degree = 0;
    std::vector<double> x, y, w;
    double d = 0, tol = 0;
};

const Value &field(const Value &o, const char *k)
{
    auto it = o.obj.find(k);
    if (it == o.obj.end())
        throw BadRequest{std::string("no \"") + k + "\""};
    return it->second;
}

double number_of(const Value &v, const char *what)
{
    if (v.kind != Value::NUM)
        throw BadRequest{std::string("\"") + what + "\" is not a number"};
    return v.num;
}

// The request's shape, exactly (docs/external-methods.md "Request"), into
// r: its id first, so that an error about the rest can name it.
void request_of(const Value &v, Request &r)
{
    if (v.kind != Value::OBJ)
        throw BadRequest{"not a JSON object"};
    const double id = number_of(field(v, "id"), "id");
    if (id != std::floor(id) || id < 0 || id > 1e15)
        throw BadRequest{"\"id\" is not a whole number >= 0"};
    r.id = (long)id;
    for (const auto &kv : v.obj)
        if (kv.first != "id" && kv.first != "degree" && kv.first != "points" && kv.first != "weights" &&
            kv.first != "d" && kv.first != "tol" && kv.first != "params")
            throw BadRequest{"unknown key \"" + kv.first + "\""};
    const double deg = number_of(field(v, "degree"), "degree");
    if (deg != std::floor(deg) || deg < 1 || deg > 25)   // Geom2d_BezierCurve's MaxDegree
        throw BadRequest{"\"degree\" is not a whole number from 1 to 25"};
    r.degree = (int)deg;
    const Value &p = field(v, "points"), &w = field(v, "weights");
    if (p.kind != Value::ARR || (int)p.arr.size() != r.degree + 1)
        throw BadRequest{"\"points\" is not degree + 1 points"};
    if (w.kind != Value::ARR || w.arr.size() != p.arr.size())
        throw BadRequest{"\"weights\" is not degree + 1 numbers"};
    for (size_t i = 0; i < p.arr.size(); i++) {
        if (p.arr[i].kind != Value::ARR || p.arr[i].arr.size() != 2)
            throw BadRequest{"\"points\"[" + std::to_string(i) + "] is not [x, y]"};
        r.x.push_back(number_of(p.arr[i].arr[0], "points"));
        r.y.push_back(number_of(p.arr[i].arr[1], "points"));
        r.w.push_back(number_of(w.arr[i], "weights"));
        if (!(r.w.back() > 0))
            throw BadRequest{"a weight is not > 0"};
    }
    r.d = number_of(field(v, "d"), "d");
    r.tol = number_of(field(v, "tol"), "tol");
    if (!(r.tol > 0))
        throw BadRequest{"\"tol\" is not > 0"};
    const Value &pa = field(v, "params");
    if (pa.kind != Value::OBJ || !pa.obj.empty())   // the hello declares no parameters
        throw BadRequest{"\"params\" is not {} (this method has no parameters)"};
}

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

// Quotes an error message as a JSON string (OCCT's messages are ASCII;
// anything else becomes '?').
std::string quoted(const std::string &m)
{
    std::string s = "\"";
    for (unsigned char c : m)
        s += c == '"' || c == '\\' ? std::string("\\") + (char)c : c < 0x20 || c >= 0x7f ? "?" : std::string(1, (char)c);
    return s + "\"";
}

std::string error_json(long id, const std::string &why, const char *status = "fail")
{
    return std::string("{\"id\":") + (id < 0 ? "null" : std::to_string(id)) + ",\"error\":" + quoted(why) +
           ",\"status\":\"" + status + "\"}";
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
        request_of(Reader(line).whole(), r);
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
