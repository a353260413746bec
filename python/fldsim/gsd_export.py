"""Convert the trajectory of an fldsim result file (H5MD, /particles/bodies) to GSD frames that
HOOMD-blue tools and OVITO open: one particle per body with its orientation quaternion, the body
shape as a GSD `SphereUnion` (particles/type_shapes), the Lees-Edwards shear as the box tilt xy,
and per-frame log entries fldsim/time, fldsim/strain and fldsim/lees_edwards_offset.

    /usr/bin/python3 -m fldsim.gsd_export RUN.h5 --gsd RUN.gsd [--nodes]
    fldsim export RUN.h5 --gsd RUN.gsd [--nodes]        (the same, from the command line tool)

--nodes writes one sphere per node instead (body index in particles/body), for renderers without
SphereUnion. Needs Debian's python3-h5py, python3-numpy and python3-gsd (2.7).

GSD boxes are centred at the origin, with cell vectors a1 = (Lx, 0, 0), a2 = (xy Ly, Ly, 0),
a3 = (0, 0, Lz) here; fldsim's cell (trajectory_layout.hpp) is a = (L, 0, 0), b = (s, L, 0),
c = (0, 0, L) with the image shift s in [-L/2, L/2), so xy = s / L, and each centre is moved by
a whole cell vector a (if needed) so that it lies inside the tilted cell.
"""
import argparse
import os
import sys

import numpy as np

BODIES = "/particles/bodies"


def _text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def _rotate(q, v):
    """Rotate vectors v (..., 3) by unit quaternions q (..., 4), scalar first."""
    w, u = q[..., :1], q[..., 1:]
    t = 2.0 * np.cross(u, v)
    return v + w * t + np.cross(u, t)


def read_frames(h5):
    """Yield dicts (step, time, cell 3x3, positions, orientations, strain, offset) per frame."""
    g = h5[BODIES]
    pos, ori, edges = g["position/value"], g["orientation/value"], g["box/edges/value"]
    steps, times = g["position/step"][()], g["position/time"][()]
    strain = g["lees_edwards/strain/value"][()] if "lees_edwards/strain" in g else np.zeros(len(steps))
    for k in range(len(steps)):
        e = np.asarray(edges[k], dtype=float)
        if e.shape == (3,):  # files before the 3x3 cell: edge lengths, shift from the strain
            L = e[0]
            s = L * (strain[k] - np.floor(strain[k] + 0.5))
            e = np.array([[L, 0, 0], [s, L, 0], [0, 0, L]])
        yield dict(step=int(steps[k]), time=float(times[k]), cell=e, positions=np.asarray(pos[k], dtype=float),
                   orientations=np.asarray(ori[k], dtype=float), strain=float(strain[k]))


def body_shape(h5):
    """(node centres (m, 3), node radii (m,)) in the body frame; one unit sphere if unknown."""
    g = h5[BODIES]
    if "shape/node_positions" in g:
        return np.asarray(g["shape/node_positions"][()]), np.asarray(g["shape/node_radii"][()])
    return np.zeros((1, 3)), np.ones(1)


def into_gsd_box(cell, positions):
    """GSD box [Lx, Ly, Lz, xy, xz, yz] and positions inside the origin-centred tilted cell."""
    L, s = cell[0, 0], cell[1, 0]
    xy = s / L
    r = positions - 0.5 * np.array([L, L, L])
    # fractional coordinate along a: (x - xy y) / L, wrapped into [-1/2, 1/2)
    fx = (r[:, 0] - xy * r[:, 1]) / L
    r[:, 0] -= np.floor(fx + 0.5) * L
    return [L, L, L, xy, 0.0, 0.0], r


def export(h5_path, gsd_path, nodes=False):
    import gsd
    import gsd.hoomd
    import h5py

    frame_type = getattr(gsd.hoomd, "Frame", None) or gsd.hoomd.Snapshot
    mode = "w" if int(gsd.__version__.split(".")[0]) >= 3 else "wb"
    with h5py.File(h5_path, "r") as h5:
        if BODIES + "/position" not in h5:
            raise SystemExit(f"{h5_path}: no trajectory ({BODIES}/position); add the `trajectory` observer")
        centres, radii = body_shape(h5)
        time_unit = _text(h5[BODIES + "/position"].attrs.get("time_unit", "a^2/D0"))
        count = 0
        part = gsd_path + ".part"
        with gsd.hoomd.open(name=part, mode=mode) as out:
            for f in read_frames(h5):
                box, r = into_gsd_box(f["cell"], f["positions"].copy())
                s = frame_type()
                s.configuration.step = f["step"]
                s.configuration.dimensions = 3
                s.configuration.box = box
                n = len(r)
                if nodes:
                    m = len(radii)
                    world = r[:, None, :] + _rotate(f["orientations"][:, None, :], centres[None, :, :])
                    s.particles.N = n * m
                    s.particles.types = ["node"]
                    s.particles.typeid = np.zeros(n * m, dtype=np.uint32)
                    s.particles.position = world.reshape(-1, 3).astype(np.float32)
                    s.particles.orientation = np.repeat(f["orientations"], m, axis=0).astype(np.float32)
                    s.particles.diameter = np.tile(2.0 * radii, n).astype(np.float32)
                    s.particles.body = np.repeat(np.arange(n, dtype=np.int32), m)
                else:
                    s.particles.N = n
                    s.particles.types = ["body"]
                    s.particles.typeid = np.zeros(n, dtype=np.uint32)
                    s.particles.position = r.astype(np.float32)
                    s.particles.orientation = f["orientations"].astype(np.float32)
                    reach = np.max(np.linalg.norm(centres, axis=1) + radii)
                    s.particles.diameter = np.full(n, 2.0 * reach, dtype=np.float32)
                    s.particles.type_shapes = [{"type": "SphereUnion", "centers": centres.tolist(),
                                                "diameters": (2.0 * radii).tolist()}]
                s.log["fldsim/time"] = np.array([f["time"]])
                s.log["fldsim/strain"] = np.array([f["strain"]])
                s.log["fldsim/lees_edwards_offset"] = np.array([f["strain"] * f["cell"][0, 0]])
                out.append(s)
                count += 1
        os.replace(part, gsd_path)
    return count, time_unit


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result", help="fldsim result file RUN.h5 with a trajectory")
    ap.add_argument("--gsd", required=True, help="GSD file to write")
    ap.add_argument("--nodes", action="store_true", help="one sphere per node instead of one body per particle")
    ap.add_argument("--overwrite", action="store_true", help="replace an existing GSD file")
    args = ap.parse_args(argv)
    if os.path.exists(args.gsd) and not args.overwrite:
        print(f"fldsim export: {args.gsd} exists; refusing to overwrite it (use --overwrite)", file=sys.stderr)
        return 2
    if not os.path.exists(args.result):
        print(f"fldsim export: {args.result}: result file not found", file=sys.stderr)
        return 2
    try:
        import gsd.hoomd  # noqa: F401
    except ImportError:
        print("fldsim export: the Python module gsd is missing (Debian: apt-get install python3-gsd)",
              file=sys.stderr)
        return 1
    count, time_unit = export(args.result, args.gsd, nodes=args.nodes)
    print(f"{args.gsd}: {count} frames ({'nodes' if args.nodes else 'bodies'}; log fldsim/time in {time_unit})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
