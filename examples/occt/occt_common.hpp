// occt_common.hpp - what occt_offset.cpp (DXF files for `measure`) and
// occt_worker.cpp (an external method) share, so that both give OCCT the
// same offset: offbench's sign of d, and numbers written as offbench does.
#ifndef OCCT_COMMON_HPP
#define OCCT_COMMON_HPP

#include <Geom2d_Curve.hxx>
#include <Geom2d_OffsetCurve.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace occt_common {

// A number as offbench writes it (host/io/numfmt.c): the shortest %g text
// that reads back as the same double, without an exponent from 1e-4 to
// 1e16 ("0.0001", "1e-05"), so that the stems, d and tol are results.csv's
// and a worker's answer reads back to the same doubles.
inline std::string num(double x)
{
    char buf[64];
    const bool plain = std::fabs(x) >= 1e-4 && std::fabs(x) < 1e16;
    for (int p = 1; p <= 17; p++) {
        std::snprintf(buf, sizeof buf, "%.*g", p, x);
        if (std::strtod(buf, nullptr) == x && !(plain && std::strchr(buf, 'e')))
            return buf;
    }
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

// The offset of basis at offbench's d.  Sign: offbench's normal is the left
// one, N = (-y', x') / |C'|, d > 0 on the left of the direction of travel;
// OCCT's offset direction is T ^ Z = (y', -x'), the right one
// (Geom2d_OffsetCurve.hxx: the tangent rotated "in the anti-trigonometric
// sense").  So OCCT is given -d.  tests/e2e/e2e_occt.sh checks it on a
// straight line, whose offset OCCT reproduces to rounding.
inline Handle(Geom2d_OffsetCurve) offset_of(const Handle(Geom2d_Curve) &basis, double d)
{
    return new Geom2d_OffsetCurve(basis, -d);
}

// Control points (Euclidean) and weights as OCCT's 1-based arrays, for a
// Geom2d_BezierCurve or Geom2d_BSplineCurve of the same curve, parameter
// for parameter; rational when a weight is not 1 (OCCT's polynomial
// constructors then, so a polynomial curve stays one).
struct Poles {
    TColgp_Array1OfPnt2d points;
    TColStd_Array1OfReal weights;
    bool rational = false;
    Poles(const std::vector<double> &x, const std::vector<double> &y, const std::vector<double> &w)
        : points(1, (int)x.size()), weights(1, (int)x.size())
    {
        for (size_t i = 0; i < x.size(); i++) {
            points((int)i + 1) = gp_Pnt2d(x[i], y[i]);
            weights((int)i + 1) = w[i];
            rational |= w[i] != 1.0;
        }
    }
};

}  // namespace occt_common

#endif
