#!/usr/bin/python3
"""Reads a granflow run folder (the `--out DIR` of `granflow run`) into numpy arrays.

The one reader of the output files, used by the figure, verification and validation scripts
and by the test tools. Needs numpy only (Debian's /usr/bin/python3 with python3-numpy);
tables convert to pandas DataFrames where python3-pandas happens to be installed.

User guide
----------
Load a run (from the repository root; from elsewhere put the repository's scripts/ folder on
sys.path first):

    import sys; sys.path.insert(0, "scripts")
    import granflow_run as gr
    run = gr.Run("out/ar07_rough")
    run.title, run.grid                 # the case title, "256 x 64"
    run.summary["runout_m"]             # summary.json as a dict ...
    run.summary_units["runout_m"]       # ... with the unit of each key: "m"
    run.case["grid"]["n"]               # case.toml, the fully resolved case, as a dict
    run.case_units["domain.Lx"]         # "m", read from the file's own comments

Tables (diagnostics.csv, profiles.csv, structure.csv, deposit.csv, probes/NAME.csv) are
`Table` objects: one numpy array per column, with its unit.

    d = run.diagnostics
    d["t"], d["front_x"]                # numpy float arrays, one value per output time
    d.columns                           # the column names, in the file's order
    d.units["front_x"]                  # "m"
    print(d.describe())                 # every column with its unit, count and range
    len(d)                              # the number of rows; bool(d) is False when empty
    d.to_pandas()                       # a DataFrame (units in df.attrs["units"]), if pandas

A table missing from the folder (structure.csv of a one-phase run, say) is an empty Table:
`if run.structure:` tells whether there is one.

Output times. A row written when a step lands on the output schedule (a multiple of
output.interval, or t_end) carries the scheduled time itself (0.3, not the float noise of the
steps' sum, 0.30000000000000004); other rows (adaptive steps that do not land on it, the row of
a failure or a stop) carry the step's time, to 17 digits. Select a time by distance:

    d.times                             # the distinct output times, sorted
    p = run.profiles.at(0.3)            # the rows of the output time within 1e-9 s of 0.3 s
    p = run.profiles.at(0.3, tol=0.01)  # ... within 0.01 s (a LookupError if there is none)
    p = run.profiles.at(0.3, tol=None)  # ... the nearest output time, however far
    p.times[0]                          # the output time actually picked
    x, h = p["x"], p["h"]
    for t, block in run.profiles.blocks(): ...    # one Table per output time
    st = run.structure.at(0.3)          # both cut-offs at 0.3 s ...
    st = st.where(st["cutoff"] == 0.075)  # ... the 7.5 % one (a value of the file: == is safe)

Fields (the VTK series fields.pvd / fields_NNNNNN.vtr: cell values of a 2-D rectilinear grid):

    run.snapshots                       # [(t, path), ...] of fields.pvd, in time order
    f = run.fields(0.3, tol=None)       # the snapshot nearest t = 0.3 s (`Fields`)
    f.t                                 # its time (s)
    f.xc, f.yc                          # cell-centre coordinates (m), f.xn, f.yn the nodes
    f.names                             # phi, rho, u, speed, p, eta, D_norm, S_norm, ...
    f["p"]                              # shape (ny, nx): f["p"][j, i] at (f.xc[i], f.yc[j])
    f["u"]                              # shape (ny, nx, 3): u, v and a zero third component
    f.units["p"]                        # "Pa"
    f.granular_mask                     # phi < 0: the granular phase
    f.granular("speed")                 # |u| masked (numpy.ma) where phi >= 0 (the air)

Probes: `run.probe_names`, `run.probe("bottom")` (a Table of t, x, y and the probe's fields,
a block of rows per output time: `.blocks()` or `.at(t)`).

Command line: `scripts/granflow_run.py RUN_DIR [--time T]` lists what a run folder holds (every
file, column and summary key with its unit, the output times, the fields of the VTK series)
and, with --time, the values of diagnostics.csv at the output time nearest T.

The units come from the README's output table and the headers of src/diagnostics/*.hpp and
src/io/Probes.hpp (exact definitions there); "1" marks a dimensionless quantity, "-" a count.
"""
import argparse
import json
import math
import os
import re
import struct
import sys
import tomllib
import xml.etree.ElementTree as ET

import numpy as np

# Times closer than this (s) are the same output time: far below any output interval, far
# above the float noise of the times' sums.
TIME_TOL = 1e-9

# ---- Units of every column the C++ writers produce (README, "What a run writes").
DIAGNOSTICS_UNITS = {
    "t": "s", "dt": "s", "step": "-", "granular_volume": "m²/m", "volume_change_pct": "%",
    "max_speed": "m/s", "granular_u": "m/s", "granular_v": "m/s", "kinetic_energy": "J/m",
    "max_divergence": "1/s", "visc_its": "-", "pres_its": "-", "fp_iters": "-",
    "fp_change": "1", "left_stick_m": "m", "left_slide_m": "m", "bottom_stick_m": "m",
    "bottom_slide_m": "m", "left_normal_N": "N/m", "left_friction_N": "N/m",
    "bottom_normal_N": "N/m", "bottom_friction_N": "N/m", "front_x": "m", "backwall_h": "m",
    "max_p_granular": "Pa", "max_speed_granular": "m/s", "volume_step_change": "1",
    "potential_energy": "J/m", "dissipated_viscous": "J/m", "dissipated_plastic": "J/m",
    "dissipated_friction": "J/m", "energy_residual": "J/m", "side_stick_m2": "m²",
    "side_slide_m2": "m²", "side_normal_N": "N/m", "side_friction_x_N": "N/m",
    "side_friction_y_N": "N/m", "gate_bottom_m": "m", "gate_normal_N": "N/m",
    "gate_friction_N": "N/m", "fp_change_max": "1", "fp_capped_steps": "-",
}
PROFILES_UNITS = {"t": "s", "x": "m", "h": "m"}
STRUCTURE_UNITS = {"t": "s", "cutoff": "1", "x": "m", "h": "m", "h_deposit": "m", "h_l": "m"}
DEPOSIT_UNITS = {
    "t": "s", "cutoff": "1", "max_speed_granular": "m/s", "u_ref": "m/s", "front_x": "m",
    "x_deposit": "m", "L": "m", "L_d": "m", "L_h": "m", "A": "m²/m", "A_d": "m²/m",
    "Ad_over_A": "1",
}
# Cell fields of the VTK series and of the probes (phi is a signed distance, m; S_norm is |S|,
# below 1 where the material is rigid; yielded is 1 flowing, 0 rigid).
FIELD_UNITS = {
    "phi": "m", "rho": "kg/m³", "u": "m/s", "v": "m/s", "speed": "m/s", "p": "Pa",
    "eta": "Pa s", "D_norm": "1/s", "S_norm": "1", "yielded": "1", "kappa": "Pa",
    "volume_fraction": "1",
}
PROBE_UNITS = {"t": "s", "x": "m", "y": "m", **FIELD_UNITS}
FILE_UNITS = {"diagnostics.csv": DIAGNOSTICS_UNITS, "profiles.csv": PROFILES_UNITS,
              "structure.csv": STRUCTURE_UNITS, "deposit.csv": DEPOSIT_UNITS}

# summary.json: the keys whose unit its name does not say, then the naming rule.
SUMMARY_UNITS = {
    "t_end": "s", "checkpoint_t": "s", "max_divergence": "1/s", "max_speed": "m/s",
    "kinetic_energy": "J/m", "max_speed_granular_end": "m/s", "max_p_granular_ratio": "1",
    "fp_capped_max_change": "1", "interface_l1_error_m2": "m²", "s_per_step": "s",
    "nx": "cells", "ny": "cells", "cells": "cells", "ranks": "-",
}
_SUFFIX_UNITS = [("_mps", "m/s"), ("_pct", "%"), ("_deg", "°"), ("_pa", "Pa"), ("_m2", "m²"),
                 ("_mib_max_rank", "MiB"), ("_mib_all_ranks", "MiB"), ("_s", "s"), ("_m", "m")]
_TEXT_KEYS = {"title", "status", "message", "version"}


def summary_unit(key):
    """Unit of a summary.json key ("" for text, "-" for counts)."""
    if key in SUMMARY_UNITS:
        return SUMMARY_UNITS[key]
    if key in _TEXT_KEYS:
        return ""
    for suffix, unit in _SUFFIX_UNITS:
        if key.endswith(suffix):
            return unit
    return "-"  # steps, iteration totals, warnings, restarts: counts


class RunFileError(ValueError):
    """A run file that exists but cannot be read as what it should be."""


# ------------------------------------------------------------------------------- tables
class Table:
    """Columns of a CSV file as numpy float arrays, in the file's order, with their units.

    Behaves like a read-only dict of columns (t["x"], "x" in t, t.items()) and, like a pandas
    DataFrame, has len() = its number of rows, so that `if table:` is False for a missing or
    empty file."""

    def __init__(self, columns, units=None, path=None):
        self._c = dict(columns)
        self.units = {k: (units or {}).get(k, "") for k in self._c}
        self.path = path

    # -- the dict of columns
    @property
    def columns(self):
        return list(self._c)

    def __getitem__(self, name):
        try:
            return self._c[name]
        except KeyError:
            where = f" of {self.path}" if self.path else ""
            have = ", ".join(self._c) if self._c else "none: the file is missing or empty"
            raise KeyError(f"no column {name!r}{where} (columns: {have})") from None

    def __contains__(self, name):
        return name in self._c

    def __iter__(self):
        return iter(self._c)

    def keys(self):
        return self._c.keys()

    def values(self):
        return self._c.values()

    def items(self):
        return self._c.items()

    def get(self, name, default=None):
        return self._c.get(name, default)

    # -- the rows
    def __len__(self):
        return len(next(iter(self._c.values()))) if self._c else 0

    def __bool__(self):
        return len(self) > 0

    def where(self, mask):
        """The rows where the boolean array `mask` is True (a Table)."""
        return Table({k: v[mask] for k, v in self._c.items()}, self.units, self.path)

    def row(self, i):
        """Row i as a dict of floats."""
        return {k: float(v[i]) for k, v in self._c.items()}

    def array(self):
        """All columns as one 2-D array, shape (rows, columns)."""
        return np.column_stack(list(self._c.values())) if self._c else np.zeros((0, 0))

    # -- output times
    @property
    def times(self):
        """The distinct values of column t, sorted."""
        return np.unique(self["t"])

    def nearest_time(self, t, tol=TIME_TOL):
        """The output time nearest t (s); a LookupError if it is further than tol (None: any)."""
        return float(self.times[nearest(self.times, t, tol, what=self.path)])

    def at(self, t, tol=TIME_TOL):
        """The rows of the output time nearest t (within tol s; tol=None: however far)."""
        return self.where(self["t"] == self.nearest_time(t, tol))

    def blocks(self):
        """[(t, Table of that output time's rows)] in time order (probes, profiles)."""
        return [(float(tv), self.where(self["t"] == tv)) for tv in self.times]

    # -- others
    def to_pandas(self):
        """A pandas DataFrame of the table (units in df.attrs["units"]); needs python3-pandas."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("Table.to_pandas needs pandas (Debian: python3-pandas); the "
                              "numpy columns (table[name]) need nothing more") from None
        df = pd.DataFrame(self._c)
        df.attrs["units"] = dict(self.units)
        return df

    def describe(self):
        """One line per column: name, unit, and the range of its finite values."""
        lines = [f"{self.path or 'table'}: {len(self)} rows, {len(self._c)} columns"]
        for k, v in self._c.items():
            fin = v[np.isfinite(v)]
            rng = f"{fin.min():.6g} .. {fin.max():.6g}" if len(fin) else "no finite value"
            lines.append(f"  {k:<22} {self.units.get(k) or '?':<7} {rng}")
        return "\n".join(lines)

    def __repr__(self):
        return f"Table({self.path!r}, {len(self)} rows, columns {self.columns})"


def nearest(values, t, tol=TIME_TOL, what=None):
    """Index of the entry of `values` (output times, s) nearest t. Raises LookupError when it is
    further than tol from t (tol=None: accept any distance) or when there is none."""
    values = np.asarray(values, dtype=float)
    src = f" in {what}" if what else ""
    if values.size == 0:
        raise LookupError(f"no output time{src}")
    k = int(np.argmin(np.abs(values - t)))
    if tol is not None and not abs(values[k] - t) <= tol:
        raise LookupError(f"no output time{src} within {tol:g} s of t = {t:g} s (nearest "
                          f"{values[k]:.17g} s; outputs {values.min():g} .. {values.max():g} s)")
    return k


def read_csv(path, units=None, missing_ok=False):
    """A CSV file of granflow (one header line, numbers; blank lines and '#' lines skipped) as a
    Table. A missing file is a FileNotFoundError, or an empty Table with missing_ok; an empty
    file is an empty Table; a ragged or non-numeric line a RunFileError. Units: `units`, else
    those of the file's name (diagnostics.csv, profiles.csv, ...) where granflow writes it."""
    if units is None:
        units = FILE_UNITS.get(os.path.basename(path), {})
    try:
        with open(path) as f:
            lines = [ln.strip() for ln in f if ln.strip() and not ln.lstrip().startswith("#")]
    except FileNotFoundError:
        if missing_ok:
            return Table({}, units, path)
        raise
    if not lines:
        return Table({}, units, path)
    header = [h.strip() for h in lines[0].split(",")]
    if len(set(header)) != len(header):
        raise RunFileError(f"{path}: the header repeats a column: {lines[0]!r}")
    rows = []
    for n, ln in enumerate(lines[1:], start=2):
        parts = ln.split(",")
        if len(parts) != len(header):
            raise RunFileError(f"{path}: data line {n} has {len(parts)} fields, header "
                               f"has {len(header)}")
        try:
            rows.append([float(p) for p in parts])
        except ValueError:
            raise RunFileError(f"{path}: data line {n} is not numeric: {ln!r}") from None
    data = np.array(rows, dtype=float).reshape(len(rows), len(header))
    return Table({h: data[:, k].copy() for k, h in enumerate(header)}, units, path)


# ---------------------------------------------------------------------- VTK fields
class Fields:
    """One snapshot of the VTK series: cell fields on the rectilinear grid.

    xn, yn: node coordinates (m, nx + 1 and ny + 1 values); xc, yc: cell centres; t: the
    snapshot's time (s). f[name] has shape (ny, nx) for a scalar, (ny, nx, 3) for a vector
    (2-D vectors are written with a zero third component, as VTK wants)."""

    def __init__(self, xn, yn, arrays, t=float("nan"), path=None):
        self.xn, self.yn, self.t, self.path = xn, yn, t, path
        self.xc, self.yc = 0.5 * (xn[1:] + xn[:-1]), 0.5 * (yn[1:] + yn[:-1])
        self.nx, self.ny = len(xn) - 1, len(yn) - 1
        self._a = arrays  # name -> (flat values, components)
        self.units = {k: FIELD_UNITS.get(k, "") for k in arrays}

    @property
    def names(self):
        return list(self._a)

    def __contains__(self, name):
        return name in self._a

    def __getitem__(self, name):
        if name not in self._a:
            raise KeyError(f"no field {name!r} in {self.path} (fields: {', '.join(self._a)})")
        a, nc = self._a[name]
        return a.reshape(self.ny, self.nx) if nc == 1 else a.reshape(self.ny, self.nx, nc)

    @property
    def granular_mask(self):
        """True in the granular phase, phi < 0."""
        return self["phi"] < 0

    def granular(self, name):
        """Field `name` as a masked array, masked in the air (phi >= 0)."""
        return np.ma.masked_where(self["phi"] >= 0, self[name])

    def __repr__(self):
        return f"Fields({self.path!r}, t = {self.t:g} s, {self.nx} x {self.ny}, {self.names})"


def read_vtr(path):
    """A VTK XML RectilinearGrid file as granflow writes it (src/io/Vtk.cpp: appended raw data,
    each block a byte count then Float64 values; cell data; time in FieldData TimeValue)."""
    with open(path, "rb") as f:
        raw = f.read()
    try:
        head = raw.index(b"<AppendedData")
        k = raw.index(b"_", head) + 1  # the blocks start after the underscore
        root = ET.fromstring(raw[:head].decode() + "</VTKFile>")
    except (ValueError, ET.ParseError) as e:
        raise RunFileError(f"{path}: not a VTK RectilinearGrid file with appended data ({e})")
    end = "<" if root.get("byte_order", "LittleEndian") == "LittleEndian" else ">"
    count = {"UInt64": "Q", "UInt32": "I"}[root.get("header_type", "UInt32")]
    hsize = struct.calcsize(count)

    def block(off):
        n = struct.unpack_from(end + count, raw, k + off)[0]
        return np.frombuffer(raw, dtype=end + "f8", count=n // 8, offset=k + off + hsize)

    arrays, t = {}, float("nan")
    for da in root.iter("DataArray"):
        if da.get("Name") == "TimeValue" and da.get("format") == "ascii":
            t = float(da.text.split()[0])
    cell = next(root.iter("CellData"), None)
    for da in (cell.iter("DataArray") if cell is not None else ()):
        arrays[da.get("Name")] = (block(int(da.get("offset"))),
                                  int(da.get("NumberOfComponents", "1")))
    coords = next(root.iter("Coordinates"))
    xn, yn = [block(int(da.get("offset"))) for da in coords.iter("DataArray")][:2]
    return Fields(xn, yn, arrays, t, path)


def bottom_toes(path):
    """The granular phase's two toes on the bottom wall in the VTK file `path`: (t in s,
    left toe x in m, right toe x in m, cell width in m). phi is extrapolated linearly from the
    two lowest cell rows to the wall and its zero crossings interpolated between columns."""
    f = read_vtr(path)
    phi, x = f["phi"], f.xc
    pb = 1.5 * phi[0] - 0.5 * phi[1]  # phi extrapolated to the bottom
    k = np.where(pb < 0)[0]
    i0, i1 = k[0], k[-1]
    xl = x[i0 - 1] + (x[i0] - x[i0 - 1]) * pb[i0 - 1] / (pb[i0 - 1] - pb[i0])
    xr = x[i1] + (x[i1 + 1] - x[i1]) * pb[i1] / (pb[i1] - pb[i1 + 1])
    return f.t, xl, xr, x[1] - x[0]


def read_pvd(path, join=True):
    """[(t, path of the file)] of a ParaView collection, in the file's order (join=False: the
    file names as listed, relative to the collection's folder)."""
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        raise RunFileError(f"{path}: not valid XML: {e}") from None
    if root.tag != "VTKFile" or root.get("type") != "Collection":
        raise RunFileError(f"{path}: not a VTK Collection (root <{root.tag} "
                           f"type={root.get('type')}>)")
    folder = os.path.dirname(path) if join else ""
    return [(float(e.get("timestep")), os.path.join(folder, e.get("file")))
            for e in root.iter("DataSet")]


# ----------------------------------------------------------------------- case.toml
_UNIT_COMMENT = re.compile(r"^#.*\bunit: ([^|]+?)\s*(\||$)")
_SECTION = re.compile(r"^\[\[?([^\]]+)\]\]?\s*$")
_KEY = re.compile(r"^([A-Za-z0-9_\-]+)\s*=")


def case_units(path):
    """{"section.key": unit} from the comments of a resolved case.toml ("# unit: m | ...")."""
    units, section, pending = {}, "", None
    with open(path) as f:
        for line in f:
            line = line.strip()
            m = _UNIT_COMMENT.match(line)
            if m:
                pending = m.group(1)
                continue
            m = _SECTION.match(line)
            if m:
                section, pending = m.group(1).strip(), None
                continue
            m = _KEY.match(line)
            if m:
                if pending:
                    units[f"{section}.{m.group(1)}" if section else m.group(1)] = pending
                pending = None
    return units


# ----------------------------------------------------------------------------- runs
class Run:
    """A run folder. Every file is read when first asked for, then kept."""

    def __init__(self, folder, must_exist=True):
        self.folder = folder
        if must_exist and not os.path.isdir(folder):
            raise FileNotFoundError(f"{folder}: no such run folder")
        self._cache = {}

    def path(self, *name):
        return os.path.join(self.folder, *name)

    def has(self, name):
        return os.path.exists(self.path(name))

    def _once(self, key, make):
        if key not in self._cache:
            self._cache[key] = make()
        return self._cache[key]

    @property
    def name(self):
        return os.path.basename(os.path.normpath(self.folder))

    # -- case and summary
    @property
    def case(self):
        """case.toml as a dict ({} without one)."""
        def load():
            if not self.has("case.toml"):
                return {}
            with open(self.path("case.toml"), "rb") as f:
                return tomllib.load(f)
        return self._once("case", load)

    @property
    def case_units(self):
        return self._once("case_units", lambda: case_units(self.path("case.toml"))
                          if self.has("case.toml") else {})

    @property
    def summary(self):
        """summary.json as a dict ({} without one)."""
        def load():
            if not self.has("summary.json"):
                return {}
            with open(self.path("summary.json")) as f:
                return json.load(f)
        return self._once("summary", load)

    @property
    def summary_units(self):
        return {k: summary_unit(k) for k in self.summary}

    def value(self, key):
        """A number of summary.json as a float (NaN where it is missing or null)."""
        v = self.summary.get(key)
        return float("nan") if v is None else float(v)

    @property
    def title(self):
        return self.case.get("title", self.folder)

    @property
    def grid(self):
        return f"{self.summary.get('nx')} x {self.summary.get('ny')}"

    # -- tables
    def table(self, name):
        """The Table of a CSV file of the folder (empty if the file is missing)."""
        return self._once(name, lambda: read_csv(self.path(name), missing_ok=True))

    diagnostics = property(lambda self: self.table("diagnostics.csv"))
    profiles = property(lambda self: self.table("profiles.csv"))
    structure = property(lambda self: self.table("structure.csv"))
    deposit = property(lambda self: self.table("deposit.csv"))

    @property
    def probe_names(self):
        folder = self.path("probes")
        return sorted(f[:-4] for f in os.listdir(folder) if f.endswith(".csv")) \
            if os.path.isdir(folder) else []

    def probe(self, name):
        """probes/NAME.csv as a Table (a FileNotFoundError if there is no such probe)."""
        return self._once(f"probes/{name}", lambda: read_csv(self.path("probes", name + ".csv"),
                                                             units=PROBE_UNITS))

    # -- fields
    @property
    def snapshots(self):
        """[(t, path)] of fields.pvd ([] without one)."""
        return self._once("pvd", lambda: read_pvd(self.path("fields.pvd"))
                          if self.has("fields.pvd") else [])

    def fields(self, t=None, tol=TIME_TOL, index=None):
        """The snapshot nearest time t (within tol; tol=None: the nearest), or number `index`
        (-1 the last), as Fields."""
        snaps = self.snapshots
        if not snaps:
            raise LookupError(f"{self.folder}: no VTK series (fields.pvd)")
        if index is None:
            if t is None:
                raise ValueError("Run.fields: give a time t or an index")
            index = nearest([s[0] for s in snaps], t, tol, what=self.path("fields.pvd"))
        ts, path = snaps[index]
        f = read_vtr(path)
        if math.isnan(f.t):
            f.t = ts
        return f

    def __repr__(self):
        return f"Run({self.folder!r})"


# ----------------------------------------------------------------------- inventory
def inventory(run, time=None):
    """What `granflow_run.py RUN_DIR` prints: the folder's files, columns, units and times."""
    out = [f"run folder {run.folder}: {run.title}"]
    s = run.summary
    if s:
        out.append(f"summary.json: {len(s)} keys (status {s.get('status', '?')})")
        out += [f"  {k:<34} {summary_unit(k) or '':<7} {v}" for k, v in s.items()
                if not isinstance(v, (dict, list))]
    for name in FILE_UNITS:
        tb = run.table(name)
        if tb:
            out.append(tb.describe())
            out.append(f"  output times: {len(tb.times)}, {tb.times[0]:g} .. {tb.times[-1]:g} s")
    for p in run.probe_names:
        out.append(run.probe(p).describe())
    snaps = run.snapshots
    if snaps:
        f = run.fields(index=0)
        out.append(f"fields.pvd: {len(snaps)} snapshots, t = {snaps[0][0]:g} .. "
                   f"{snaps[-1][0]:g} s, grid {f.nx} x {f.ny}, fields "
                   + ", ".join(f"{n} ({f.units[n] or '?'})" for n in f.names))
    if time is not None:
        d = run.diagnostics
        row = d.at(time, tol=None)
        out.append(f"diagnostics.csv at the output time nearest {time:g} s:")
        out += [f"  {k:<22} {d.units.get(k) or '?':<7} {v[0]:.10g}" for k, v in row.items()]
    return "\n".join(out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                 epilog="The module's docstring is its user guide: "
                                        "/usr/bin/python3 -c 'import granflow_run; "
                                        "help(granflow_run)' from scripts/.")
    ap.add_argument("run_dir", help="a granflow output folder (--out DIR of granflow run)")
    ap.add_argument("--time", type=float, help="also print diagnostics.csv at this time (s)")
    a = ap.parse_args(argv)
    if not os.path.isdir(a.run_dir):
        ap.error(f"{a.run_dir}: no such folder")
    try:
        print(inventory(Run(a.run_dir), a.time))
    except (RunFileError, LookupError, OSError) as e:
        sys.exit(f"granflow_run: {e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
