"""Runs `fldsim run` for many settings, a few at a time, and times each run.

Each run's cost is measured two ways: wall-clock seconds, and CPU seconds (user + system of the
child, from wait4). On a machine shared with other jobs wall time also counts the time the run
waited for a core; CPU time does not, so it is the cost the harness ranks settings by (the
FLDSIM_ACCURACY_CLOCK environment variable switches to wall time).
"""
import os
import re
import subprocess
import time
from dataclasses import dataclass

# fldsim's closing log line, e.g.
# "done: 1000 steps in 13.4 s (13.419532 ms/step, 32.74 CG iterations/step, 132 neighbour rebuilds)"
DONE_LINE = re.compile(r"done: (\d+) steps in [0-9.]+ s \(([0-9.]+) ms/step, ([0-9.]+) CG iterations/step")


@dataclass
class Job:
    name: str
    args: list  # full fldsim command line
    output: str  # the result file it writes
    log: str  # where its stderr goes
    steps: int = 0  # expected time steps; the longest runs start first
    may_fail: bool = False  # a run that stops (e.g. the guard cannot go on) is recorded, not fatal


@dataclass
class Timing:
    wall: float  # s, whole process
    cpu: float  # s, user + system of the process
    steps: int
    ms_per_step: float  # fldsim's own wall ms/step of the time loop
    cg_per_step: float
    failure: str = ""  # the run's last log line if it stopped with an error (only for may_fail jobs)


def _parse_log(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        m = DONE_LINE.search(f.read())
    if not m:
        return 0, float("nan"), float("nan")
    return int(m.group(1)), float(m.group(2)), float(m.group(3))


def run_all(jobs, parallel=1, on_done=None):
    """Run the jobs, at most `parallel` at once; returns {name: Timing}. A failing run raises,
    unless it is `may_fail`: then its Timing carries the failure."""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    pending = sorted(jobs, key=lambda j: -j.steps)  # longest first: both slots stay busy to the end
    running = {}  # pid -> (job, start time, log file)
    timings = {}
    while pending or running:
        while pending and len(running) < parallel:
            job = pending.pop(0)
            log = open(job.log, "w", encoding="utf-8")
            proc = subprocess.Popen(job.args, stdout=log, stderr=subprocess.STDOUT, env=env)
            running[proc.pid] = (job, time.monotonic(), log, proc)
        pid, status, usage = os.wait4(-1, 0)
        if pid not in running:
            continue
        job, start, log, proc = running.pop(pid)
        wall = time.monotonic() - start
        proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
        log.close()
        if proc.returncode != 0:
            with open(job.log, encoding="utf-8", errors="replace") as f:
                tail = f.read()[-2000:]
            if job.may_fail:
                last = tail.strip().splitlines()[-1] if tail.strip() else f"exit code {proc.returncode}"
                timings[job.name] = Timing(wall, usage.ru_utime + usage.ru_stime, 0, float("nan"),
                                           float("nan"), last)
                if on_done:
                    on_done(job, timings[job.name])
                continue
            for _, _, other_log, other in running.values():  # stop the runs still going
                other.kill()
                other.wait()
                other_log.close()
            raise RuntimeError(f"{job.name}: fldsim exited with {proc.returncode}:\n{tail}")
        steps, ms, cg = _parse_log(job.log)
        timings[job.name] = Timing(wall, usage.ru_utime + usage.ru_stime, steps, ms, cg)
        if on_done:
            on_done(job, timings[job.name])
    return timings
