# SPDX-License-Identifier: Apache-2.0
"""The SmoothShaper FMU's parameters for a chain: its variables' names and Integer codes
(``modelDescription/generate.py``), the stages it designs itself for a mode (:class:`ModeStage`),
and the plain chain the NumPy reference filters for the same parameters."""
from __future__ import annotations

from dataclasses import dataclass

from ..stages import KINDS, TIMINGS, Stage, for_mode
from ..errors import ParameterError
from .._checks import positive as _positive

__all__ = ["STAGE_FIELDS", "KIND_VALUES", "ModeStage", "start_values", "reference_stages"]


#: Model value references (modelDescription/generate.py).
STAGE_FIELDS = ("kind", "design", "timing", "T", "sigma", "k", "wn", "zeta", "order", "tolerance",
                "notch_pole_zeta", "duration")


#: Integer code of each kind: its ``sms_kind`` value (the order of KINDS).
KIND_VALUES = {k: i for i, k in enumerate(KINDS)}


@dataclass(frozen=True)
class ModeStage:
    """A stage the SmoothShaper FMU designs itself for a mode (``stage[k].design = for_mode``).

    Attributes
    ----------
    kind : str
        A stage kind (:data:`smoothshaper.stages.KINDS`).
    wn : float
        Natural frequency of the mode [rad/s].
    zeta : float
        Its damping ratio (default 0).
    k : int
        Multiple of the zero placed on the mode (default 1).
    """
    kind: str
    wn: float
    zeta: float = 0.0
    k: int = 1


def start_values(stages, *, Ts: float) -> dict:
    """fmpy start values of the SmoothShaper FMU for a chain.

    Parameters
    ----------
    stages : sequence of Stage or ModeStage
        At most 8 stages; unused slots get ``stage[k].kind = -1``.
    Ts : float, keyword-only
        The FMU's sample period [s].

    Returns
    -------
    dict
        Variable name -> value (kinds and choices as Integer codes).

    Raises
    ------
    ParameterError
        Naming ``stages`` when there are more than 8.
    """
    stages = list(stages)
    Ts = _positive("Ts", Ts)
    if len(stages) > 8:
        raise ParameterError("stages", f"stages must hold at most 8 stages, got {len(stages)}")
    values = {"Ts": float(Ts)}
    values.update({f"stage[{k}].kind": -1 for k in range(len(stages), 8)})   # unused: none
    for k, s in enumerate(stages):
        p = f"stage[{k}]."
        values.update({p + "kind": KIND_VALUES[s.kind], p + "k": s.k, p + "wn": s.wn,
                       p + "zeta": s.zeta})
        if isinstance(s, ModeStage):
            values[p + "design"] = 1
        else:
            values.update({p + "design": 0, p + "timing": TIMINGS.index(s.timing),
                           p + "T": s.T, p + "sigma": s.sigma, p + "order": s.order,
                           p + "tolerance": s.tolerance, p + "notch_pole_zeta": s.notch_pole_zeta,
                           p + "duration": s.duration})
            for i, (a, t) in enumerate(zip(s.amplitudes, s.times)):   # kind = impulses
                values[f"{p}amplitude[{i}]"] = a
                values[f"{p}time[{i}]"] = t
    return values


def reference_stages(stages) -> list[Stage]:
    """The Stage list the NumPy reference filters: a ModeStage becomes
    :func:`smoothshaper.stages.for_mode`.

    Parameters
    ----------
    stages : sequence of Stage or ModeStage
        The chain given to the FMU.

    Returns
    -------
    list of Stage
        The same chain as plain stages.

    Raises
    ------
    ParameterError
        A ModeStage's mode is invalid (naming ``kind``, ``wn``, ``zeta`` or ``k``).
    """
    return [for_mode(s.kind, wn=s.wn, zeta=s.zeta, k=s.k) if isinstance(s, ModeStage) else s
            for s in stages]
