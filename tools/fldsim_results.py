"""Reading helpers for fldsim result files (HDF5), shared by the plotting scripts.

Layout written by the core and the observers:
  /parameters              attributes peclet, volume_fraction, shape_c (numbers), shape, time_unit
  /results/<observer>/<q>  scalar datasets with attributes unit and stderr; arrays
  /timeseries/<name>/<q>   H5MD time series: groups with step, time (run's unit), value
                           (files before 2026-12 kept them under /observables, times in a^2/D0)
"""
import math

import numpy as np


def text(value):
    """An HDF5 attribute as a Python string."""
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, np.ndarray) and value.shape == ():
        return text(value[()])
    return str(value)


def parameter(h5, key, default=None):
    """A /parameters attribute (string), or default when absent."""
    grp = h5.get("parameters")
    if grp is None or key not in grp.attrs:
        return default
    return text(grp.attrs[key])


def number(h5, key, default=math.nan):
    value = parameter(h5, key)
    try:
        return float(value)
    except (TypeError, ValueError):
        return default


def scalar(h5, path):
    """(value, stderr) of a result scalar, or None when the observer did not write it."""
    d = h5.get(path)
    if d is None or not hasattr(d, "shape"):
        return None
    value = float(np.asarray(d[()]).reshape(-1)[0])
    err = float(d.attrs["stderr"]) if "stderr" in d.attrs else math.nan
    return value, err


def array(h5, path):
    """A result array as numpy, or None."""
    d = h5.get(path)
    if d is None or not hasattr(d, "shape"):
        return None
    return np.asarray(d[()])


def _series_group(h5, path):
    g = h5.get(path)
    if g is None and path.startswith("timeseries/"):  # older files
        g = h5.get("observables/" + path[len("timeseries/"):])
    return g


def series_time_unit(h5, path):
    """The unit of a time series' time, as stored ("a^2/D0" for files without one)."""
    g = _series_group(h5, path)
    if g is None or "time" not in g:
        return "a^2/D0"
    return text(g["time"].attrs.get("unit", "a^2/D0"))


def series(h5, path):
    """(time, value) of an H5MD time series, or None."""
    g = _series_group(h5, path)
    if g is None or "value" not in g or "time" not in g:
        return None
    return np.asarray(g["time"][()]), np.asarray(g["value"][()])


# Kumar & Higdon's names of the symmetric dicolloids (a = b) by their centre distance c/a.
DICOLLOID_NAMES = {0.2: "homonuclear", 1.0: "fused dumbbell"}


def shape_label(h5):
    """A readable shape name; dicolloids carry their c/a and, for the paper's two, its name."""
    shape = parameter(h5, "shape", "unknown")
    c = parameter(h5, "shape_c")
    if c is not None:
        try:
            cv = float(c)
        except ValueError:
            return f"{shape} c={c}"
        named = DICOLLOID_NAMES.get(round(cv, 6)) if shape == "dicolloid" else None
        return f"{named} (c/a={cv:g})" if named else f"{shape} c/a={cv:g}"
    return shape
