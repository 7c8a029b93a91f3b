# SPDX-License-Identifier: Apache-2.0
"""Controller designs for the servo testbed (Bascetta, "Motion control: advanced control
techniques"): each returns the numbers a discrete controller of :mod:`.loop` runs with.

* :func:`pid_gains`: the P/PI cascade's rules (velocity PI on the rigid approximation,
  ``K_pv = J w_cv``, integral time ``T_Iv``; position P, ``K_pp = w_cp``).
* :func:`tdo_coefficients`: the torque disturbance observer with the first-order filter
  ``Q(s) = 1/(1 + s T_f)`` on the nominal rigid model ``P_n(s) = 1/(J_n s + D_n)``, in its
  exact discrete form.
* :func:`augmented`: the integral-action model ``F, G_u`` (the notes' ``z = [x; x_I]``).
* :func:`place`: pole placement of ``F + G_u K_tot`` and of the observer ``A + L C`` (the notes'
  sign convention), by scipy.signal.place_poles.
* :func:`lq_gain` and :func:`kalman_gain`: LQ state feedback and the steady-state Kalman
  predictor, from scipy.linalg.solve_discrete_are.
* :func:`reference_model`: the reference model ``F^o(s) = w_f^3/(s + w_f)^3`` (relative degree 3)
  with the state and torque the plant needs to follow it: the notes' feed-forward
  compensators ``C_1 = G_lm^-1 F^o`` and ``C_2 = G_k^-1 G_lm^-1 F^o`` in state-reference form.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm, solve_discrete_are
from scipy.signal import place_poles

from .._checks import positive as _positive
from ..errors import ParameterError
from .plant import DiscretePlant, ServoPlant

__all__ = ["pid_gains", "tdo_coefficients", "tdo_high_pass", "augmented", "place", "lq_gain",
           "kalman_gain",
           "ReferenceModel", "reference_model", "discrete_poles", "eigenvector_condition"]


def pid_gains(*, J: float, wcv: float, Ti: float, wcp: float) -> dict:
    """Gains of the P/PI cascade: ``K_pv = J w_cv`` (the velocity loop crosses over at ``w_cv``
    on the rigid model of inertia ``J``), ``T_Iv = Ti``, ``K_pp = w_cp``.

    Parameters
    ----------
    J : float, keyword-only
        Inertia the velocity loop sees [kg m^2] (``J_m + J_l/n^2``, or ``J_m`` behind a TDO).
    wcv, wcp : float, keyword-only
        Velocity and position loop crossover [rad/s], > 0, ``wcp < wcv``.
    Ti : float, keyword-only
        Velocity integral time [s], > 0.

    Returns
    -------
    dict
        ``Kpv`` [N m s/rad], ``Ti`` [s], ``Kpp`` [1/s].

    Raises
    ------
    ParameterError
        Naming ``J``, ``wcv``, ``Ti`` or ``wcp``.
    """
    J, wcv, Ti, wcp = (_positive("J", J), _positive("wcv", wcv), _positive("Ti", Ti),
                       _positive("wcp", wcp))
    if wcp >= wcv:
        raise ParameterError("wcp", f"wcp must be below wcv = {wcv!r} (the position loop is "
                             f"the outer, slower one), got {wcp!r}")
    return {"Kpv": J * wcv, "Ti": Ti, "Kpp": wcp}


def tdo_coefficients(*, Jn: float, Dn: float, Tf: float, Ts: float) -> dict:
    """The discrete TDO: ``d[k] = alpha d[k-1] + (1 - alpha) (u[k-1] - (w[k] - a w[k-1])/b)``.

    ``w[k+1] = a w[k] + b (u[k] - d[k])`` is the exact ZOH model of ``P_n`` (``a = e^{-D_n
    Ts/J_n}``, ``b = (1 - a)/D_n``, or ``Ts/J_n`` for ``D_n = 0``), so the bracket is the
    disturbance torque of the previous sample; ``alpha = e^{-Ts/T_f}`` is ``Q(s)`` matched. The
    torque applied is ``u = u* + d``, and with ``P = P_n`` the plant sees ``u* - G_f(z) d`` with
    ``G_f(z) = (1 - z^-1)/(1 - alpha z^-1)``: the notes' high-pass ``s T_f/(1 + s T_f)``
    sampled (equal to it as ``Ts -> 0``).

    Parameters
    ----------
    Jn : float, keyword-only
        Nominal inertia [kg m^2], > 0.
    Dn : float, keyword-only
        Nominal viscous friction [N m s/rad], >= 0.
    Tf : float, keyword-only
        Time constant of ``Q`` [s], > 0.
    Ts : float, keyword-only
        Sample period [s], > 0.

    Returns
    -------
    dict
        ``a``, ``b`` [rad/s per N m], ``alpha``.

    Raises
    ------
    ParameterError
        Naming ``Jn``, ``Dn``, ``Tf`` or ``Ts``.
    """
    Jn, Tf, Ts = _positive("Jn", Jn), _positive("Tf", Tf), _positive("Ts", Ts)
    if not (math.isfinite(Dn) and Dn >= 0):
        raise ParameterError("Dn", f"Dn must be finite and >= 0, got {Dn!r}")
    a = math.exp(-Dn * Ts / Jn)
    b = -math.expm1(-Dn * Ts / Jn) / Dn if Dn > 0 else Ts / Jn
    return {"a": a, "b": b, "alpha": math.exp(-Ts / Tf)}


def tdo_high_pass(w, *, Tf: float, Ts: float) -> np.ndarray:
    """``G_f(z) = (1 - z^-1)/(1 - alpha z^-1)`` at ``z = e^{j w Ts}``, ``alpha = e^{-Ts/T_f}``:
    what the sampled TDO (:func:`tdo_coefficients`) leaves of a disturbance on an exact nominal
    model; the notes' ``s T_f/(1 + s T_f)`` as ``Ts -> 0``.

    Parameters
    ----------
    w : array_like of float
        Frequencies [rad/s].
    Tf, Ts : float, keyword-only
        Filter time constant and sample period [s], > 0.

    Returns
    -------
    ndarray of complex128, the shape of ``w``

    Raises
    ------
    ParameterError
        Naming ``w``, ``Tf`` or ``Ts``.
    """
    from .._checks import finite_array
    w = finite_array("w", w)
    Tf, Ts = _positive("Tf", Tf), _positive("Ts", Ts)
    zi = np.exp(-1j * w * Ts)
    return (1 - zi) / (1 - math.exp(-Ts / Tf) * zi)


def augmented(dp: DiscretePlant) -> tuple[np.ndarray, np.ndarray]:
    """The integral-action model of the notes, discrete: ``x_I[k+1] = x_I[k] + Ts (ybar - q_m)``.

    Parameters
    ----------
    dp : DiscretePlant
        The sampled plant.

    Returns
    -------
    F : ndarray, shape (nx + 1, nx + 1)
        ``[[Ad, 0], [-Ts C, 1]]`` with ``C = [1, 0, ...]`` (the motor encoder).
    G : ndarray, shape (nx + 1,)
        ``[Bu; 0]``.

    Raises
    ------
    ParameterError
        Naming ``dp`` when it is not a DiscretePlant.
    """
    if not isinstance(dp, DiscretePlant):
        raise ParameterError("dp", f"dp must be a DiscretePlant, got {type(dp).__name__}")
    nx = dp.Ad.shape[0]
    F = np.zeros((nx + 1, nx + 1))
    F[:nx, :nx] = dp.Ad
    F[nx, 0] = -dp.Ts
    F[nx, nx] = 1.0
    return F, np.r_[dp.Bu, 0.0]


def discrete_poles(poles, Ts: float) -> np.ndarray:
    """``e^{p Ts}``: where the continuous poles ``p`` [1/s] land in the sampled loop.

    Parameters
    ----------
    poles : array_like of complex
        Continuous poles [1/s], any shape.
    Ts : float
        Sample period [s], > 0.

    Returns
    -------
    ndarray of complex128
        ``e^{p Ts}``, the shape of ``poles``.

    Raises
    ------
    ParameterError
        Naming ``poles`` (not finite numbers) or ``Ts``.
    """
    from .._checks import complex_array
    return np.exp(complex_array("poles", poles) * _positive("Ts", Ts))


def _check_poles(name: str, poles, n: int) -> np.ndarray:
    p = np.asarray(poles, dtype=complex).ravel()
    if p.size != n:
        raise ParameterError(name, f"{name} must hold {n} poles, got {p.size}")
    if not np.all(np.isfinite(p)) or np.any(p.real >= 0):
        raise ParameterError(name, f"{name} must be finite with negative real parts [1/s]")
    for q in p[p.imag != 0]:
        if np.min(np.abs(p - np.conj(q))) > 1e-9 * abs(q):
            raise ParameterError(name, f"{name}: the complex pole {q!r} needs its conjugate")
    if np.unique(np.round(p, 9)).size != p.size:
        raise ParameterError(name, f"{name} must be distinct (a single-input system cannot "
                             "place a repeated pole robustly)")
    return p


def place(dp: DiscretePlant, *, poles, observer_poles) -> dict:
    """Pole placement with integral action and an observer (notes, "State space design").

    ``u = K x~ + k_I x_I`` places the eigenvalues of ``F + G_u [K k_I]`` at ``e^{p Ts}`` for the
    continuous ``poles``; the observer ``x~[k+1] = Ad x~ + Bu u + L (C x~ - q_m)`` places those of
    ``Ad + L C`` at ``e^{o Ts}``.

    Parameters
    ----------
    dp : DiscretePlant
    poles : array_like of complex, keyword-only
        ``nx + 1`` distinct continuous closed-loop poles [1/s], left half-plane, conjugate pairs.
    observer_poles : array_like of complex, keyword-only
        ``nx`` distinct continuous observer poles [1/s].

    Returns
    -------
    dict
        ``K`` shape (nx,), ``kI``, ``L`` shape (nx,), and ``cond``: the condition number of the
        closed loop's eigenvector matrix (the notes' robustness measure, Bauer-Fike).

    Raises
    ------
    ParameterError
        Naming ``poles`` or ``observer_poles``.
    """
    nx = dp.Ad.shape[0]
    p = _check_poles("poles", poles, nx + 1)
    o = _check_poles("observer_poles", observer_poles, nx)
    F, G = augmented(dp)
    Ktot = -place_poles(F, G[:, None], discrete_poles(p, dp.Ts)).gain_matrix[0]
    L = -place_poles(dp.Ad.T, np.eye(nx)[:1].T, discrete_poles(o, dp.Ts)).gain_matrix[0]
    return {"K": Ktot[:nx], "kI": float(Ktot[nx]), "L": L,
            "cond": eigenvector_condition(F + np.outer(G, Ktot))}


def eigenvector_condition(M: np.ndarray) -> float:
    """2-norm condition number of the eigenvector matrix of ``M`` (columns of unit length): the
    notes' robustness measure (Bauer-Fike: a perturbation ``E`` moves each eigenvalue by at most
    ``cond(V) |E|``).

    Parameters
    ----------
    M : array_like, shape (n, n)
        A closed-loop matrix.

    Returns
    -------
    float
        ``cond(V)`` (inf for a defective ``M``).

    Raises
    ------
    ParameterError
        Naming ``M`` when it is not a finite square matrix.
    """
    from .._checks import finite_array
    M = finite_array("M", M)
    if M.ndim != 2 or M.shape[0] != M.shape[1]:
        raise ParameterError("M", f"M must be a square matrix, got shape {M.shape}")
    _, V = np.linalg.eig(M)
    return float(np.linalg.cond(V / np.linalg.norm(V, axis=0)))


def lq_gain(dp: DiscretePlant, *, Q, R: float) -> dict:
    """LQ state feedback for the integral-action model, ``u = K_tot z`` minimising
    ``sum_k (z' Q z + R u^2) Ts`` (the notes' ``J = int z' Q z + u^2 dt`` sampled; ``R`` scales
    the torque).

    Parameters
    ----------
    dp : DiscretePlant
    Q : array_like, shape (nx + 1,) or (nx + 1, nx + 1), keyword-only
        State weight (a vector is the diagonal), symmetric positive semidefinite.
    R : float, keyword-only
        Torque weight [1/(N m)^2], > 0.

    Returns
    -------
    dict
        ``K`` shape (nx,), ``kI``, ``P`` the Riccati solution, shape (nx + 1, nx + 1).

    Raises
    ------
    ParameterError
        Naming ``Q`` or ``R``.
    """
    F, G = augmented(dp)
    Q = _weight("Q", Q, F.shape[0])
    R = _positive("R", R)
    Ts = dp.Ts
    P = solve_discrete_are(F, G[:, None], Q * Ts, np.array([[R * Ts]]))
    Ktot = -(G @ P @ F) / (R * Ts + G @ P @ G)
    nx = dp.Ad.shape[0]
    return {"K": Ktot[:nx], "kI": float(Ktot[nx]), "P": P}


def kalman_gain(dp: DiscretePlant, *, torque_noise: float, load_torque_noise: float,
                encoder_noise: float) -> dict:
    """Steady-state Kalman predictor for ``y = q_m`` in the notes' sign: ``L = -Ad P C'/(C P C'
    + V)``, so that ``x~[k+1] = Ad x~ + Bu u + L (C x~ - y)`` has error dynamics ``Ad + L C``.

    Noise model: white torques held over each sample on the motor (``torque_noise``, std [N m])
    and on the load (``load_torque_noise``), and white encoder noise (``encoder_noise``, std
    [rad]; quantisation of a step ``q`` has std ``q/sqrt(12)``): ``W = s_u^2 Bu Bu' + s_l^2 Bd
    Bd'``, ``V = s_e^2``.

    Parameters
    ----------
    dp : DiscretePlant
    torque_noise, load_torque_noise : float, keyword-only
        Standard deviations [N m], >= 0, not both 0.
    encoder_noise : float, keyword-only
        Standard deviation [rad], > 0.

    Returns
    -------
    dict
        ``L`` shape (nx,), ``P`` (prior error covariance), ``W``, ``V``.

    Raises
    ------
    ParameterError
        Naming the noise that is out of range.
    """
    su = _nonneg("torque_noise", torque_noise)
    sl = _nonneg("load_torque_noise", load_torque_noise)
    se = _positive("encoder_noise", encoder_noise)
    if su == 0 and sl == 0:
        raise ParameterError("torque_noise", "torque_noise and load_torque_noise cannot both be 0")
    W = su * su * np.outer(dp.Bu, dp.Bu) + sl * sl * np.outer(dp.Bd, dp.Bd)
    V = se * se
    C = np.eye(dp.Ad.shape[0])[0]
    P = solve_discrete_are(dp.Ad.T, C[:, None], W, np.array([[V]]))
    L = -(dp.Ad @ P @ C) / (C @ P @ C + V)
    return {"L": L, "P": P, "W": W, "V": V}


def _nonneg(name, value) -> float:
    from .._checks import nonnegative
    return nonnegative(name, value)


def _weight(name: str, Q, n: int) -> np.ndarray:
    from .._checks import real_array
    Q = real_array(name, Q)
    if Q.shape == (n,):
        Q = np.diag(Q)
    if Q.shape != (n, n):
        raise ParameterError(name, f"{name} must have shape ({n},) or ({n}, {n}), got {Q.shape}")
    if not np.all(np.isfinite(Q)) or not np.allclose(Q, Q.T, rtol=0, atol=1e-12 * np.abs(Q).max()):
        raise ParameterError(name, f"{name} must be finite and symmetric")
    if np.min(np.linalg.eigvalsh(Q)) < -1e-12 * np.abs(Q).max():
        raise ParameterError(name, f"{name} must be positive semidefinite")
    return Q


@dataclass(frozen=True)
class ReferenceModel:
    """The reference model and what the plant needs to follow it, discretised (ZOH on ``r``).

    ``xi[k+1] = Phi xi[k] + Gam r[k]``; the desired plant state is ``x_d = M xi`` and the
    torque that keeps the model plant on it ``u_d = N xi + N0 r`` (``r``: the load reference
    referred to the motor side, ``n q_l^d``). Then ``n q_l = F^o(s) r`` and
    ``q_m = C_1(s) r``; with a state feedback ``K`` the feed-forward torque
    ``u_ff = u_d - K x_d`` is the notes' ``C_2(s) r`` (:meth:`compensators`).

    Attributes
    ----------
    Phi : ndarray, shape (m, m)
        Sampled state matrix (``m`` = 4 elastic, 3 rigid).
    Gam : ndarray, shape (m,)
        Sampled input vector.
    M : ndarray, shape (nx, m)
        Desired plant state ``x_d = M xi``.
    N : ndarray, shape (m,)
        Torque row: ``u_d = N xi + N0 r`` [N m].
    N0 : float
        Torque feed-through [N m/rad].
    wf : float
        Bandwidth of ``F^o`` [rad/s].
    Ac : ndarray, shape (m, m)
        Continuous state matrix (for the closed forms).
    Bc : ndarray, shape (m,)
        Continuous input vector.
    """
    Phi: np.ndarray
    Gam: np.ndarray
    M: np.ndarray
    N: np.ndarray
    N0: float
    wf: float
    Ac: np.ndarray
    Bc: np.ndarray

    def compensators(self, s, K) -> tuple[np.ndarray, np.ndarray]:
        """The notes' compensators of the continuous realisation: ``C_1(s) = q_m^d/r`` and
        ``C_2(s) = (u_d - K x_d)/r``.

        Parameters
        ----------
        s : array_like of complex
            Laplace variable [1/s] (not a pole of ``F^o``).
        K : array_like of float, shape (nx,)
            State feedback (the notes' sign, ``u = K x``).

        Returns
        -------
        C1 : ndarray of complex128, shape (len(s),)
        C2 : ndarray of complex128, shape (len(s),) [N m/rad]

        Raises
        ------
        ParameterError
            Naming ``s`` or ``K``.
        """
        from .._checks import complex_array, finite_array
        s = np.atleast_1d(complex_array("s", s)).ravel()
        K = finite_array("K", K)
        if K.shape != (self.M.shape[0],):
            raise ParameterError("K", f"K must have shape ({self.M.shape[0]},), got {K.shape}")
        n = self.Ac.shape[0]
        X = np.array([np.linalg.solve(v * np.eye(n) - self.Ac, self.Bc) for v in s])
        xd = X @ self.M.T
        ud = X @ self.N + self.N0
        return xd[:, 0], ud - xd @ K


def reference_model(plant: ServoPlant, *, wf: float, Ts: float) -> ReferenceModel:
    """``F^o(s) = w_f^3/(s + w_f)^3`` for the load and the plant's state and torque along it.

    Elastic plant: with ``c = D_el/K_el`` and ``v = F^o(s)/(c s + 1) r`` (4th order, state
    ``xi = [v, v', v'', v''']``), ``n q_l = v + c v'`` (``= F^o r``) and ``q_m = v + c v' +
    (J_lr/K_el) v''`` (so ``q_m = G_lm^-1 n q_l``: the notes' ``C_1``); the torque follows from
    the motor equation, ``u_d = J_m q_m'' + (D_m + D_el) q_m' + K_el (q_m - n q_l) - D_el n
    q_l'``. Relative degree 3 is the least that keeps ``u_d`` proper (the notes); with
    ``D_el = 0`` the transmission has no zero and ``F^o`` gets a fourth pole at ``w_f``.
    Rigid plant: ``v = F^o r`` (3rd order), ``q_m = v``, ``u_d = J_m v'' + D_m v'``.

    Parameters
    ----------
    plant : ServoPlant
    wf : float, keyword-only
        Bandwidth of the reference model [rad/s], > 0.
    Ts : float, keyword-only
        Sample period [s], > 0.

    Returns
    -------
    ReferenceModel

    Raises
    ------
    ParameterError
        Naming ``plant``, ``wf`` or ``Ts``.
    """
    if not isinstance(plant, ServoPlant):
        raise ParameterError("plant", f"plant must be a ServoPlant, got {type(plant).__name__}")
    wf, Ts = _positive("wf", wf), _positive("Ts", Ts)
    p = plant.params
    Jm, Dm = p["Jm"], p["Dm"]
    den = np.poly([-wf] * 3)                               # (s + wf)^3
    if plant.kind == "elastic":
        c = p["Del"] / p["Kel"]
        e = c if c > 0 else 1.0 / wf                       # the extra first-order factor
        den = np.polymul(den, [e, 1.0]) / e
        gain = wf ** 3 / e
    else:
        gain = wf ** 3
    m = den.size - 1
    # Controllable canonical form of gain/den(s): xi = [v, ..., v^(m-1)].
    Ac = np.zeros((m, m))
    Ac[np.arange(m - 1), np.arange(1, m)] = 1.0
    Ac[m - 1, :] = -den[:0:-1]
    Bc = np.zeros(m)
    Bc[m - 1] = gain
    # Row i: v^(i) as a combination of [xi, r], i = 0..m.
    d = np.zeros((m + 1, m + 1))
    d[:m, :m] = np.eye(m)
    d[m, :m], d[m, m] = Ac[m - 1], gain
    if plant.kind == "elastic":
        c, c2, K, D = p["Del"] / p["Kel"], p["Jl"] / p["n"] ** 2 / p["Kel"], p["Kel"], p["Del"]
        ql, wl = d[0] + c * d[1], d[1] + c * d[2]
        qm, wm = d[0] + c * d[1] + c2 * d[2], d[1] + c * d[2] + c2 * d[3]
        am = d[2] + c * d[3] + c2 * d[4]
        ud = Jm * am + (Dm + D) * wm + K * (qm - ql) - D * wl
        Mx = np.array([qm, wm, ql, wl])
    else:
        qm, wm, am = d[0], d[1], d[2]
        ud = Jm * am + Dm * wm
        Mx = np.array([qm, wm])
    Phi, Gam = _zoh(Ac, Bc, Ts)
    # The desired state has no feed-through from r (relative degree >= 3): only u_d does.
    return ReferenceModel(Phi, Gam, Mx[:, :m], ud[:m], float(ud[m]), wf, Ac, Bc)


def _zoh(A: np.ndarray, B: np.ndarray, Ts: float) -> tuple[np.ndarray, np.ndarray]:
    n = A.shape[0]
    Mx = np.zeros((n + 1, n + 1))
    Mx[:n, :n] = A
    Mx[:n, n] = B
    E = expm(Mx * Ts)
    return E[:n, :n], E[:n, n].copy()
