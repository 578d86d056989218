/*
 * columns.c - the results.csv column table.  See columns.h.
 */
#include "host/io/columns.h"

#include <pthread.h>
#include <string.h>

const ob_column ob_columns[OB_NCOLS] = {
    [OB_COL_CURVE] = {"curve", "curve id (job key)"},
    [OB_COL_D] = {"d", "signed offset distance, d > 0 left of travel (job key)"},
    [OB_COL_METHOD] = {"method", "method name (job key)"},
    [OB_COL_METRIC] = {"metric", "error metric: bound, radial, normal, hausdorff, param or certified (job key)"},
    [OB_COL_SPLIT] = {"split", "split rule: mid, maxerr, greedy or optimal (job key)"},
    [OB_COL_TOL] = {"tol", "tolerance (job key)"},
    [OB_COL_CTRL_POINTS] = {"ctrl_points", "control points of the approximation (open joints count both ends)"},
    [OB_COL_SEGMENTS] = {"segments", "Bezier pieces of the approximation"},
    [OB_COL_OUT_DEGREE] = {"out_degree", "largest degree of the pieces"},
    [OB_COL_MAX_ERR] = {"max_err", "largest error of the accepted pieces under the metric (empty: none)"},
    [OB_COL_STATUS] = {"status", "ok, limit, fail, skip or timeout"},
    [OB_COL_FIT_NS] = {"fit_ns", "thread CPU time of the job's fits, ns"},
    [OB_COL_EVAL_NS] = {"eval_ns", "the job's measuring time, ns (its share of a batch by the work it used)"},
    [OB_COL_MESSAGE] = {"message", "why the job ended as it did, where not ok"},
    [OB_COL_FAMILY] = {"family", "the curve's family (random families, published, ...)"},
    [OB_COL_OFFSET_DEGREE] = {"offset_degree", "degree of the exact offset curve, where known"},
    [OB_COL_OFFSET_RATIONAL] = {"offset_rational", "yes: the exact offset is rational (a Pythagorean-hodograph base)"},
    [OB_COL_MAX_GAP] = {"max_gap", "largest distance between consecutive pieces' ends (empty: no joint)"},
    [OB_COL_MAX_KINK] = {"max_kink", "largest tangent angle at a closed joint, rad (empty: none)"},
    [OB_COL_CONTINUITY] = {"continuity", "the weakest joint: open, G0 or G1 (empty: one piece)"},
    [OB_COL_TIME_IQR_NS] = {"time_iqr_ns", "--reps N >= 2: interquartile range of the repetitions' fit_ns + eval_ns, whole ns "
                                           "(empty without)"},
    [OB_COL_TIME_CV] = {"time_cv", "--reps N >= 2: their coefficient of variation, sd / mean (empty without)"},
    [OB_COL_ERR_UPPER] = {"err_upper", "--certify: a certified upper bound of the two-sided Hausdorff distance to "
                                       "the exact offset (inf: a piece could not be bounded; empty without)"},
    [OB_COL_ERR_LOWER] = {"err_lower", "--certify: a certified lower bound of it, a distance attained (empty without)"},
    [OB_COL_CERTIFIED] = {"certified", "--certify: yes when err_upper <= tol, else no (empty without, or no "
                                       "approximation)"},
    [OB_COL_CERT_NS] = {"cert_ns", "--certify: thread CPU time of the job's certificate, ns (empty without)"},
    [OB_COL_FIT_CALLS] = {"fit_calls", "--time-fits: fit calls in one pass over the job's accepted pieces (empty "
                                       "without, or no approximation)"},
    [OB_COL_METHOD_NS] = {"method_ns", "--time-fits: the method's own time, thread CPU ns of one fit of each accepted "
                                       "piece, microbenchmarked, median of the rounds (empty without)"},
    [OB_COL_METHOD_IQR_NS] = {"method_iqr_ns", "--time-fits: interquartile range of the rounds' method_ns (empty "
                                               "without, or one round)"},
    [OB_COL_TRIMMED_ERR] = {"trimmed_err", "--trimmed: the approximation trimmed by its own crossings (as a CAD kernel "
                                           "trims) against the exact trimmed offset, the two-sided distance of the "
                                           "two point sets (empty without, or no approximation)"},
    [OB_COL_TRIMMED_CUT] = {"trimmed_cut", "--trimmed: regions (runs of arcs) of the approximation that trimming removed (0: none; "
                                           "empty without)"},
};

static char header[640];
static pthread_once_t header_once = PTHREAD_ONCE_INIT;

static void build_header(void)
{
    size_t k = 0;
    for (int c = 0; c < OB_NCOLS; c++) {
        const size_t n = strlen(ob_columns[c].name);
        if (k + n + 2 > sizeof header)
            break; /* cannot happen: the names are short (a test checks the whole header) */
        if (c)
            header[k++] = ',';
        memcpy(header + k, ob_columns[c].name, n);
        k += n;
    }
    header[k] = '\0';
}

const char *ob_results_header(void)
{
    pthread_once(&header_once, build_header);
    return header;
}
