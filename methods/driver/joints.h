/*
 * joints.h - where consecutive pieces of an approximation meet.
 *
 * A joint is where one approximating piece ends and the next begins: between
 * the pieces of one fit (ob_fit has n pieces), and between consecutive
 * accepted fits of a job in curve order (segment, then parameter), also
 * across two base segments where the base curve itself is G1.  At a corner of
 * the base curve, or a gap between its segments, the exact offset is not
 * continuous, so that joint is not measured (it does not enter max_gap,
 * max_kink or the continuity); its two ends are still two points when they
 * are apart, and are counted so.
 *
 * At each joint, from the Bézier pieces themselves (their ends, t = 0 and 1):
 *   gap   the distance between the end point of the left piece and the start
 *         point of the right one;
 *   kink  the angle in [0, pi] between the left piece's end tangent and the
 *         right piece's start tangent, atan2(|cross|, dot) of the directions.
 * End points: the end control points (homogeneous, divided by the weight).
 * End tangents: the one-sided limit of the direction of C(t) - C(0) as t
 * falls to 0 (and of C(1) - C(t) at the end), in homogeneous form, so a
 * negative weight is handled and a collapsed end leg (P_1 = P_0) gives the
 * next control point's direction.
 *
 * Thresholds (the contract; README "Joints", meta.json "joints"):
 *   open  a joint whose gap exceeds OB_JOINT_GAP_REL (1e-12) times the size
 *         of the curve: the diagonal of the base curve's control-point
 *         bounding box grown by |d| on every side (a box that holds the exact
 *         offset).  Its two ends count as two control points.
 *   G1    a closed joint whose kink is at most OB_JOINT_KINK_RAD (1e-6 rad).
 * A job's measured continuity: "open" when any measured joint is open, else
 * "G0" when any kink exceeds the angle threshold (or a tangent is undefined),
 * else "G1"; none (empty) when the job has no measured joint or no
 * approximation.
 */
#ifndef OB_JOINTS_H
#define OB_JOINTS_H

#include "methods/core/curve.h"

#define OB_JOINT_GAP_REL 1e-12
#define OB_JOINT_KINK_RAD 1e-6

/* One end of a piece: its point and unit tangent direction ((0,0) when the
 * piece has none: a point-like piece). */
typedef struct {
    double p[2], t[2];
} ob_end;

/* Purpose: the end of b at t = 0 (at_end 0) or t = 1 (at_end 1). */
void ob_bez_end(const ob_bez *b, int at_end, ob_end *e);

/* Measured continuity of a job. */
typedef enum { OB_CONT_NONE = 0, OB_CONT_OPEN, OB_CONT_G0, OB_CONT_G1 } ob_cont;
/* "", "open", "G0", "G1" */
const char *ob_cont_name(ob_cont c);
/* The inverse of ob_cont_name; 0, or -1 for another text. */
int ob_cont_parse(const char *s, ob_cont *c);

/* The size of curve c with offset d (see the top) and the gap threshold,
 * OB_JOINT_GAP_REL times it. */
double ob_joint_size(const ob_curve *c, double d);
double ob_joint_gap_tol(const ob_curve *c, double d);

/* The joints seen so far. */
typedef struct {
    double max_gap, max_kink;   /* over the measured joints (0 before any) */
    int joints;                 /* measured joints */
    int open;                   /* of them open */
    int kinked;                 /* of them closed with a kink over the threshold or no tangent */
    int excluded;               /* joints not measured (base corners and gaps) */
    int excluded_open;          /* of them with their ends apart */
} ob_joint_stats;

/* Purpose: measure one joint: left's end against right's start.  Returns 1
 * when it is open. */
int ob_joint_measure(ob_joint_stats *s, const ob_end *left, const ob_end *right, double gap_tol);

/* Adds the counts and maxima of b to a. */
void ob_joint_merge(ob_joint_stats *a, const ob_joint_stats *b);

/* Purpose: 1 when the base curve is G1 where segment s ends and s + 1
 * begins (ends within gap_tol, tangents within OB_JOINT_KINK_RAD): the exact
 * offset is continuous there. */
int ob_base_joint_smooth(const ob_curve *c, int s, double gap_tol);

/* Purpose: the joint between two consecutive pieces of a job in curve order,
 * the left one in base segment sl, the right one in sr (>= sl): measured
 * when sl == sr or the base is G1 from sl to sr = sl + 1; otherwise only
 * counted as excluded.  Returns 1 when its ends are apart (open or not
 * measured): the joint counts as two control points. */
int ob_joint_between(ob_joint_stats *s, const ob_curve *c, double gap_tol, int sl, const ob_end *left, int sr,
                     const ob_end *right);

/* The continuity the measured joints reach (see the top). */
ob_cont ob_joint_continuity(const ob_joint_stats *s);

#endif
