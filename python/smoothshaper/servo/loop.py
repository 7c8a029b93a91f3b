# SPDX-License-Identifier: Apache-2.0
"""The sampled drive: a controller of :mod:`.controllers` around the exact ZOH plant.

At sample ``k`` the drive reads ``q_m[k]``, ``q_m'[k]`` (the plant state at ``t = k Ts``) and
the reference ``r[k]``, and holds ``u[k]`` over ``[k Ts, (k+1) Ts)``; the load torque is held
the same way. Plant and controller are linear, so the whole loop is one discrete system
``X[k+1] = Acl X[k] + Bcl [r[k], tau_l[k]]``: its eigenvalues are the closed-loop poles, its
transfer ``Ccl (zI - Acl)^-1 Bcl + Dcl`` at ``z = e^{j w Ts}`` the exact frequency response of the
simulation, and :meth:`Drive.simulate` runs it.
"""
from __future__ import annotations

import numpy as np

from .._checks import finite_signal as _finite_signal, positive as _positive, \
    real_array as _real_array
from ..errors import ParameterError
from . import controllers as _ctrl
from .plant import ServoPlant, discretize

__all__ = ["Drive", "OUTPUTS", "INPUTS"]

#: Rows of :meth:`Drive.simulate`'s result and of :meth:`Drive.frequency_response`'s outputs.
OUTPUTS = ("q_m", "w_m", "q_l", "w_l", "tau_m")
#: The loop's inputs: the load position reference [rad] and the load torque [N m].
INPUTS = ("reference", "tau_load")


def _linearise(step, n: int):
    """Matrices of a linear step ``(s, r, qm, wm) -> (s', u)`` read off unit inputs:
    ``s' = Ac s + Bc [r, qm, wm]``, ``u = Cc s + Dc [r, qm, wm]``."""
    Ac, Cc = np.zeros((n, n)), np.zeros(n)
    Bc, Dc = np.zeros((n, 3)), np.zeros(3)
    zero = np.zeros(n)
    for i in range(n):
        e = np.zeros(n)
        e[i] = 1.0
        Ac[:, i], Cc[i] = step(e, 0.0, 0.0, 0.0)
    for j in range(3):
        w = [0.0, 0.0, 0.0]
        w[j] = 1.0
        Bc[:, j], Dc[j] = step(zero, *w)
    return Ac, Bc, Cc, Dc


class Drive:
    """A servo drive in closed loop: the controller ``controller`` on ``plant`` sampled at
    ``Ts``.

    Parameters
    ----------
    plant : ServoPlant
        :func:`.elastic_servo`, :func:`.rigid_servo` or :func:`.servo_from_modes`.
    controller : PID, PolePlacement or LQG
        The configuration (:mod:`.controllers`).
    Ts : float, keyword-only
        Sample period [s], > 0.

    Attributes
    ----------
    discrete : DiscretePlant
        The sampled plant.
    controller : Controller
        The built controller (``gains``: the design's numbers).
    A, B, C, D : ndarray
        The closed loop: state ``[x, controller state]``, inputs :data:`INPUTS`, outputs
        :data:`OUTPUTS`; shapes (N, N), (N, 2), (5, N), (5, 2).

    Raises
    ------
    ParameterError
        Naming ``plant``, ``controller``, ``Ts`` or the tuning parameter at fault.
    """

    def __init__(self, plant: ServoPlant, controller, *, Ts: float):
        if not isinstance(plant, ServoPlant):
            raise ParameterError("plant", f"plant must be a ServoPlant, got {type(plant).__name__}")
        self.Ts = _positive("Ts", Ts)
        self.plant = plant
        self.config = controller
        self.discrete = dp = discretize(plant, Ts=self.Ts)
        self.controller = c = _ctrl.build(controller, dp)
        Ac, Bc, Cc, Dc = _linearise(c.step, c.n_states)
        nx, n = plant.order, plant.params["n"]
        Cm = np.eye(nx)[:2]                           # the drive reads q_m and q_m'
        N = nx + c.n_states
        A = np.zeros((N, N))
        # u = Cc s + Dc[0] r_m + Dc[1:] Cm x, with r_m = n r (motor-side reference)
        A[:nx, :nx] = dp.Ad + np.outer(dp.Bu, Dc[1:] @ Cm)
        A[:nx, nx:] = np.outer(dp.Bu, Cc)
        A[nx:, :nx] = Bc[:, 1:] @ Cm
        A[nx:, nx:] = Ac
        B = np.zeros((N, 2))
        B[:nx, 0] = dp.Bu * Dc[0] * n
        B[:nx, 1] = dp.Bd
        B[nx:, 0] = Bc[:, 0] * n
        C = np.zeros((5, N))
        C[:4, :nx] = plant.outputs
        C[4, :nx] = Dc[1:] @ Cm
        C[4, nx:] = Cc
        D = np.zeros((5, 2))
        D[4, 0] = Dc[0] * n
        self.A, self.B, self.C, self.D = A, B, C, D

    @property
    def order(self) -> int:
        """The loop's state dimension N (plant and controller states)."""
        return self.A.shape[0]

    def poles(self) -> np.ndarray:
        """Eigenvalues of the closed loop (plant, observer, integrator, filters).

        Returns
        -------
        ndarray of complex128, shape (N,)
            Discrete poles (``e^{s Ts}`` of the continuous ones they stand for); unused
            controller states show as poles at 0.
        """
        return np.linalg.eigvals(self.A)

    def rest_state(self, r0: float = 0.0) -> np.ndarray:
        """The loop's state at rest at the load reference ``r0`` (no load torque).

        Parameters
        ----------
        r0 : float
            Load position [rad].

        Returns
        -------
        ndarray of float64, shape (N,)
            ``X`` with ``X = A X + B [r0, 0]``.

        Raises
        ------
        ParameterError
            Naming ``r0`` when it is not finite.
        """
        from .._checks import finite
        r0 = finite("r0", r0)
        M = np.eye(self.order) - self.A
        return np.linalg.solve(M, self.B[:, 0] * r0)

    def simulate(self, reference, *, tau_load=None, x0=None) -> dict:
        """Run the loop.

        Parameters
        ----------
        reference : array_like of float, shape (N,)
            Load position reference ``q_l^d[k]`` [rad] (load side), e.g. a library chain's
            output.
        tau_load : array_like of float, shape (N,), keyword-only
            Load torque [N m] (load side, opposing motion), default 0.
        x0 : array_like of float, shape (order,), keyword-only
            Initial loop state (default: at rest at 0).

        Returns
        -------
        dict of str to ndarray of float64, shape (N,)
            :data:`OUTPUTS` at ``t = k Ts`` (before the step to ``k + 1``): ``q_m`` [rad],
            ``w_m`` [rad/s], ``q_l`` [rad], ``w_l`` [rad/s], ``tau_m`` [N m]; and ``t`` [s].

        Raises
        ------
        ParameterError
            Naming ``reference``, ``tau_load`` or ``x0``.
        """
        r = _finite_signal("reference", reference)
        d = np.zeros_like(r) if tau_load is None else _finite_signal("tau_load", tau_load)
        if d.shape != r.shape:
            raise ParameterError("tau_load", f"tau_load must have the shape of reference "
                                 f"{r.shape}, got {d.shape}")
        X = np.zeros(self.order) if x0 is None else _real_array("x0", x0).copy()
        if X.shape != (self.order,) or not np.all(np.isfinite(X)):
            raise ParameterError("x0", f"x0 must be {self.order} finite values")
        W = np.column_stack([r, d])
        Y = np.empty((r.size, 5))
        A, B, C, D = self.A, self.B, self.C, self.D
        for k in range(r.size):
            Y[k] = C @ X + D @ W[k]
            X = A @ X + B @ W[k]
        out = {name: Y[:, i].copy() for i, name in enumerate(OUTPUTS)}
        out["t"] = np.arange(r.size) * self.Ts
        return out

    def frequency_response(self, w, *, input: str, output: str) -> np.ndarray:
        """The sampled loop's response at ``z = e^{j w Ts}``: exactly what :meth:`simulate`
        does to a sampled sinusoid in steady state.

        Parameters
        ----------
        w : array_like of float
            Frequencies [rad/s], below the Nyquist frequency ``pi/Ts``.
        input : {"reference", "tau_load"}, keyword-only
        output : {"q_m", "w_m", "q_l", "w_l", "tau_m"}, keyword-only

        Returns
        -------
        ndarray of complex128, the shape of ``w``

        Raises
        ------
        ParameterError
            Naming ``w``, ``input`` or ``output``.
        """
        from .._checks import choice, finite_array
        i = INPUTS.index(choice("input", input, INPUTS))
        o = OUTPUTS.index(choice("output", output, OUTPUTS))
        w = finite_array("w", w)
        z = np.exp(1j * w * self.Ts)
        eye = np.eye(self.order)
        flat = [self.C[o] @ np.linalg.solve(v * eye - self.A, self.B[:, i]) + self.D[o, i]
                for v in z.ravel()]
        return np.array(flat).reshape(w.shape)
