# SPDX-License-Identifier: Apache-2.0
"""Run the FMUs in the two importers: fmpy (``simulate_fmu``, default settings,
``output_interval`` = the communication step) and libcosim (libcosimpy)."""
from __future__ import annotations

import numpy as np

from .. import _optional
from ..errors import ParameterError
from .parameters import start_values

__all__ = ["simulate", "simulate_trajectory", "simulate_libcosim", "start_values_for",
           "multi_axis_input", "simulate_multi_axis", "run_fmpy"]


def simulate(fmu: str, stages, t: np.ndarray, u: np.ndarray, *, Ts: float) -> np.ndarray:
    """Output of the SmoothShaper FMU simulated by fmpy with default settings and
    ``output_interval`` = the communication step.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    stages : sequence of Stage or ModeStage
        The chain, set as start values.
    t : ndarray of float64, shape (K,)
        Communication points [s] (:func:`communication_points`).
    u : ndarray of float64, shape (K,)
        Inputs set at ``t``.
    Ts : float, keyword-only
        The FMU's sample period [s].

    Returns
    -------
    ndarray of float64, shape (K,)
        ``y`` at ``t``.

    Raises
    ------
    RuntimeError
        fmpy returned other points than ``t``.
    """
    r = run_fmpy(fmu, t, {"u": u}, start_values(stages, Ts=Ts), ["y"], what="SmoothShaper")
    return np.asarray(r["y"], dtype=float)


def run_fmpy(fmu, t: np.ndarray, inputs, start_values: dict, outputs, *,
             what: str = "an FMU") -> np.ndarray:
    """An FMU in fmpy with default settings from 0 to ``t[-1]``, ``output_interval`` = the
    communication step ``t[1] - t[0]``: the run every fmpy helper of this package makes.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    t : ndarray of float64, shape (K,)
        Communication points [s] (:func:`communication_points`).
    inputs : dict or ndarray (structured)
        Input name -> values at ``t`` (shape (K,) each), or ``fmpy.simulate_fmu``'s ``input``
        itself (``time`` and the inputs, as :func:`multi_axis_input` makes it).
    start_values : dict
        ``fmpy.simulate_fmu``'s start values.
    outputs : sequence of str
        The variables to record.
    what : str, keyword-only
        What runs, for the error of a missing fmpy.

    Returns
    -------
    ndarray (structured)
        fmpy's result: ``time`` (= ``t``) and the outputs.

    Raises
    ------
    RuntimeError
        fmpy returned other points than ``t``.
    """
    fmpy = _optional.require("fmpy", f"running {what} in fmpy")
    step = float(t[1] - t[0])
    if isinstance(inputs, dict):
        signal = np.zeros(t.size, dtype=[("time", float)] + [(n, float) for n in inputs])
        for name, values in inputs.items():
            signal[name] = values
        signal["time"] = t
    else:
        signal = inputs
    signal = _with_held_inputs(fmpy, fmu, signal, start_values)
    result = fmpy.simulate_fmu(str(fmu), start_values=dict(start_values), input=signal,
                               start_time=0.0, stop_time=float(t[-1]), output_interval=step,
                               output=list(outputs), validate=False)
    if result.size != t.size or not np.allclose(result["time"], t, rtol=0, atol=1e-9 * step):
        raise RuntimeError(f"fmpy returned {result.size} samples, expected {t.size}")
    return result


def _with_held_inputs(fmpy, fmu, signal, start_values: dict):
    """``signal`` with a constant column for every scalar input of ``fmu`` it does not drive,
    at the value the run starts it with (``start_values``, else the model description's start):
    the input the FMU holds anyway, given to fmpy so it does not warn of a missing input."""
    names = set(signal.dtype.names)
    kinds = {"Real": float, "Float64": float, "Float32": float, "Boolean": bool}
    held = [v for v in fmpy.read_model_description(str(fmu)).modelVariables
            if v.causality == "input" and v.name not in names and not v.dimensions
            and (v.start is not None or v.name in start_values)]
    if not held:
        return signal
    dtype = signal.dtype.descr + [(v.name, kinds.get(v.type, np.int64)) for v in held]
    out = np.zeros(signal.size, dtype=dtype)
    for name in signal.dtype.names:
        out[name] = signal[name]
    for v in held:
        value = start_values.get(v.name, v.start)
        if isinstance(value, str):   # the model description's start, as written
            value = value.lower() == "true" if v.type == "Boolean" else float(value)
        out[v.name] = value
    return out


def simulate_trajectory(fmu: str, t: np.ndarray, target: np.ndarray, *, Ts: float, **limits):
    """Outputs q, v, a, j of the TrajectoryGenerator FMU simulated by fmpy.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    t : ndarray of float64, shape (K,)
        Communication points [s] (:func:`communication_points`).
    target : ndarray of float64, shape (K,)
        Targets set at ``t``.
    Ts : float, keyword-only
        The FMU's sample period [s].
    **limits
        The FMU's parameters (``vmax``, ``amax``, ``jmax``, ``profile``, ``wn``, ``zeta``,
        ``q0``).

    Returns
    -------
    ndarray of float64, shape (K, 4)
        q, v, a, j at ``t``.

    Raises
    ------
    RuntimeError
        fmpy returned other points than ``t``.
    """
    r = run_fmpy(fmu, t, {"target": target}, dict(Ts=Ts, **limits), "qvaj",
                 what="TrajectoryGenerator")
    return np.column_stack([np.asarray(r[c], dtype=float) for c in "qvaj"])


def start_values_for(model_description, values: dict) -> dict:
    """Start values named as the FMI 2.0 FMU names them (``"vmax[1]"``, ``"stage[0].kind[2]"``)
    for an FMU of either version: for FMI 3.0 the elements of an array variable become that
    array, its other elements at their start values.

    Parameters
    ----------
    model_description : fmpy ModelDescription
        The FMU's (``fmpy.read_model_description``).
    values : dict
        Variable name -> value; names of FMI 2.0 array elements end in ``[i]``.

    Returns
    -------
    dict
        Start values for ``fmpy.simulate_fmu`` on that FMU.

    Raises
    ------
    ParameterError
        A name is none of the FMU's variables (nor an element of one of its arrays).
    """
    if model_description.fmiVersion == "2.0":
        return dict(values)
    arrays = {v.name: v for v in model_description.modelVariables if v.shape}
    scalars = {v.name for v in model_description.modelVariables if not v.shape}
    out, grouped = {}, {}
    for name, value in values.items():
        base, _, index = name.rpartition("[")
        if name in scalars or name in arrays:
            out[name] = value
        elif base in arrays and index.endswith("]") and index[:-1].isdigit():
            grouped.setdefault(base, {})[int(index[:-1])] = value
        else:
            raise ParameterError("values", f"values names {name!r}, not a variable of "
                                 f"{model_description.modelName}")
    for base, elements in grouped.items():
        v = arrays[base]
        full = [v._python_type(x) for x in str(v.start).split()] if v.start is not None \
            else [0] * int(np.prod(v.shape))
        for i, value in elements.items():
            if i >= len(full):
                raise ParameterError("values", f"values names {base}[{i}], beyond the "
                                     f"{len(full)} elements of {base}")
            full[i] = value
        out[base] = full
    return out


def multi_axis_input(model_description, t: np.ndarray, target: np.ndarray,
                     rest=None) -> np.ndarray:
    """The input signal of the MultiAxisGenerator FMU for fmpy: every axis's target, the axes
    beyond ``target``'s columns held at ``rest`` (q0, default 0), so that fmpy finds every input
    and prints no "missing input" warning: ``target[0]`` .. ``target[7]`` for FMI 2.0, the array
    ``target`` for FMI 3.0.

    Parameters
    ----------
    model_description : fmpy ModelDescription
        The FMU's.
    t : ndarray of float64, shape (K,)
        Communication points [s].
    target : ndarray of float64, shape (K, axes)
        Targets of the axes in use.
    rest : sequence of float or None
        Values for every one of the 8 axes' targets (default 0); the columns of ``target``
        replace the first ones.

    Returns
    -------
    ndarray (structured)
        ``time`` and the targets, as ``fmpy.simulate_fmu``'s ``input``.

    Raises
    ------
    ParameterError
        ``target`` has more columns than the FMU has axes, or rows other than ``t``.
    """
    arrays = {v.name: v for v in model_description.modelVariables if v.shape}
    n = int(np.prod(arrays["target"].shape)) if "target" in arrays else sum(
        1 for v in model_description.modelVariables if v.name.startswith("target["))
    target = np.asarray(target, dtype=float).reshape(len(t), -1)
    if target.shape[1] > n:
        raise ParameterError("target", f"target has {target.shape[1]} columns, the FMU has "
                             f"{n} axes")
    full = np.tile(np.zeros(n) if rest is None else np.asarray(rest, float)[:n], (len(t), 1))
    full[:, :target.shape[1]] = target
    if "target" in arrays:
        signal = np.zeros(len(t), dtype=[("time", float), ("target", float, (n,))])
        signal["target"] = full
    else:
        signal = np.zeros(len(t), dtype=[("time", float)] + [(f"target[{i}]", float)
                                                             for i in range(n)])
        for i in range(n):
            signal[f"target[{i}]"] = full[:, i]
    signal["time"] = t
    return signal


def simulate_multi_axis(fmu: str, t: np.ndarray, target: np.ndarray, values: dict) -> np.ndarray:
    """Outputs q, v, a, j of the MultiAxisGenerator FMU (FMI 2.0 or 3.0) simulated by fmpy.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    t : ndarray of float64, shape (K,)
        Communication points [s].
    target : ndarray of float64, shape (K, axes)
        Targets of the axes in use (``axes`` from ``values``).
    values : dict
        Start values named as the FMI 2.0 FMU names them (:func:`start_values_for`), with
        ``axes``.

    Returns
    -------
    ndarray of float64, shape (K, axes, 4)
        q, v, a, j of each axis at ``t``.

    Raises
    ------
    ParameterError
        A start value names no variable, or ``target`` does not fit.
    """
    fmpy = _optional.require("fmpy", "running MultiAxisGenerator in fmpy")
    md = fmpy.read_model_description(str(fmu))
    axes = int(values["axes"])
    rest = [values.get(f"q0[{i}]", 0.0) for i in range(8)]
    signal = multi_axis_input(md, t, target, rest)
    if md.fmiVersion == "2.0":
        names = [f"{c}[{i}]" for i in range(axes) for c in "qvaj"]
    else:
        names = list("qvaj")
    r = run_fmpy(fmu, t, signal, start_values_for(md, values), names, what="MultiAxisGenerator")
    if md.fmiVersion == "2.0":
        return np.stack([np.asarray(r[n], dtype=float) for n in names],
                        axis=1).reshape(t.size, axes, 4)
    return np.stack([np.asarray(r[c], dtype=float)[:, :axes] for c in "qvaj"], axis=2)


def simulate_libcosim(fmu: str, t: np.ndarray, u: np.ndarray, params: dict, *,
                      input_name: str | tuple = "u", outputs=("y",)) -> np.ndarray:
    """Outputs of an FMU in libcosim (libcosimpy), the second importer.

    Fixed step ``t[1] - t[0]``, the input overridden before every step (as fmpy sets it),
    outputs read after the step; row 0 is the rest point (libcosim observes only after steps)
    and is left NaN.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    t : ndarray of float64, shape (K,)
        Communication points [s] (:func:`communication_points`).
    u : ndarray of float64, shape (K,) or (K, m)
        Inputs set at ``t`` (one column per input).
    params : dict
        Start values: int values are set as Integers (the FMUs' choice codes), the others as
        Reals.
    input_name : str or tuple of str, keyword-only
        The input variable (default ``"u"``), or the ``m`` inputs, one per column of ``u``.
    outputs : sequence of str, keyword-only
        Output variables, one column each (default ``("y",)``).

    Returns
    -------
    ndarray of float64, shape (K, len(outputs))
        The outputs at ``t`` (row 0 NaN).

    Raises
    ------
    RuntimeError
        libcosim refused an initial value or a step failed.
    """
    _optional.require("fmpy", "running an FMU in libcosim (fmpy reads its model description)")
    _optional.require("libcosimpy", "running an FMU in libcosim")
    from fmpy import read_model_description
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave
    log_output_level(CosimLogLevel.ERROR)
    vr = {v.name: v.valueReference for v in read_model_description(fmu).modelVariables}
    step_ns = int(round((t[1] - t[0]) * 1e9))
    execution = CosimExecution.from_step_size(step_size=step_ns)
    index = execution.add_local_slave(local_slave=CosimLocalSlave(fmu_path=str(fmu), instance_name="s"))
    override = CosimManipulator.create_override()
    execution.add_manipulator(manipulator=override)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer=observer)
    names = (input_name,) if isinstance(input_name, str) else tuple(input_name)
    u = np.asarray(u, dtype=float).reshape(t.size, len(names))
    for name, value in {**params, **dict(zip(names, map(float, u[0])))}.items():
        if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
            accepted = execution.integer_initial_value(index, vr[name], int(value))
        else:
            accepted = execution.real_initial_value(index, vr[name], float(value))
        if not accepted:
            raise RuntimeError(f"libcosim refused the initial value of {name}")
    y = np.full((t.size, len(outputs)), np.nan)
    out_vrs = [vr[n] for n in outputs]
    for k in range(t.size - 1):
        override.slave_real_values(index, [vr[n] for n in names], [float(x) for x in u[k]])
        if not execution.step():
            raise RuntimeError(f"libcosim step {k} failed")
        y[k + 1] = observer.last_real_values(index, out_vrs)
    return y
