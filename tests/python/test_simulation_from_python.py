"""The Python module drives the same Simulation as `fldsim run`: a short run from Python, its
state and results as numpy arrays, checked against exact oracles (the command line's run of the
same experiment, bit for bit; the trace identity S_xx + S_yy + S_zz = 0; unit quaternions)."""
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fixture import experiment, fldsim, require, scratch  # noqa: E402

np, h5py, fs = require("numpy", "h5py", "fldsim")
try:
    Simulation = fs.Simulation
except ImportError as e:
    print(f"SKIPPED: {e}")
    sys.exit(77)


class SimulationFromPython(unittest.TestCase):
    def test_steps_state_and_results(self):
        d = scratch()
        sim = fs.Simulation(experiment(d, os.path.join(d, "unused.h5")), overrides=["run.duration=0.02"])
        self.assertEqual(sim.total_steps, 20)
        self.assertEqual(sim.time_unit, "1/gammadot")  # Pe = 5 >= 1: the paper's strain unit
        sim.step(5)
        self.assertEqual(sim.step_index, 5)
        self.assertAlmostEqual(sim.time, 0.005, delta=1e-15)  # 5 steps of 0.001 (round-off only)
        x, q, n = sim.positions, sim.orientations, sim.directors
        self.assertEqual(x.shape, (27, 3))
        self.assertEqual(q.shape, (27, 4))
        self.assertTrue(np.all((x >= 0) & (x < sim.box_edge)))  # wrapped into the box
        np.testing.assert_allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-12)
        np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-12)
        with self.assertRaises(ValueError):  # not past run.duration
            sim.step(100)
        sim.run()
        self.assertTrue(sim.finished)
        sim.finish()
        r = sim.results()
        trace = sum(r[f"results/orientation/S_{a}{a}"][0] for a in "xyz")
        self.assertAlmostEqual(trace, 0.0, delta=1e-12)  # sum_i (3/2 n_i^2 - 1/2) = 0
        s = sim.series("timeseries/orientation/theta_m")
        np.testing.assert_array_equal(s["step"], [5, 10, 15, 20])
        np.testing.assert_allclose(s["time"], s["step"] * 0.001, rtol=1e-12)  # in 1/gammadot

    def test_same_bits_as_the_command_line(self):
        d = scratch()
        out = os.path.join(d, "cli.h5")
        e = experiment(d, out, duration=0.02)
        code, log = fldsim("run", "-q", e)
        self.assertEqual(code, 0, log)
        py_out = os.path.join(d, "py.h5")
        sim = fs.Simulation(e, output=py_out)
        sim.run()
        sim.finish()
        with h5py.File(out + ".checkpoint", "r") as a, h5py.File(py_out + ".checkpoint", "r") as b:
            np.testing.assert_array_equal(a["positions"][()], sim.positions)
            np.testing.assert_array_equal(a["orientations"][()], b["orientations"][()])
        with h5py.File(out, "r") as f:
            for path, (value, err, _) in sim.results().items():
                self.assertEqual(f[path][()], value, path)
                # NaN: an exact value without a standard error (the step counts); NaN == NaN here
                np.testing.assert_equal(f[path].attrs["stderr"], err, path)

    def test_checkpoint_round_trip(self):
        d = scratch()
        e = experiment(d, os.path.join(d, "unused.h5"), duration=0.02)
        whole = fs.Simulation(e)
        whole.step(8)
        whole.save_checkpoint(os.path.join(d, "at8.checkpoint"))
        whole.run()
        resumed = fs.Simulation(e)
        resumed.load_checkpoint(os.path.join(d, "at8.checkpoint"))
        self.assertEqual(resumed.step_index, 8)
        resumed.run()
        np.testing.assert_array_equal(whole.positions, resumed.positions)
        np.testing.assert_array_equal(whole.orientations, resumed.orientations)

    def test_bad_override_is_a_config_error(self):
        d = scratch()
        with self.assertRaises(fs.ConfigError) as c:
            fs.Simulation(experiment(d, os.path.join(d, "unused.h5")), overrides=["run.dt=-1"])
        self.assertIn("run.dt: expected a number > 0 or auto, got -1", str(c.exception))


if __name__ == "__main__":
    unittest.main()
