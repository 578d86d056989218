/*
 * columns.h - the columns of results.csv, once: their order, names and what
 * each holds.  The header line, the row writer (output.c), the reader
 * (results_csv.c), the journal and `./offbench list columns` all take them
 * from this table, so a column added here is added everywhere (new columns
 * go at the end: other tools read results.csv, README "Output").
 */
#ifndef OB_COLUMNS_H
#define OB_COLUMNS_H

typedef enum {
    OB_COL_CURVE, OB_COL_D, OB_COL_METHOD, OB_COL_METRIC, OB_COL_SPLIT, OB_COL_TOL,
    OB_COL_CTRL_POINTS, OB_COL_SEGMENTS, OB_COL_OUT_DEGREE, OB_COL_MAX_ERR, OB_COL_STATUS,
    OB_COL_FIT_NS, OB_COL_EVAL_NS, OB_COL_MESSAGE, OB_COL_FAMILY, OB_COL_OFFSET_DEGREE,
    OB_COL_OFFSET_RATIONAL, OB_COL_MAX_GAP, OB_COL_MAX_KINK, OB_COL_CONTINUITY,
    OB_COL_TIME_IQR_NS, OB_COL_TIME_CV, OB_COL_ERR_UPPER, OB_COL_ERR_LOWER, OB_COL_CERTIFIED, OB_COL_CERT_NS,
    OB_COL_FIT_CALLS, OB_COL_METHOD_NS, OB_COL_METHOD_IQR_NS, OB_COL_TRIMMED_ERR, OB_COL_TRIMMED_CUT,
    OB_NCOLS
} ob_col;

typedef struct {
    const char *name;
    const char *meaning;
} ob_column;

extern const ob_column ob_columns[OB_NCOLS];

/* The header line of results.csv (no newline): the names, comma-separated. */
const char *ob_results_header(void);

#endif
