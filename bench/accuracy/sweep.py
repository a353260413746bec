"""The settings of the time-against-error sweep: one parameter at a time around the defaults,
a few combined, and the tight reference.

A setting is (family, dt, tolerance, cutoff). dt is in the scene's time unit (paper = 1/gammadot
at Pe = 10, and 1/gammadot in the non-Brownian runs), tolerance is the relative CG residual of
hydro.tolerance, cutoff the lubrication cutoff hydro.cutoff in units of a.
"""
from dataclasses import dataclass

# The defaults under test: dt of examples/quickstart.yaml, the fld plugin's tolerance and cutoff.
DEFAULT_DT = 1.0e-3
DEFAULT_TOLERANCE = 1.0e-6
DEFAULT_CUTOFF = 2.5
# fld's smooth taper switches the pair terms off over this width below the cutoff; it must end
# above contact (the plugin refuses taper_width >= cutoff - 2). Cutoffs closer to contact than
# the default width (the cutoff family's 2.1-2.3 a) taper over half the gap range instead.
DEFAULT_TAPER_WIDTH = 0.3


def taper_width(cutoff):
    return DEFAULT_TAPER_WIDTH if cutoff - 2.0 > DEFAULT_TAPER_WIDTH else round(0.5 * (cutoff - 2.0), 6)


@dataclass(frozen=True)
class Setting:
    family: str  # reference, default, dt, tolerance, cutoff, combined, adaptive
    dt: float  # the step, or with step_tolerance > 0 the longest step dt_max (run.dt: auto)
    tolerance: float
    cutoff: float
    step_tolerance: float = 0.0  # > 0: adaptive steps, run.tolerance (a)

    @property
    def dt_text(self):
        return f"auto<={self.dt:g} eps={self.step_tolerance:g}" if self.step_tolerance else f"{self.dt:g}"

    @property
    def label(self):
        return f"dt={self.dt_text} tol={self.tolerance:g} cut={self.cutoff:g}"

    @property
    def key(self):
        """A file-name-safe identifier."""
        auto = f"auto{self.step_tolerance:g}_" if self.step_tolerance else ""
        return f"{auto}dt{self.dt:g}_tol{self.tolerance:g}_cut{self.cutoff:g}".replace("+", "")

    def overrides(self):
        step = ([f"run.dt=auto", f"run.dt_max={self.dt!r}", f"run.tolerance={self.step_tolerance!r}"]
                if self.step_tolerance else [f"run.dt={self.dt!r}"])
        hydro = [f"hydro.tolerance={self.tolerance!r}", f"hydro.cutoff={self.cutoff!r}"]
        width = taper_width(self.cutoff)
        if width != DEFAULT_TAPER_WIDTH:  # the plugin's default (sdk ResistanceModel.cpp)
            hydro.append(f"hydro.taper_width={width!r}")
        return step + hydro

    @property
    def is_default(self):
        return (self.dt, self.tolerance, self.cutoff, self.step_tolerance) == (
            DEFAULT_DT, DEFAULT_TOLERANCE, DEFAULT_CUTOFF, 0.0)


@dataclass(frozen=True)
class Plan:
    """Everything one invocation runs: the settings of each kind of run and their lengths.

    `reference` is the tight reference of every comparison (smallest dt, tolerance 1e-10,
    cutoff 2.9). The cutoff is a model parameter of FLD (R_0(phi) was fitted with the LAMMPS
    cutoffs), not a convergence parameter, so the deterministic runs also have a
    `numerical_reference` at the default cutoff: the error of the settings at that cutoff against
    it is the numerical error of dt and tolerance alone.
    """
    reference: Setting
    numerical_reference: Setting
    deterministic: list  # settings compared with both references
    brownian_reference: Setting
    brownian_numerical_reference: Setting  # the Brownian reference's dt and tolerance, default cutoff
    brownian: list
    strain: float  # deterministic runs: compare positions after this strain
    brownian_duration: float  # Brownian runs: length, in strain units (Pe = 10, paper units)
    brownian_start: float  # Brownian runs: observers average from this time on


def _around_defaults(dts, tolerances, cutoffs, combined, adaptive=()):
    """adaptive: (dt_max, step tolerance) pairs, run at the default CG tolerance and cutoff."""
    out = [Setting("default", DEFAULT_DT, DEFAULT_TOLERANCE, DEFAULT_CUTOFF)]
    out += [Setting("adaptive", dt_max, DEFAULT_TOLERANCE, DEFAULT_CUTOFF, eps) for dt_max, eps in adaptive]
    out += [Setting("dt", dt, DEFAULT_TOLERANCE, DEFAULT_CUTOFF) for dt in dts]
    out += [Setting("tolerance", DEFAULT_DT, tol, DEFAULT_CUTOFF) for tol in tolerances]
    out += [Setting("cutoff", DEFAULT_DT, DEFAULT_TOLERANCE, cut) for cut in cutoffs]
    out += [Setting("combined", *c) for c in combined]
    return out


TIGHT_TOLERANCE = 1e-10
TIGHT_CUTOFF = 2.9


def _plan(dt_ref, deterministic, brownian_dt_ref, brownian, **lengths):
    return Plan(reference=Setting("reference", dt_ref, TIGHT_TOLERANCE, TIGHT_CUTOFF),
                numerical_reference=Setting("numerical reference", dt_ref, TIGHT_TOLERANCE, DEFAULT_CUTOFF),
                deterministic=deterministic,
                brownian_reference=Setting("reference", brownian_dt_ref, TIGHT_TOLERANCE, TIGHT_CUTOFF),
                brownian_numerical_reference=Setting("numerical reference", brownian_dt_ref, TIGHT_TOLERANCE,
                                                     DEFAULT_CUTOFF),
                brownian=brownian, **lengths)


def full_plan():
    deterministic = _around_defaults(
        dts=[8e-3, 4e-3, 2e-3, 5e-4],
        tolerances=[1e-2, 1e-3, 1e-4, 1e-5, 1e-8],
        cutoffs=[2.1, 2.2, 2.3, 2.7, 2.9],
        combined=[(4e-3, 1e-3, 2.5), (2e-3, 1e-4, 2.5), (2e-3, 1e-3, 2.7), (4e-3, 1e-4, 2.3),
                  (1e-3, 1e-4, 2.7), (5e-4, 1e-8, 2.7)],
        adaptive=[(8e-3, 1e-5), (8e-3, 1e-6), (8e-3, 1e-7), (8e-3, 1e-8)])
    # Brownian errors are limited by sampling, not by the setting: the reference takes the smallest
    # dt of the Brownian settings (a smaller one would cost minutes and not be seen within the SE).
    brownian = _around_defaults(dts=[4e-3, 2e-3], tolerances=[1e-3], cutoffs=[2.2, 2.9],
                                combined=[(2e-3, 1e-4, 2.5)], adaptive=[(8e-3, 3e-3), (8e-3, 1e-3)])
    return _plan(2.5e-4, deterministic, 1e-3, brownian, strain=1.0, brownian_duration=8.0,
                 brownian_start=1.0)


def quick_plan():
    deterministic = _around_defaults(dts=[4e-3, 2e-3], tolerances=[1e-3, 1e-4], cutoffs=[2.2, 2.7],
                                     combined=[(2e-3, 1e-4, 2.5)], adaptive=[(8e-3, 1e-6), (8e-3, 1e-7)])
    brownian = _around_defaults(dts=[4e-3], tolerances=[], cutoffs=[], combined=[], adaptive=[(8e-3, 3e-3)])
    return _plan(2.5e-4, deterministic, 1e-3, brownian, strain=0.5, brownian_duration=4.0,
                 brownian_start=1.0)
