"""Errors of one run against the reference run, read from their result files.

Deterministic runs (kT = 0, same start, same strain): RMS over bodies of
  - the centre displacement between the two runs, taken as the Lees-Edwards minimum image
    (the image at y + L is shifted by the offset in x, TrajectoryLayout.hpp), in a;
  - the rotation angle between the two orientations (4 atan2(|q1 - q2|, |q1 + q2|) for unit
    quaternions with q1 . q2 >= 0, exact also for small angles), in rad.

Brownian runs: steady-state eta_r and delta_theta_m with their standard errors
(/results/stress/eta_r, /results/orientation/delta_theta_m, attribute stderr), and g(r) near
contact: the mean of g over the shells with centres in CONTACT_SHELL, its SE from the per-shell
Poisson SEs. Error = |value - reference|, compared with the combined SE sqrt(se^2 + se_ref^2);
"consistent" when within 2 combined SE.
"""
import math
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
import fldsim_results as results  # noqa: E402

POSITION = "/particles/bodies/position"
ORIENTATION = "/particles/bodies/orientation"
OFFSET = "/particles/bodies/lees_edwards/offset"
STRAIN = "/particles/bodies/lees_edwards/strain"
EDGES = "/particles/bodies/box/edges"

# Homonuclear dicolloids (c = 0.2 a) touch at centre distances 2a (side by side) to 2.2a (end to
# end); the shells of g(r) centred in [2.0, 2.4) a hold the contact peak.
CONTACT_SHELL = (2.0, 2.4)

CONSISTENT_SE = 2.0


def last_frame(h5):
    """(positions N x 3, quaternions N x 4, Lees-Edwards offset, box edge, strain) of the last
    trajectory frame."""
    edges = np.asarray(h5[EDGES + "/value"][-1])  # the box vectors (3 x 3, H5MD), or older files' 3 edges
    edge = float(edges[0, 0] if edges.ndim == 2 else edges[0])
    return (np.asarray(h5[POSITION + "/value"][-1]), np.asarray(h5[ORIENTATION + "/value"][-1]),
            float(h5[OFFSET + "/value"][-1]), edge, float(h5[STRAIN + "/value"][-1]))


def minimum_image(d, edge, offset):
    """Lees-Edwards minimum image of separations d (N x 3): crossing y by n L shifts x by n offset."""
    d = d.copy()
    ny = np.round(d[:, 1] / edge)
    d[:, 0] -= ny * offset
    d[:, 1] -= ny * edge
    d[:, 0] -= np.round(d[:, 0] / edge) * edge
    d[:, 2] -= np.round(d[:, 2] / edge) * edge
    return d


def trajectory_error(path, reference_path):
    """(RMS position error in a, RMS orientation error in rad) between the last frames of two runs
    from the same start to the same strain."""
    with h5py.File(path, "r") as f, h5py.File(reference_path, "r") as g:
        x, q, offset, edge, strain = last_frame(f)
        x_ref, q_ref, offset_ref, _, strain_ref = last_frame(g)
    if abs(strain - strain_ref) > 1e-9 * max(1.0, abs(strain_ref)):
        raise ValueError(f"{path}: last frame at strain {strain}, the reference's at {strain_ref}")
    mismatch = (offset - offset_ref) % edge  # offsets are defined modulo L
    if min(mismatch, edge - mismatch) > 1e-9 * edge:
        raise ValueError(f"{path}: Lees-Edwards offset {offset} differs from the reference {offset_ref}")
    d = minimum_image(x - x_ref, edge, offset)
    position = math.sqrt(np.mean(np.sum(d * d, axis=1)))
    # Rotation angle between unit quaternions u, v (sign chosen so that u . v >= 0): the arc between
    # them is alpha = 2 atan2(|u - v|, |u + v|) and the rotation 2 alpha. Unlike 2 acos(u . v), this
    # keeps its digits for small angles (acos loses everything below about 1e-8 rad).
    u = q / np.linalg.norm(q, axis=1)[:, None]
    v = q_ref / np.linalg.norm(q_ref, axis=1)[:, None]
    v = v * np.where(np.sum(u * v, axis=1) < 0.0, -1.0, 1.0)[:, None]
    angle = 4.0 * np.arctan2(np.linalg.norm(u - v, axis=1), np.linalg.norm(u + v, axis=1))
    return position, math.sqrt(np.mean(angle * angle))


def contact_g(h5):
    """(mean g over the contact shells, its SE)."""
    r = results.array(h5, "/results/pair_distribution/r")
    g = results.array(h5, "/results/pair_distribution/g_r")
    se = results.array(h5, "/results/pair_distribution/g_r_stderr")
    if r is None or g is None or se is None:
        raise ValueError(f"{h5.filename}: no /results/pair_distribution/g_r")
    shells = (r >= CONTACT_SHELL[0]) & (r < CONTACT_SHELL[1])
    n = int(np.count_nonzero(shells))
    return float(np.mean(g[shells])), float(math.sqrt(np.sum(se[shells] ** 2)) / n)


def brownian_observables(path):
    """{name: (value, SE)} for eta_r, delta_theta_m and g near contact."""
    with h5py.File(path, "r") as f:
        out = {}
        for name, where in (("eta_r", "/results/stress/eta_r"),
                            ("delta_theta_m", "/results/orientation/delta_theta_m")):
            value = results.scalar(f, where)
            if value is None:
                raise ValueError(f"{path}: no {where}")
            out[name] = value
        out["g_contact"] = contact_g(f)
    return out


def compare(observed, reference):
    """{name: (|value - ref|, combined SE, consistent?)}."""
    out = {}
    for name, (value, se) in observed.items():
        ref, se_ref = reference[name]
        combined = math.hypot(se, se_ref)
        error = abs(value - ref)
        out[name] = (error, combined, error <= CONSISTENT_SE * combined)
    return out


def step_statistics(path):
    """{name: value} of /results/steps (accepted and rejected steps, dt quantiles, smallest gap)."""
    with h5py.File(path, "r") as f:
        if "/results/steps" not in f:
            return {}
        return {name: float(d[()]) for name, d in f["/results/steps"].items()}
