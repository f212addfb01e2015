"""Compare two studies' outputs file by file: the same numbers, bit for bit.

    python workflow/scripts/compare_results.py BEFORE AFTER

BEFORE and AFTER are study folders (each with results/ and reports/, as
``snakemake -j2`` or ``snakemake -d FOLDER`` writes them). Every file of
either is compared with its namesake:

* NetCDF: every variable and coordinate bit for bit (NaN equal to NaN), the
  same dimensions, and every attribute equal except the provenance ones that
  name a command, a module, a path, a time or a run's wall time
  (:data:`PROVENANCE`);
* CSV: the same table, cell for cell (a column that only one side has is a
  difference);
* HTML reports: the same text once time stamps, durations and file paths are
  taken out;
* everything else (design.json, STL, STEP, URDF, PNG, the manifest): the same
  bytes, except JSON files compared as data without their provenance keys.

Prints one line per difference and a count; exits 1 if any file differs or
is missing on one side.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
from pathlib import Path

import numpy as np

#: Attributes that record how a file was made, not what it holds.
PROVENANCE = re.compile(r"^(history|source|command|wall_time_s|wall_time|created|date_created|"
                        r"lsbg_version|.*_version|.*inputs_hash|python|platform|machine|"
                        r"fe_seconds.*|.*_seconds|seconds_per_.*|compliance_file|geometry_dir)$")
#: What a report's text may differ by: time stamps, durations, absolute paths.
VOLATILE = [re.compile(p) for p in (r"\d{4}-\d{2}-\d{2}[ T]\d{2}:\d{2}(:\d{2}(\.\d+)?)?",
                                    r"\d+(\.\d+)? ?s wall", r"/tmp/[\w/.-]+", r"/work/[\w/.-]+",
                                    r"lsbg\.[\w.]+")]


def _equal_arrays(a, b):
    if a.shape != b.shape or a.dtype.kind != b.dtype.kind:
        return False
    if a.dtype.kind in "fc":
        return bool(np.array_equal(a, b, equal_nan=True))
    return bool(np.array_equal(a, b))


def _attrs_differ(a, b, where):
    out = []
    for key in sorted(set(a) | set(b)):
        if PROVENANCE.match(key):
            continue
        x, y = a.get(key), b.get(key)
        same = (isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y))
        if not same and not _values_equal(x, y):
            out.append(f"{where}: attribute {key}: {x!r} != {y!r}")
    return out


def _values_equal(x, y):
    if isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
        return _equal_arrays(np.asarray(x), np.asarray(y))
    return x == y


def compare_netcdf(before, after, name):
    import xarray as xr

    with xr.open_dataset(before) as a, xr.open_dataset(after) as b:
        a, b = a.load(), b.load()
    out = _attrs_differ(a.attrs, b.attrs, name)
    for var in sorted(set(a.variables) | set(b.variables)):
        if var not in a.variables or var not in b.variables:
            out.append(f"{name}: variable {var} only in {'after' if var in b.variables else 'before'}")
            continue
        if PROVENANCE.match(var):
            continue
        if a[var].dims != b[var].dims or not _equal_arrays(a[var].values, b[var].values):
            out.append(f"{name}: variable {var} differs")
        out += _attrs_differ(a[var].attrs, b[var].attrs, f"{name}:{var}")
    return out


def compare_csv(before, after, name):
    import pandas as pd

    a, b = pd.read_csv(before), pd.read_csv(after)
    if list(a.columns) != list(b.columns):
        return [f"{name}: columns {sorted(set(a.columns) ^ set(b.columns))} on one side only"]
    if a.shape != b.shape:
        return [f"{name}: {a.shape} rows x columns, after {b.shape}"]
    differ = [c for c in a.columns if not PROVENANCE.match(c) and not a[c].equals(b[c])]
    return [f"{name}: column {c} differs" for c in differ]


def _report_text(path):
    text = re.sub(r"<[^>]+>", " ", path.read_text(encoding="utf-8"))
    text = re.sub(r"data:image/png;base64,[A-Za-z0-9+/=]+", "", text)
    for pattern in VOLATILE:
        text = pattern.sub("#", text)
    return " ".join(text.split())


def compare_html(before, after, name):
    """The words that differ between two reports' texts, each with its context."""
    import difflib

    a, b = _report_text(before).split(), _report_text(after).split()
    out = []
    for tag, i1, i2, j1, j2 in difflib.SequenceMatcher(a=a, b=b, autojunk=False).get_opcodes():
        if tag != "equal":
            context = " ".join(a[max(0, i1 - 8):i1])
            out.append(f"{name}: ...{context} [{' '.join(a[i1:i2])}] -> [{' '.join(b[j1:j2])}]")
    return out


def compare_json(before, after, name):
    a, b = (json.loads(p.read_text(encoding="utf-8")) for p in (before, after))
    drop = (lambda d: {k: v for k, v in d.items() if not PROVENANCE.match(k)}
            if isinstance(d, dict) else d)
    return [] if drop(a) == drop(b) else [f"{name}: JSON differs"]


def compare(before, after):
    """Every difference between two study folders' outputs, one line each."""
    names = set()
    for root in (before, after):
        for top in ("results", "reports"):
            names |= {p.relative_to(root) for p in (root / top).rglob("*") if p.is_file()}
    out = []
    for name in sorted(names):
        a, b = before / name, after / name
        if not a.is_file() or not b.is_file():
            out.append(f"{name}: only {'after' if b.is_file() else 'before'}")
            continue
        suffix = name.suffix
        if suffix == ".nc":
            out += compare_netcdf(a, b, name)
        elif suffix == ".csv":
            out += compare_csv(a, b, name)
        elif suffix == ".html":
            out += compare_html(a, b, name)
        elif suffix == ".json" and name.name != "manifest.json":
            out += compare_json(a, b, name)
        elif name.name in ("manifest.json", "config.yaml"):
            continue  # the manifest hashes the files compared here; the config is the input
        elif a.read_bytes() != b.read_bytes():
            out.append(f"{name}: bytes differ")
    return out, len(names)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before", type=Path)
    parser.add_argument("after", type=Path)
    args = parser.parse_args(argv)
    differences, count = compare(args.before, args.after)
    for line in differences:
        print(line)
    print(f"{count} files compared, {len(differences)} differences")
    return 1 if differences else 0


if __name__ == "__main__":
    sys.exit(main())
