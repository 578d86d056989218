"""csvrows.py - the CSV reader shared by scripts/plot.py and
scripts/plot_tables.py: rows as dicts keyed by header names, numbers parsed,
every error exits through the caller's `die` naming FILE:LINE."""
import csv


def read_csv(path, columns, numeric, integer=(), die=None):
    """The rows of a CSV file as dicts keyed by the header names.

    `columns` must all be present (others are ignored), the fields in `numeric`
    are parsed as floats (empty allowed: None) and those in `integer` as ints.
    Each row gets its line number as row['_line'].  die(message) must not
    return (the scripts print the message and exit 2)."""
    try:
        f = open(path, newline="", encoding="utf-8-sig")
    except OSError as e:
        die(f"cannot read {path}: {e.strerror}")
    rows = []
    with f:
        reader = csv.reader(f)
        try:
            header = next(reader, None)
            if header is None:
                die(f"{path}:1: empty file (expected a header with columns {','.join(columns)})")
            header = [h.strip() for h in header]
            missing = [c for c in columns if c not in header]
            if missing:
                die(f"{path}:1: missing column{'s' if len(missing) > 1 else ''} "
                    f"{', '.join(missing)} (header: {','.join(header)})")
            index = {c: header.index(c) for c in columns}
            while True:
                line = reader.line_num + 1  # where this record starts
                fields = next(reader, None)
                if fields is None:
                    break
                if not any(x.strip() for x in fields):
                    continue
                if len(fields) != len(header):
                    hint = " (unbalanced quote?)" if any("\n" in x for x in fields) else ""
                    die(f"{path}:{line}: {len(fields)} fields, the header has {len(header)}{hint}")
                row = {c: fields[i].strip() for c, i in index.items()}
                for c in numeric:
                    text = row[c]
                    if text == "":
                        row[c] = None
                        continue
                    try:
                        row[c] = float(text)
                    except ValueError:
                        die(f"{path}:{line}: {c} is not a number: {text!r}")
                    if c in integer:
                        if not row[c].is_integer():
                            die(f"{path}:{line}: {c} is not an integer: {text!r}")
                        row[c] = int(row[c])
                row["_line"] = line
                rows.append(row)
        except csv.Error as e:
            die(f"{path}:{reader.line_num}: {e}")
        except UnicodeDecodeError:
            die(f"{path}: not UTF-8 text")
    return rows


