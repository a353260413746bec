"""fldsim from Python: the same Simulation as `fldsim run`, and readers for its result files.

    import fldsim
    sim = fldsim.Simulation("examples/quickstart.yaml", overrides=["run.duration=2"])
    sim.run(); sim.finish()
    sim.positions, sim.orientations, sim.results()

Simulation comes from the compiled extension (_fldsim, pybind11); the helpers below need only
h5py and the reader they serve (MDAnalysis, gsd).
"""
try:
    from ._fldsim import ConfigError, Error, Simulation, __version__  # noqa: F401
except ImportError as _e:  # the extension is not built (no pybind11): the readers still work
    _import_error = _e

    def __getattr__(name):
        if name in ("Simulation", "ConfigError", "Error", "__version__"):
            raise ImportError(f"fldsim.{name}: the compiled module is not available ({_import_error})")
        raise AttributeError(name)


def mdanalysis_universe(path):
    """An MDAnalysis Universe over a result file's trajectory (/particles/bodies): positions in a,
    box with the Lees-Edwards tilt, time in the run's unit.

    MDAnalysis 2.4 knows only its own unit names, so the file is opened with convert_units=False,
    and the body count is passed because its minimal topology looks for /particles/trajectory.
    """
    import h5py
    import MDAnalysis as mda

    with h5py.File(path, "r") as f:
        n = f["particles/bodies/position/value"].shape[1]
    return mda.Universe(path, format="H5MD", topology_format="MINIMAL", n_atoms=n, convert_units=False)
