"""A result file as the field's tools read it (Debian 12's python3-mdanalysis 2.4 and
python3-gsd 2.7): MDAnalysis opens it with positions, box and time; `fldsim export --gsd` gives
GSD frames with orientations and the Lees-Edwards shear as box tilt. Also the units (H5MD units
module, times in the run's unit) and the exact parameters. Oracles: the values written in the
HDF5 file itself (read with h5py), the Lees-Edwards relations offset = strain L and tilt =
(strain - round(strain)) L, and the strain gammadot t = t in units of 1/gammadot."""
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fixture import experiment, fldsim, require, scratch  # noqa: E402

np, h5py = require("numpy", "h5py")

def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


STEPS, DT, EVERY = 1200, 0.001, 100  # strain 1.2: the image shift passes L/2 and L


class ResultFileReaders(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        d = scratch()
        cls.path = os.path.join(d, "run.h5")
        cls.yaml = experiment(d, cls.path, duration=STEPS * DT,
                              observers=["{plugin: orientation, every: 50}", f"{{plugin: trajectory, every: {EVERY}}}"])
        code, log = fldsim("run", "-q", cls.yaml, "--set", "flow.peclet=5")
        assert code == 0, log
        cls.h5 = h5py.File(cls.path, "r")
        g = cls.h5["particles/bodies"]
        cls.positions = g["position/value"][()]
        cls.cell = g["box/edges/value"][()]
        cls.strain = g["lees_edwards/strain/value"][()]
        cls.edge = cls.cell[0, 0, 0]
        cls.frames = STEPS // EVERY + 1

    def test_units_module_and_times_in_the_runs_unit(self):
        units = self.h5["h5md/modules/units"]
        self.assertEqual(list(units.attrs["version"]), [1, 0])
        self.assertIn("a = node radius", text(units.attrs["system"]))
        theta = self.h5["timeseries/orientation/theta_m"]
        self.assertEqual(text(theta["time"].attrs["unit"]), "gammadot-1")  # H5MD grammar for 1/gammadot
        np.testing.assert_allclose(theta["time"][()], theta["step"][()] * DT, rtol=1e-12)
        pos = self.h5["particles/bodies/position"]
        self.assertEqual(text(pos.attrs["unit"]), "a")  # on the group: MDAnalysis 2.4 (see Hdf5ResultSink)
        self.assertEqual(text(pos.attrs["time_unit"]), "gammadot-1")
        # strain = gammadot t, and t is in 1/gammadot: the stored time is the strain.
        np.testing.assert_allclose(pos["time"][()], self.strain, rtol=1e-12)

    def test_parameters_are_stored_exactly(self):
        p = self.h5["parameters"]
        self.assertEqual(p.attrs["peclet"], 5.0)
        self.assertEqual(p.attrs["peclet"].dtype, np.float64)  # a number, not text
        self.assertEqual(p.attrs["dt"], DT)
        with open(self.yaml) as f:
            written = f.read()
        self.assertEqual(p["experiment_source"][()].decode(), written)
        self.assertEqual([text(o) for o in p["experiment_source"].attrs["overrides"]], ["flow.peclet=5"])

    def test_lees_edwards_offset_is_continuous_and_the_box_tilts(self):
        offset = self.h5["particles/bodies/lees_edwards/offset/value"][()]
        np.testing.assert_array_equal(offset, self.strain * self.edge)
        self.assertGreater(offset[-1], self.edge)  # past one box length: not wrapped
        self.assertTrue(np.all(np.diff(offset) > 0))
        tilt = self.cell[:, 1, 0]
        np.testing.assert_allclose(tilt, self.edge * (self.strain - np.floor(self.strain + 0.5)), atol=1e-12)
        self.assertTrue(np.all(np.abs(tilt) <= 0.5 * self.edge))
        np.testing.assert_array_equal(self.cell[:, 0], np.tile([self.edge, 0, 0], (self.frames, 1)))

    def test_mdanalysis_reads_positions_box_and_time(self):
        (mda,) = require("MDAnalysis")
        import fldsim
        n = self.positions.shape[1]
        # The documented command (docs/output.md); fldsim.mdanalysis_universe does the same.
        u = mda.Universe(self.path, format="H5MD", topology_format="MINIMAL", n_atoms=n, convert_units=False)
        self.assertEqual(fldsim.mdanalysis_universe(self.path).trajectory.n_frames, self.frames)
        self.assertEqual(u.atoms.n_atoms, 27)
        self.assertEqual(u.trajectory.n_frames, self.frames)
        times = self.h5["particles/bodies/position/time"][()]
        for k, ts in enumerate(u.trajectory):
            np.testing.assert_allclose(ts.positions, self.positions[k], rtol=1e-6, atol=1e-5)  # float32
            np.testing.assert_allclose(ts.triclinic_dimensions, self.cell[k], atol=1e-4)
            self.assertAlmostEqual(ts.time, times[k], delta=1e-12)

    def test_gsd_export_for_ovito(self):
        (gsd_hoomd,) = require("gsd.hoomd")
        out = os.path.join(os.path.dirname(self.path), "run.gsd")
        code, log = fldsim("export", self.path, "--gsd", out)
        self.assertEqual(code, 0, log)
        code, log = fldsim("export", self.path, "--gsd", out)  # never overwritten silently
        self.assertEqual(code, 2, log)
        self.assertIn("refusing to overwrite", log)
        ori = self.h5["particles/bodies/orientation/value"][()]
        with gsd_hoomd.open(name=out, mode="rb") as t:
            self.assertEqual(len(t), self.frames)
            for k, s in enumerate(t):
                L, xy = s.configuration.box[0], s.configuration.box[3]
                self.assertAlmostEqual(L, self.edge, delta=1e-5)
                self.assertAlmostEqual(xy, self.cell[k, 1, 0] / self.edge, delta=1e-6)
                r = s.particles.position.astype(float)
                fx = (r[:, 0] - xy * r[:, 1]) / L
                self.assertTrue(np.all((fx >= -0.5 - 1e-6) & (fx < 0.5 + 1e-6)))  # inside the tilted cell
                # The same point as the HDF5 centre up to a whole cell vector (L, 0, 0).
                shift = r + 0.5 * L - self.positions[k]
                np.testing.assert_allclose(shift[:, 1:], 0.0, atol=1e-4)
                np.testing.assert_allclose(shift[:, 0] / L, np.round(shift[:, 0] / L), atol=1e-5)
                np.testing.assert_allclose(s.particles.orientation, ori[k], atol=1e-6)
                self.assertEqual(s.particles.type_shapes[0]["type"], "SphereUnion")
                self.assertAlmostEqual(float(s.log["fldsim/strain"][0]), self.strain[k], delta=1e-12)
            centres = np.array(t[0].particles.type_shapes[0]["centers"])
            self.assertAlmostEqual(np.linalg.norm(centres[1] - centres[0]), 0.2, delta=1e-12)  # c = 0.2 a
            np.testing.assert_allclose(t[0].particles.type_shapes[0]["diameters"], [2.0, 2.0])


if __name__ == "__main__":
    unittest.main()
