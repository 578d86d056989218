"""The types of results.csv's columns (docs/output.md, `offbench list
columns`), one table for a fit's row and for read_results.

kinds:
  str    text ("" stays "")
  cat    text from a small set (pandas: category)
  float  a double; empty is NaN (none measured), "inf" and "nan" read as such
  int    a whole number, never empty
  int?   a whole number or empty (None; pandas: the nullable Int64)
  yesno  "yes" / "no" / empty: True / False / None (pandas: the nullable boolean)

A column the table does not know (a newer library's) is read as str.
"""

import math

KINDS = {
    "curve": "str",
    "d": "float",
    "method": "cat",
    "metric": "cat",
    "split": "cat",
    "tol": "float",
    "ctrl_points": "int",
    "segments": "int",
    "out_degree": "int",
    "max_err": "float",
    "status": "cat",
    "fit_ns": "int",
    "eval_ns": "int",
    "message": "str",
    "family": "cat",
    "offset_degree": "int?",
    "offset_rational": "yesno",
    "max_gap": "float",
    "max_kink": "float",
    "continuity": "cat",
    "time_iqr_ns": "int?",
    "time_cv": "float",
    "err_upper": "float",
    "err_lower": "float",
    "certified": "yesno",
    "cert_ns": "int?",
    "fit_calls": "int?",
    "method_ns": "float",
    "method_iqr_ns": "float",
    "trimmed_err": "float",
    "trimmed_cut": "int?",
}

# the pandas dtype of each kind
PANDAS_DTYPES = {
    "str": "object",
    "cat": "category",
    "float": "float64",
    "int": "int64",
    "int?": "Int64",
    "yesno": "boolean",
}

# columns that depend on the machine and the moment, not on the job
TIMING = ("fit_ns", "eval_ns", "time_iqr_ns", "time_cv", "cert_ns", "method_ns", "method_iqr_ns")


def kind(name):
    return KINDS.get(name, "str")


def _int(text):
    # fit_ns and eval_ns are written "%.0f": whole, but may be large
    try:
        return int(text)
    except ValueError:
        v = float(text)
        if not v.is_integer():
            raise
        return int(v)


def parse(name, text):
    """The value of column `name` from its text; ValueError when it does not
    read as its kind (the caller names the file and line)."""
    k = kind(name)
    if k in ("str", "cat"):
        return text
    if k == "float":
        return math.nan if text == "" else float(text)
    if k == "int":
        return _int(text)
    if k == "int?":
        return None if text == "" else _int(text)
    if k == "yesno":
        if text == "":
            return None
        if text in ("yes", "no"):
            return text == "yes"
        raise ValueError("%r is not yes, no or empty" % text)
    raise AssertionError(k)
