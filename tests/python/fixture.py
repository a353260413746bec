"""Shared by the Python tests: skip cleanly without a module, a scratch directory, a small
experiment file, and the fldsim command of the build tree."""
import os
import subprocess
import sys
import tempfile

SKIP = 77  # ctest SKIP_RETURN_CODE


def require(*modules):
    """Import the modules, or exit 77 with a message naming the missing one."""
    loaded = []
    for name in modules:
        try:
            loaded.append(__import__(name, fromlist=["_"]))
        except ImportError as e:
            print(f"SKIPPED: Python module {name} is not available ({e}); "
                  f"tools/install-deps.sh installs the Debian packages")
            sys.exit(SKIP)
    return loaded


def scratch():
    return tempfile.mkdtemp(prefix="fldsim-py-")


def experiment(directory, output, duration=0.05, observers=None, extra=""):
    """A 27-dicolloid experiment at Pe = 5 (time unit 1/gammadot: paper convention, Pe >= 1)."""
    obs = observers if observers is not None else [
        "{plugin: orientation, every: 5}", "{plugin: stress, every: 5}", "{plugin: trajectory, every: 10}"]
    text = ("system:\n"
            "  shape: {plugin: dicolloid, c: 0.2}\n"
            "  count: 27\n"
            "  volume_fraction: 0.3\n"
            "  init: {method: monte_carlo, seed: 3, sweeps: 50}\n"
            "flow: {peclet: 5}\n"
            "hydro: {plugin: fld}\n"
            "forces:\n  - {plugin: repulsion}\n"
            f"run: {{dt: 0.001, duration: {duration}, seed: 9, threads: 1}}\n"
            "observers:\n" + "".join(f"  - {o}\n" for o in obs) +
            f"output: {output}\n" + extra)
    path = os.path.join(directory, "e.yaml")
    with open(path, "w") as f:
        f.write(text)
    return path


def fldsim(*args):
    """Run the build tree's fldsim; returns (exit code, combined output)."""
    exe = os.path.join(os.environ["FLDSIM_BINARY_DIR"], "bin", "fldsim")
    p = subprocess.run([exe, *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return p.returncode, p.stdout
