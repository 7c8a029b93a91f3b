# SPDX-License-Identifier: Apache-2.0
"""A system of FMUs in an SSP 1.0 file (SystemStructure.ssd + resources/<Model>.fmu), run in
libcosim and fmpy: what the system co-simulations (:mod:`~smoothshaper.fmi.cosim`,
:mod:`~smoothshaper.fmi.servo_cosim`) share.

A :class:`System` is a chain ``Generator -> ... -> last``: components, connections, their
parameters, the parameter changes of its "without shaper" run, the system input (or none: the
generator's target is then one of the bound parameters) and the variables recorded.
Co-simulation timing (both importers, step h = Ts): at step k every FMU steps with the inputs
its connections carried after step k-1, so each connection adds one step of delay and the
generator sees the system input of step k-1.

A system without an input is one file that both importers run: libcosim refuses a connection
from a system-level connector ("Unable to create execution from path"), so a system with an
input gets a second file without it for libcosim. libcosim applies the file's parameter
bindings; fmpy 0.3's ``simulate_ssp`` reads them but applies only its ``parameter_set``
argument (:func:`fmpy_applies_bindings` detects it), so :func:`run_fmpy` passes them
(:func:`ssp_parameter_set`).
"""
from __future__ import annotations

import zipfile
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace
from typing import Callable
from xml.sax.saxutils import quoteattr

import numpy as np

from .. import _optional

__all__ = ["SSD_NS", "System", "system_structure", "write_ssp", "ssp_parameters",
           "ssp_parameter_set", "fmpy_applies_bindings", "run_fmpy", "run_libcosim",
           "generator_shaper_reference", "settled_residual"]

SSD_NS = ('xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon" '
          'xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription" '
          'xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues"')


@dataclass(frozen=True)
class System:
    """A chain of FMUs driven by one system input.

    Attributes
    ----------
    name : str
        The system's name (and its SSP file's stem).
    description : str
        One line for the SSD.
    components : tuple
        ``(name, model, ((connector, "input" or "output"), ...))`` per component.
    connections : tuple
        ``(element, connector, element, connector)`` per connection.
    parameters : dict
        Component -> {variable: value} (int values are Integers).
    without_shaper : dict
        ``"Component.variable"`` -> value for the run without the shaper.
    system_input : tuple or None
        ``(connector, element, element's connector)`` of the system input; None: the system
        has none, the generator's target is among its ``parameters`` (set at initialization).
    recorded : tuple
        ``(element, variable)`` pairs the runs return, in order.
    Ts : float
        The communication step [s] (every FMU's sample period).
    stop_time : float
        Length of a run [s].
    target : callable
        ``target(t)``: the system input (the bound target) at the times ``t`` [s].
    """
    name: str
    description: str
    components: tuple
    connections: tuple
    parameters: dict
    without_shaper: dict
    system_input: tuple | None
    recorded: tuple
    Ts: float
    stop_time: float
    target: Callable


def _ssv_value(value) -> str:
    if isinstance(value, int):
        return f'<ssv:Integer value="{value}"/>'
    return f'<ssv:Real value="{value!r}"/>'


def system_structure(system: System, *, system_input: bool = True) -> str:
    """SystemStructure.ssd of the system (SSP 1.0; parameters inline as ssv parameter sets).

    Parameters
    ----------
    system : System
    system_input : bool, keyword-only
        False leaves out the system's input connector and its connection (libcosim refuses
        connections without a start element); a system without an input has neither.

    Returns
    -------
    str
        The XML.

    Raises
    ------
    KeyError
        A component without its parameters in ``system.parameters``.
    """
    system_input = system_input and system.system_input is not None
    connector, element, element_connector = system.system_input or (None, None, None)
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<ssd:SystemStructureDescription {SSD_NS} version="1.0" name="{system.name}">',
             f'  <ssd:System name="{system.name}" description={quoteattr(system.description)}>']
    if system_input:
        lines += ['    <ssd:Connectors>',
                  f'      <ssd:Connector name="{connector}" kind="input"><ssc:Real/>'
                  '</ssd:Connector>', '    </ssd:Connectors>']
    lines.append('    <ssd:Elements>')
    for name, model, connectors in system.components:
        lines.append(f'      <ssd:Component name="{name}" type="application/x-fmu-sharedlibrary" '
                     f'source="resources/{model}.fmu">')
        lines.append('        <ssd:Connectors>')
        lines += [f'          <ssd:Connector name="{c}" kind="{kind}"><ssc:Real/></ssd:Connector>'
                  for c, kind in connectors]
        lines += ['        </ssd:Connectors>', '        <ssd:ParameterBindings>',
                  '          <ssd:ParameterBinding>', '            <ssd:ParameterValues>',
                  f'              <ssv:ParameterSet version="1.0" name="{name}">',
                  '                <ssv:Parameters>']
        lines += [f'                  <ssv:Parameter name={quoteattr(p)}>{_ssv_value(v)}'
                  '</ssv:Parameter>' for p, v in system.parameters[name].items()]
        lines += ['                </ssv:Parameters>', '              </ssv:ParameterSet>',
                  '            </ssd:ParameterValues>', '          </ssd:ParameterBinding>',
                  '        </ssd:ParameterBindings>', '      </ssd:Component>']
    lines += ['    </ssd:Elements>', '    <ssd:Connections>']
    if system_input:
        lines.append(f'      <ssd:Connection startConnector="{connector}" '
                     f'endElement="{element}" endConnector="{element_connector}"/>')
    lines += [f'      <ssd:Connection startElement="{a}" startConnector="{ac}" endElement="{b}" '
              f'endConnector="{bc}"/>' for a, ac, b, bc in system.connections]
    lines += ['    </ssd:Connections>', '  </ssd:System>',
              f'  <ssd:DefaultExperiment startTime="0.0" stopTime="{system.stop_time!r}"/>',
              '</ssd:SystemStructureDescription>', '']
    return "\n".join(lines)


def write_ssp(system: System, out_dir: Path, fmus: dict[str, Path]) -> tuple[Path, Path]:
    """Write ``<name>.ssp`` (a zip: SystemStructure.ssd + resources/<Model>.fmu), the system
    with its input, and ``<name>-libcosim.ssp``, the same without the system-level input
    (libcosim cannot connect it; its runner sets the generator's input). A system without an
    input is the one file ``<name>.ssp``, which both importers run.

    Parameters
    ----------
    system : System
    out_dir : Path
        Folder (created).
    fmus : dict of str to Path
        Model name -> FMU file.

    Returns
    -------
    tuple of Path
        The files fmpy and libcosim run (the same file for a system without an input).

    Raises
    ------
    RuntimeError
        A model of the system is missing from ``fmus``.
    """
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    missing = [m for _, m, _ in system.components if m not in fmus]
    if missing:
        raise RuntimeError(f"the system needs {', '.join(missing)}.fmu (build the FMUs first)")
    paths = out_dir / f"{system.name}.ssp", out_dir / f"{system.name}-libcosim.ssp"
    files = tuple(zip(paths, (True, False)))
    if system.system_input is None:
        paths, files = (paths[0], paths[0]), files[:1]
    for path, with_input in files:
        with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
            z.writestr("SystemStructure.ssd", system_structure(system, system_input=with_input))
            for _, model, _ in system.components:
                z.write(fmus[model], f"resources/{model}.fmu")
    return paths


def ssp_parameters(ssp: Path) -> dict[str, float | int]:
    """{"Component.variable": value} read back from an SSP's inline parameter bindings.

    Parameters
    ----------
    ssp : Path
        An SSP file.

    Returns
    -------
    dict
        Real parameters as float, Integers as int.

    Raises
    ------
    OSError
        The file cannot be read.
    zipfile.BadZipFile
        It is not an SSP (zip) file.
    """
    import xml.etree.ElementTree as ET
    ns = {"ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
          "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues"}
    with zipfile.ZipFile(ssp) as z:
        root = ET.fromstring(z.read("SystemStructure.ssd"))
    values = {}
    for comp in root.iterfind(".//ssd:Component", ns):
        for p in comp.iterfind(".//ssv:Parameter", ns):
            real, integer = p.find("ssv:Real", ns), p.find("ssv:Integer", ns)
            value = float(real.get("value")) if real is not None else int(integer.get("value"))
            values[f"{comp.get('name')}.{p.get('name')}"] = value
    return values


def ssp_parameter_set(ssp: Path, **overrides) -> SimpleNamespace:
    """An SSP's parameter bindings as ``fmpy.ssp.simulate_ssp``'s ``parameter_set``: fmpy reads
    a system's bindings but applies only this argument, so
    ``simulate_ssp(ssp, parameter_set=ssp_parameter_set(ssp))`` runs the system as its file
    says.

    Parameters
    ----------
    ssp : Path
        An SSP file.
    **overrides
        ``"Component.variable"`` -> value, replacing or adding to the bindings.

    Returns
    -------
    SimpleNamespace
        ``parameters``: a list of objects with ``name`` and ``value``.

    Raises
    ------
    OSError
        The file cannot be read.
    zipfile.BadZipFile
        It is not an SSP (zip) file.
    """
    values = {**ssp_parameters(ssp), **overrides}
    return SimpleNamespace(parameters=[SimpleNamespace(name=n, value=v) for n, v in values.items()])


def _recorded_columns(system: System, r) -> list[str]:
    names = r.dtype.names
    return [next(n for n in names if n.endswith(f"{e}.{v}")) for e, v in system.recorded]


def fmpy_applies_bindings(system: System, ssp: Path) -> bool:
    """Does ``fmpy.ssp.simulate_ssp`` apply an SSP's parameter bindings by itself? The system
    (one without an input, its move bound from t = 0) runs alone for 50 steps: its first
    recorded variable moves only if the bindings were applied (fmpy 0.3: they are not).

    Parameters
    ----------
    system : System
        One without an input.
    ssp : Path
        Its file.

    Returns
    -------
    bool

    Raises
    ------
    ValueError
        The system has an input (its move would depend on it, not on the bindings).
    """
    if system.system_input is not None:
        raise ValueError(f"{system.name} has an input: its move does not show the bindings")
    _optional.require("fmpy", "checking whether fmpy applies an SSP's bindings")
    from fmpy.ssp.simulation import simulate_ssp
    r = simulate_ssp(str(ssp), stop_time=50.5 * system.Ts, step_size=system.Ts)
    return bool(np.any(np.asarray(r[_recorded_columns(system, r)[0]], float) != 0.0))


def run_fmpy(system: System, ssp: Path, *, shaper: bool) -> tuple[np.ndarray, ...]:
    """(t, recorded...) from fmpy's SSP master (t += h, step Ts): row k is the state after
    step k, i.e. at t_(k+1). The file's parameter bindings are passed as ``parameter_set``
    (:func:`ssp_parameter_set`), the system input (if any) as ``input``.

    Parameters
    ----------
    system : System
    ssp : Path
        ``<name>.ssp`` (:func:`write_ssp`).
    shaper : bool, keyword-only
        False applies ``system.without_shaper``.

    Returns
    -------
    tuple of ndarray
        The times and one array per ``system.recorded``.

    Raises
    ------
    StopIteration
        fmpy's result lacks a recorded variable.
    """
    _optional.require("fmpy", "an SSP system in fmpy")
    from fmpy.ssp.simulation import simulate_ssp
    pset = ssp_parameter_set(ssp, **({} if shaper else system.without_shaper))
    Ts = system.Ts
    inputs = {} if system.system_input is None else {
        "input": {system.system_input[0]: lambda t: float(system.target(t))}}
    r = simulate_ssp(str(ssp), stop_time=system.stop_time - 0.5 * Ts, step_size=Ts,
                     parameter_set=pset, **inputs)
    columns = _recorded_columns(system, r)
    return (np.asarray(r["time"]) + Ts, *(np.asarray(r[c], float) for c in columns))


def run_libcosim(system: System, ssp: Path, *, shaper: bool,
                 n_steps: int) -> tuple[np.ndarray, ...]:
    """The same in libcosim: libcosim loads ``<name>-libcosim.ssp`` (components, connections,
    parameter bindings; ``<name>.ssp`` for a system without an input); the generator's input is
    overridden with what the system input's connection would deliver (the input of the
    previous step), outputs read after every step.

    Parameters
    ----------
    system : System
    ssp : Path
        ``<name>-libcosim.ssp`` (the second file :func:`write_ssp` returns).
    shaper : bool, keyword-only
        False applies ``system.without_shaper``.
    n_steps : int, keyword-only
        Steps to run.

    Returns
    -------
    tuple of ndarray
        The times and one array per ``system.recorded``.

    Raises
    ------
    RuntimeError
        libcosim refused a value or a step failed.
    """
    _optional.require("libcosimpy", "an SSP system in libcosim")
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    log_output_level(CosimLogLevel.ERROR)
    Ts = system.Ts
    execution = CosimExecution.from_ssp_file(str(ssp), step_size=int(round(Ts * 1e9)))
    index = {i.name.decode(): i.index for i in execution.slave_infos()}
    vrs = {name: {v.name.decode(): v.reference for v in execution.slave_variables(i)}
           for name, i in index.items()}
    if not shaper:
        for key, value in system.without_shaper.items():
            comp, var = key.split(".", 1)
            setter = (execution.integer_initial_value if isinstance(value, int)
                      else execution.real_initial_value)
            if not setter(index[comp], vrs[comp][var], value):
                raise RuntimeError(f"libcosim refused {key}")
    override = None
    if system.system_input is not None:
        override = CosimManipulator.create_override()
        execution.add_manipulator(manipulator=override)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer=observer)
    t = (np.arange(n_steps) + 1) * Ts
    inputs = np.r_[0.0, system.target(np.arange(n_steps - 1) * Ts)]
    rows = np.empty((len(system.recorded), n_steps))
    for k in range(n_steps):
        if override is not None:
            _, element, connector = system.system_input
            override.slave_real_values(index[element], [vrs[element][connector]],
                                       [float(inputs[k])])
        if not execution.step():
            raise RuntimeError(f"libcosim step {k} failed")
        for j, (e, v) in enumerate(system.recorded):
            rows[j, k] = observer.last_real_values(index[e], [vrs[e][v]])[0]
    return (t, *rows)


def generator_shaper_reference(system: System, n_steps: int, *, limits: dict,
                               stages) -> np.ndarray:
    """The NumPy reference of the chain's first two components, TrajectoryGenerator and
    SmoothShaper, with the one-step delay of each connection: the shaper's output after each
    of ``n_steps`` steps (the generator rests at 0, ``stages`` empty is no shaper; a bound
    target is the generator's from the first step on).

    Parameters
    ----------
    system : System
        Its ``target`` and ``Ts``.
    n_steps : int
        Steps (checked by the caller).
    limits : dict
        The generator's ``vmax``, ``amax``, ``jmax`` (polynomial profile).
    stages : sequence of Stage
        The shaper's chain.

    Returns
    -------
    ndarray of float64, shape (n_steps,)

    Raises
    ------
    ParameterError
        Invalid limits or stages.
    """
    from .. import reference as filters_reference
    from ..trajectory import generator_reference
    Ts = system.Ts
    if system.system_input is None:   # bound at initialization
        tgt_in = np.asarray(system.target(np.arange(n_steps) * Ts), float)
    else:                             # through a connection: one step late
        tgt_in = np.r_[0.0, system.target(np.arange(n_steps - 1) * Ts)]
    q = np.r_[0.0, generator_reference(tgt_in, Ts=Ts, **limits)[:, 0]]
    if not stages:
        return q[:n_steps]
    return filters_reference.filter(list(stages), q[:n_steps], Ts=Ts)


def settled_residual(command: np.ndarray, output: np.ndarray, target: float) -> float:
    """``max |output - target|`` once the command stays within 1e-12 of the target (the
    residual a system leaves after its move).

    Parameters
    ----------
    command, output : ndarray of float64, shape (K,)
        The command into the last component and its output.
    target : float
        Where the move ends.

    Returns
    -------
    float

    Raises
    ------
    RuntimeError
        The command did not settle before the last ten samples.
    """
    off = np.nonzero(np.abs(command - target) > 1e-12 * abs(target))[0]
    settled = off[-1] + 1 if off.size else 0
    if settled >= command.size - 10:
        raise RuntimeError("the command did not settle within the run: lengthen STOP_TIME")
    return float(np.max(np.abs(output[settled:] - target)))
