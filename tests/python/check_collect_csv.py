"""Reads `carom collect --csv` back as a user would (Python's csv module and
pandas) and checks every cell against `carom collect --json`.

usage: check_collect_csv.py TABLE.csv TABLE.json
Prints the number of cells compared; exits non-zero naming the first cell that
differs (a shifted or missing column shows up here).
"""
import csv
import json
import math
import sys

import pandas

SUFFIXES = {"": "value", "_std_error": "std_error", "_spread": "spread",
            "_run_std_error": "run_std_error"}


def same(text, want):
    if want is None:
        return text is None or text == "" or (isinstance(text, float) and math.isnan(text))
    return float(text) == float(want)


def main(csv_path, json_path):
    table = json.load(open(json_path))
    axes = table["axes"]
    rows = list(csv.DictReader(open(csv_path, newline="")))
    frame = pandas.read_csv(csv_path)
    header = next(csv.reader(open(csv_path, newline="")))
    widths = {len(r) for r in csv.reader(open(csv_path, newline=""))}
    if widths != {len(header)}:
        sys.exit(f"rows of {sorted(widths)} fields under a header of {len(header)}")
    if len(rows) != len(table["points"]) or len(frame) != len(rows):
        sys.exit(f"{len(rows)} csv rows, {len(frame)} pandas rows, {len(table['points'])} points")
    cells = 0
    for k, point in enumerate(table["points"]):
        row = rows[k]
        for a in axes:
            if float(row[a]) != float(point["values"][a]) or float(frame[a][k]) != float(point["values"][a]):
                sys.exit(f"point {k}: axis {a} is {row[a]} / {frame[a][k]}, json {point['values'][a]}")
        if int(row["replicas"]) != len(point["runs"]):
            sys.exit(f"point {k}: replicas {row['replicas']} against {len(point['runs'])} runs")
        for q, result in point["results"].items():
            for suffix, field in SUFFIXES.items():
                column = q + suffix
                if column not in row:
                    sys.exit(f"no column {column} in the header {header}")
                want = result.get(field)
                if not same(row[column] or None, want):
                    sys.exit(f"point {k}: csv {column} = {row[column]!r}, json {field} = {want}")
                if not same(frame[column][k], want):
                    sys.exit(f"point {k}: pandas {column} = {frame[column][k]!r}, json {field} = {want}")
                cells += 1
    if cells == 0:
        sys.exit("no quantity compared")
    print(f"{cells} cells agree")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
