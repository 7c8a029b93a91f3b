# SPDX-License-Identifier: Apache-2.0
"""How long a ``smoothshaper`` request will take, computed from its sizes before it starts.

Every CLI path whose work grows with numbers the user gives (chain length, sweep points,
samples of a trajectory, size of a record) builds a :class:`Cost` from those sizes in O(1)
and calls :func:`announce`: a request modelled above :data:`ANNOUNCE_SECONDS` prints its
estimate on stderr before it starts, and one above :data:`LIMIT_SECONDS` is refused naming the
parameter that makes it long. The same model weights the phases of the one progress bar
(:class:`smoothshaper.cli.common.Progress`) that covers the whole request.

The unit costs below were measured on the reference machine (2 cores shared with other
jobs, OpenBLAS); ``python -m smoothshaper.cli.cost`` measures them again on yours and prints
the figures next to the model's.
"""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field

from .common import CliError

__all__ = ["ANNOUNCE_SECONDS", "LIMIT_SECONDS", "UNIT_COSTS", "PLOT_POINTS", "Cost",
           "add_options", "start", "show_progress", "announce", "chain_taps",
           "analyze_cost", "trajectory_cost", "record_cost", "DECAY_FIT_BYTES", "REPORT_SECONDS",
           "report_cost",
           "VALIDATE_SECONDS", "validate_cost", "measure"]

#: A request modelled to take longer than this [s] prints its estimate before it starts.
ANNOUNCE_SECONDS = 10.0
#: A request modelled to take longer than this [s] is refused, naming the parameter to change.
LIMIT_SECONDS = 600.0

#: Seconds per unit of work, measured by :func:`measure` (see the module docstring).
UNIT_COSTS = {
    # analysis.ChainResponse at one point: per FIR tap (blocked BLAS sum), per square root of
    # the taps (the exponentials of the powers of z^-1) and per point
    "tap_point": 1.5e-10,
    "sqrt_tap_point": 3.0e-7,
    "point": 5.0e-5,
    # the reference taps of a chain (computed once per analyze run), per tap
    "tap": 8.0e-8,
    # the C chain filtering a step (analyze's step response), per sample
    "chain_sample": 6.0e-8,
    # the C B-spline stepped from Python, per sample and axis
    "bspline_sample_axis": 4.0e-7,
    # the C online generator in blocks, per sample and axis
    "generator_sample_axis": 1.5e-7,
    # one CSV row written with 17 significant digits, per value
    "csv_value": 1.2e-6,
    # identify and calibrate: reading a CSV record (numpy.loadtxt), the checks and (calibrate)
    # the Welch spectra, per byte
    "identify_byte": 4.6e-8,
    "calibrate_byte": 2.7e-8,
    # the whole-record fit of a free decay, per byte of the file up to DECAY_FIT_BYTES (longer
    # decays are fitted at a lower rate on at most 2 x 65536 samples: a bounded cost)
    "decay_fit_byte": 2.65e-6,
    # calibrate: tuning every filter family to the modes of one axis (a resonance test's
    # spectral fit and the start-up included)
    "calibrate_axis": 2.5,
    # plotting one point of a line (matplotlib Agg, after decimation to at most 20k points)
    "plot_point": 2.0e-6,
}

#: Most points a line plot draws; longer signals are decimated (min/max per bin).
PLOT_POINTS = 20_000


@dataclass
class Cost:
    """Modelled seconds of each phase of one request, in the order they run.

    Parameters
    ----------
    what : str
        The request as the user knows it (e.g. ``"analyze"``), used in messages.
    phases : dict of str to float
        Phase name -> modelled seconds (>= 0), in the order the phases run.
    drivers : dict of str to str
        Option -> why it drives the cost (e.g. ``{"--points": "600 sweep points"}``);
        the refusal names the option of the longest phase (``blame``), else the first.
    blame : dict of str to str
        Phase name -> the option of ``drivers`` that sets its size (``{"PRV surface":
        "--surface-points"}``); phases not listed are charged to the first driver.
    """
    what: str
    phases: dict = field(default_factory=dict)
    drivers: dict = field(default_factory=dict)
    blame: dict = field(default_factory=dict)

    @property
    def seconds(self) -> float:
        """Modelled total [s]."""
        return float(sum(self.phases.values()))

    def describe(self) -> str:
        """``"about 42 s (sweep 30 s, plots 12 s)"``: the total and its largest phases."""
        parts = [f"{name} {_fmt_seconds(sec)}" for name, sec in
                 sorted(self.phases.items(), key=lambda kv: -kv[1])[:4] if sec >= 0.5]
        return f"about {_fmt_seconds(self.seconds)}" + (f" ({', '.join(parts)})" if parts else "")


def _fmt_seconds(seconds: float) -> str:
    if seconds < 1:
        return "< 1 s"
    if seconds < 120:
        return f"{seconds:.0f} s"
    return f"{seconds / 60:.1f} min"


def add_options(parser) -> None:
    """Add ``--progress/--no-progress`` and ``--estimate`` to a subcommand's parser."""
    import argparse
    parser.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                        help="show a progress bar over the whole run (default: when stderr "
                        "is a terminal)")
    parser.add_argument("--estimate", action="store_true",
                        help=f"print how long the run would take (from the sizes alone) and "
                        f"exit; runs modelled above {ANNOUNCE_SECONDS:g} s print this estimate "
                        f"before they start, above {LIMIT_SECONDS:g} s they are refused")


def start(cost: Cost, args, sizes: str):
    """The common start of a long request: with ``--estimate`` print ``sizes`` and the
    estimate on stdout and return None (the caller stops); otherwise :func:`announce` it and
    return the progress bar over its phases (drawn per :func:`show_progress`).

    Parameters
    ----------
    cost : Cost
        The modelled request.
    args : argparse.Namespace
        The parsed options (``estimate``, ``progress``).
    sizes : str
        The sizes the estimate comes from, e.g. ``"5000 samples on 2 axes"``.

    Returns
    -------
    Progress or None
        The bar, or None when only the estimate was asked for.

    Raises
    ------
    CliError
        The request is beyond :data:`LIMIT_SECONDS` (see :func:`announce`).
    """
    from .common import Progress
    if getattr(args, "estimate", False):
        print(f"{cost.what}: {sizes}: {cost.describe()}")
        return None
    announce(cost)
    return Progress.phased(cost, show_progress(args))


def show_progress(args) -> bool:
    """The ``--progress`` choice, or whether stderr is a terminal when it was not given."""
    flag = getattr(args, "progress", None)
    return sys.stderr.isatty() if flag is None else bool(flag)


def announce(cost: Cost, *, stream=None, limit: float = LIMIT_SECONDS) -> None:
    """Print the estimate of a long request on ``stream`` (stderr) before it starts.

    Parameters
    ----------
    cost : Cost
        The modelled request.
    stream : file-like or None
        Where the estimate goes (default ``sys.stderr``).
    limit : float
        Refusal threshold [s] (default :data:`LIMIT_SECONDS`).

    Raises
    ------
    CliError
        The modelled time exceeds ``limit``; the message names the option that drives the
        cost, the estimate and the limit.
    """
    stream = sys.stderr if stream is None else stream
    if cost.seconds > limit:
        option, why = next(iter(cost.drivers.items()), ("input", "the input's size"))
        longest = max(cost.phases, key=cost.phases.get) if cost.phases else None
        if cost.blame.get(longest) in cost.drivers:
            option = cost.blame[longest]
            why = cost.drivers[option]
        advice = ("use a shorter record (fewer samples)" if option == "FILE"
                  else f"{_verb(option)} {option}" + _other_drivers(cost, option))
        raise CliError(f"{option}: {cost.what} would take {cost.describe()}, more than the "
                       f"limit of {limit:.0f} s ({why}); {advice}")
    if cost.seconds > ANNOUNCE_SECONDS:
        stream.write(f"{cost.what}: this will take {cost.describe()}\n")
        stream.flush()


def _verb(option: str) -> str:
    """A longer sample period shortens the work; every other driver is a count to lower."""
    return "raise" if option == "--Ts" else "reduce"


def _other_drivers(cost: Cost, named: str) -> str:
    others = [o for o in cost.drivers if o != named]
    return (" (or " + ", ".join(f"{_verb(o)} {o}" for o in others) + ")") if others else ""


def chain_taps(stages, Ts: float) -> int:
    """Delay-line length of the chain [samples] from the C size query, in O(1) per stage
    (nothing is allocated).

    Parameters
    ----------
    stages : sequence of Stage
        The chain.
    Ts : float
        Sample period [s].

    Returns
    -------
    int
        Sum of the stages' buffer sizes: each FIR stage's taps (its length, or one more), a
        notch its few state values.

    Raises
    ------
    ParameterError
        A stage is invalid at ``Ts`` (the same error :class:`smoothshaper.Chain` raises).
    """
    from ..filters import Chain, _backend, _fill_config
    ffi, lib = _backend("double")
    config = ffi.new("sms_stage_config *")
    need = ffi.new("size_t *")
    total = 0
    for stage in stages:
        _fill_config(config, stage)
        if lib.sms_stage_buffer_size(config, Ts, need) != 0:
            Chain([stage], Ts=Ts)           # raises the chain's own, named error
        total += int(need[0])
    return total


def analyze_cost(*, taps: int, sweep: int, band: int, surface: int, spectrum: int,
                 step: int, plotted: int) -> Cost:
    """Model of ``smoothshaper analyze``.

    Parameters
    ----------
    taps : int
        FIR taps of the chain (:func:`chain_taps`).
    sweep, band, surface, spectrum : int
        Points evaluated for the PRV curve, the insensitivity band (grid plus about 100
        bisection steps), the PRV surface (0 without ``--surface``) and the magnitude plot.
    step : int
        Samples of the step response.
    plotted : int
        Points drawn in all plots together.

    Returns
    -------
    Cost
        Phases ``taps``, ``PRV sweep``, ``band``, ``PRV surface``, ``spectrum``, ``step
        response``, ``plots``.
    """
    c = UNIT_COSTS
    per_point = _seconds_per_point(taps)
    return Cost("analyze", {
        "taps": c["tap"] * taps,
        "PRV sweep": per_point * sweep,
        "band": per_point * band,
        "PRV surface": per_point * surface,
        "spectrum": per_point * spectrum,
        "step response": c["chain_sample"] * step,
        "plots": c["plot_point"] * plotted + 1.0,
    }, {"--Ts": f"a chain of {taps} samples at this Ts",
        "--points": f"{sweep} sweep points",
        "--surface-points": f"{surface} surface points"},
        {"PRV sweep": "--points", "PRV surface": "--surface-points"})


def _seconds_per_point(taps: int) -> float:
    c = UNIT_COSTS
    return c["tap_point"] * taps + c["sqrt_tap_point"] * math.sqrt(taps) + c["point"]


def trajectory_cost(form: str, *, samples: int, axes: int, csv: bool, plot: bool) -> Cost:
    """Model of ``smoothshaper design generator`` and ``design bspline``.

    Parameters
    ----------
    form : {"generator", "bspline"}
        The design form.
    samples : int
        Output samples per axis (bspline: end sample of the last via-point + 1; generator:
        the upper bound the command refuses beyond).
    axes : int
        Number of axes.
    csv, plot : bool
        Whether ``--csv`` / ``--plot`` were given.

    Returns
    -------
    Cost
        Phases ``generator`` or ``filter``, then ``csv`` and ``plot``.

    Raises
    ------
    KeyError
        ``form`` is neither ``"generator"`` nor ``"bspline"``.
    """
    c = UNIT_COSTS
    phase, unit, columns, lines, drivers = {
        "generator": ("generator", "generator_sample_axis", 2 + 4 * axes, 5 * axes,
                      {"--Ts": f"about {samples} samples (the moves' duration / Ts)",
                       "--via": "the length of the moves"}),
        "bspline": ("filter", "bspline_sample_axis", 1 + axes, 3 * axes,
                    {"--T": f"{samples} samples per axis (T/Ts times the number of via-points)",
                     "--Ts": "the samples per knot spacing"})}[form]
    return Cost(f"design {form}", {
        phase: c[unit] * samples * axes,
        "csv": c["csv_value"] * samples * columns if csv else 0.0,
        "plot": c["plot_point"] * min(samples, PLOT_POINTS) * lines + 1.0 if plot else 0.0,
    }, drivers)


#: Bytes of a CSV record beyond which a free decay's fit costs no more (2 x 65536 lines of
#: about 20 characters: calibrate.decay_decimation fits longer ones at a lower rate).
DECAY_FIT_BYTES = 2.6e6


def record_cost(what: str, *, nbytes: int, axes: int = 1, decay: bool | None = None) -> Cost:
    """Model of reading and fitting CSV records (``identify``, ``calibrate``).

    Parameters
    ----------
    what : {"identify", "calibrate"}
        The subcommand: identify fits the whole decay by least squares (cost per sample),
        calibrate estimates spectra (cheaper per sample) and then tunes every filter family per
        axis.
    nbytes : int
        Total size of the files [bytes] (``os.path.getsize``).
    axes : int
        Signal columns that will be tuned (calibrate).
    decay : bool or None
        Whether the record is a free decay (fitted in the time domain); default: yes for
        identify, no for calibrate.

    Returns
    -------
    Cost
        Phases ``read and fit`` and (calibrate) ``tune``.

    Raises
    ------
    KeyError
        ``what`` is neither ``"identify"`` nor ``"calibrate"``.
    """
    c = UNIT_COSTS
    decay = (what == "identify") if decay is None else decay
    phases = {"read and fit": c[f"{what}_byte"] * nbytes + 1.0
              + (c["decay_fit_byte"] * min(nbytes, DECAY_FIT_BYTES) if decay else 0.0)}
    if what == "calibrate":
        phases["tune"] = c["calibrate_axis"] * max(1, axes)
    return Cost(what, phases, {"FILE": f"{nbytes / 1e6:.3g} MB of records"})


#: Seconds each report section took on the reference machine (the report prints its own).
REPORT_SECONDS = {"seed000": 12.0, "seed001": 10.0, "seed002": 4.0, "seed003": 16.0,
                  "seed004": 3.0, "shapers": 1.0, "scheduled": 1.5}


def report_cost(sections) -> Cost:
    """Model of ``smoothshaper report``: the measured time of each section to build.

    Parameters
    ----------
    sections : sequence of str
        Section keys (:data:`smoothshaper.report.SECTIONS`).

    Returns
    -------
    Cost
        One phase per section.

    Raises
    ------
    KeyError
        A key is not a report section.
    """
    return Cost("report", {key: REPORT_SECONDS[key] for key in sections},
                {"--only": "the sections built"})


#: Seconds of each step of ``smoothshaper validate`` on the reference machine (building the
#: FMUs only when the build folder does not hold them yet).
VALIDATE_SECONDS = {"build": 100.0, "checks": 18.0, "importers": 18.0, "SmoothShaper": 20.0,
                    "TrajectoryGenerator": 4.0, "ServoDrive": 12.0, "FMI 3.0": 12.0}


def validate_cost(*, built: bool) -> Cost:
    """Model of ``smoothshaper validate``.

    Parameters
    ----------
    built : bool
        Whether the build folder already holds the FMUs (CMake then has nothing to do).

    Returns
    -------
    Cost
        One phase per step of :data:`smoothshaper.fmi.validate.RUN_STEPS`.
    """
    phases = dict(VALIDATE_SECONDS)
    if built:
        phases["build"] = 2.0
    return Cost("validate", phases, {"--build-dir": "building the FMUs"})


def measure(scale: float = 1.0) -> dict:
    """Measure the unit costs of the model on this machine.

    Parameters
    ----------
    scale : float
        Size of the measurement runs relative to the default (about 10 s in all at 1).

    Returns
    -------
    dict
        Name -> ``(measured, modelled)`` seconds: one evaluated point of a chain of 1e4, 1e5,
        1e6 taps, and one unit of every other entry of :data:`UNIT_COSTS`.

    Raises
    ------
    ValueError
        ``scale`` is not finite and > 0.
    """
    import io
    import time

    import numpy as np

    from .. import analysis, stages
    from ..filters import Chain
    from ..trajectory import BSpline, Generator
    if not (math.isfinite(scale) and scale > 0):
        raise ValueError(f"scale must be finite and > 0, got {scale!r}")

    def timed(fn):
        t = time.perf_counter()
        fn()
        return time.perf_counter() - t

    out = {}
    c = UNIT_COSTS
    for L in (10**4, 10**5, 10**6):
        chain = [stages.harmonic(T=L * 1e-4)]
        resp = analysis.ChainResponse(chain, Ts=1e-4)
        s = 1j * np.geomspace(0.1, 3e4, max(2, int(1000 * scale)))
        out[f"point, {L} taps"] = (timed(lambda: resp(s)) / s.size, _seconds_per_point(L))
    L = int(1e6 * scale)
    chain = [stages.harmonic(T=L * 1e-4)]
    out["tap"] = (timed(lambda: analysis.ChainResponse(chain, Ts=1e-4)) / L, c["tap"])
    ch = Chain(chain, Ts=1e-4)
    x = np.ones(4 * L)
    out["chain_sample"] = (timed(lambda: ch.process(x)) / x.size, c["chain_sample"])
    n = int(5e5 * scale)
    b = BSpline(degree=3, T=0.1, Ts=1e-3, axes=2)
    xb = np.zeros((n, 2))
    out["bspline_sample_axis"] = (timed(lambda: b.process(xb)) / (2 * n),
                                  c["bspline_sample_axis"])
    g = Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    xg = np.ones(4 * n)
    out["generator_sample_axis"] = (timed(lambda: g.process(xg)) / xg.size,
                                    c["generator_sample_axis"])
    rows = np.random.default_rng(0).normal(size=(n // 5, 5))
    out["csv_value"] = (timed(lambda: np.savetxt(io.StringIO(), rows, delimiter=",",
                                                 fmt="%.17g")) / rows.size, c["csv_value"])
    return out


if __name__ == "__main__":  # pragma: no cover - a measuring tool
    import argparse
    argparse.ArgumentParser(
        prog="python -m smoothshaper.cli.cost",
        description="Measure the unit costs of the CLI's time model on this machine and print "
                    "each next to the model's figure (about a minute).").parse_args()
    for key, (measured, model) in measure().items():
        print(f"{key:24s} measured {measured:.3g} s, model {model:.3g} s")
