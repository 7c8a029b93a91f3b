# SPDX-License-Identifier: Apache-2.0
"""The servo testbed (smoothshaper.servo) against closed forms: plant, poles, observer, steady
states, the TDO's transfer functions, the Kalman and LQ gains, the feed-forward compensators."""
import math

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.signal import lfilter

import smoothshaper as sms
from smoothshaper import servo
from smoothshaper.errors import ParameterError
from smoothshaper.servo import design, presets

TS = presets.TS
EPS = np.finfo(float).eps
PLANT = servo.elastic_servo()


def bauer_fike(M: np.ndarray) -> float:
    """Bound on how far rounding moves the eigenvalues of M: cond(V) N eps |M| (Bauer-Fike,
    with the rounding of forming M taken as N eps |M|)."""
    _, V = np.linalg.eig(M)
    return np.linalg.cond(V / np.linalg.norm(V, axis=0)) * M.shape[0] * EPS * np.linalg.norm(M, 2)


def match(got, want, tol):
    """Every wanted eigenvalue has one of ``got`` within tol."""
    return max(np.min(np.abs(np.asarray(got) - w)) for w in want) <= tol


def test_plant_is_the_notes_model_with_the_damping_sign_corrected():
    p = servo.NOTES
    Jr = p["Jl"] / p["n"] ** 2
    A = PLANT.A
    assert A[1, 0] == -p["Kel"] / p["Jm"] and A[1, 1] == -(p["Dm"] + p["Del"]) / p["Jm"]
    assert A[3, 0] == p["Kel"] / Jr and A[3, 3] == -p["Del"] / Jr   # the notes print +D_el/J_lr
    assert np.all(np.linalg.eigvals(A).real <= 1e-9)
    assert PLANT.B_u[1] == 1 / p["Jm"] and PLANT.B_d[3] == -1 / (p["n"] * Jr)
    m = PLANT.modes()
    assert m["w_z"] == pytest.approx(math.sqrt(p["Kel"] / Jr), rel=1e-14)
    assert m["w_p"] == pytest.approx(179.0, abs=0.05)        # the table's resonance


def test_zoh_is_exact():
    """Ad = e^{A Ts}; Bu = int_0^Ts e^{A t} dt B_u by Simpson's rule on 2001 points (error
    ~ (Ts/2000)^4 |A|^4 / 180, far below 1e-12 relative)."""
    dp = servo.discretize(PLANT, Ts=TS)
    assert np.max(np.abs(dp.Ad - expm(PLANT.A * TS))) <= 1e-13
    t = np.linspace(0, TS, 2001)
    vals = np.array([expm(PLANT.A * v) @ PLANT.B_u for v in t])
    w = np.ones(t.size)
    w[1:-1:2], w[2:-1:2] = 4, 2
    integral = (w[:, None] * vals).sum(0) * (t[1] - t[0]) / 3
    assert np.max(np.abs(dp.Bu - integral)) <= 1e-10 * np.max(np.abs(dp.Bu))


def test_pole_placement_puts_every_pole_where_placed():
    cfg = presets.pole_placement(None)
    drive = servo.Drive(PLANT, cfg, Ts=TS)
    want = np.r_[design.discrete_poles(cfg.poles, TS),
                 design.discrete_poles(cfg.observer_poles, TS)]
    assert match(drive.poles(), want, bauer_fike(drive.A))   # the loop is ill-conditioned:
    g = drive.controller.gains                                 # the blocks are checked tighter
    F, G = design.augmented(drive.discrete)
    ctrl = F + np.outer(G, np.r_[g["K"], g["kI"]])
    obs = drive.discrete.Ad + np.outer(g["L"], np.eye(4)[0])
    for M, poles in ((ctrl, cfg.poles), (obs, cfg.observer_poles)):
        tol = bauer_fike(M)
        assert tol < 1e-5
        assert match(np.linalg.eigvals(M), design.discrete_poles(poles, TS), tol)


def test_feed_forward_adds_the_reference_model_poles():
    """With F^o the loop adds the reference model: (s + wf)^3 and the transmission zero's pole
    -K_el/D_el, sampled. The triple pole is compared through the characteristic polynomial of
    Phi (a triple eigenvalue moves by eps^(1/3))."""
    drive = servo.Drive(PLANT, presets.pole_placement(), Ts=TS)
    ref = drive.controller.gains["reference_model"]
    p = PLANT.params
    want = np.poly(design.discrete_poles([-presets.WF] * 3 + [-p["Kel"] / p["Del"]], TS)).real
    assert np.max(np.abs(np.poly(ref.Phi) - want)) <= 64 * EPS


def test_observer_error_obeys_A_plus_LC():
    drive = servo.Drive(PLANT, presets.lqg(None), Ts=TS)
    L = drive.controller.gains["L"]
    M = drive.discrete.Ad + np.outer(L, np.eye(4)[0])
    X = np.zeros(drive.order)
    X[4:8] = [1e-3, -0.2, 2e-3, 0.1]          # estimate off the (resting) plant
    e = X[4:8] - X[:4]
    for _ in range(60):
        X = drive.A @ X
        e_next = M @ e
        # rounding of one product A X: a few eps |A|_inf |X| (and of e's own product)
        tol = 4 * EPS * np.abs(drive.A).sum(1).max() * np.max(np.abs(X))
        assert np.max(np.abs(X[4:8] - X[:4] - e_next)) <= tol
        e = X[4:8] - X[:4]
    assert np.max(np.abs(np.linalg.eigvals(M))) < 1


@pytest.mark.parametrize("name", ["pid", "pid_tdo", "pole_placement", "lqg"])
def test_integral_action_leaves_no_steady_state_motor_error(name):
    """Step reference and constant load torque: q_m = n r to rounding (the loop's rest state
    solves (I - A) X = B w exactly up to cond * eps); the load sits behind the spring twist
    tau_l/(n^2 K_el). A simulation reaches the same rest."""
    cfg = getattr(presets, name)(PLANT) if name.startswith("pid") else getattr(presets, name)()
    drive = servo.Drive(PLANT, cfg, Ts=TS)
    n, r, tau = PLANT.params["n"], 0.2, 3.0
    M = np.eye(drive.order) - drive.A
    X = np.linalg.solve(M, drive.B @ [r, tau])
    y = drive.C @ X + drive.D @ [r, tau]
    tol = np.linalg.cond(M) * EPS * n * r
    assert abs(y[0] - n * r) <= tol
    assert r - y[2] == pytest.approx(tau / (n * n * PLANT.params["Kel"]), rel=1e-9)
    N = int(3.0 / TS)
    out = drive.simulate(np.full(N, r), tau_load=np.full(N, tau))
    assert abs(out["q_m"][-1] - n * r) <= 1e-7 * n * r


def test_simulated_tdo_loop_leaves_the_sampled_high_pass_of_a_sinusoid():
    """Rigid model (P = P_n), a sampled sinusoidal load torque: the steady-state amplitude and
    phase of the motor velocity with the TDO over without it is G_f(z) (the report checks the
    frequency responses; this is the simulation, fitted after 2 s: transients below 1e-8)."""
    rigid = servo.rigid_servo()
    Tf, N = 8 * TS, int(2.5 / TS)
    t = np.arange(N) * TS
    late = t > 2.0
    fits = {}
    for tdo in (None, servo.TDO(Tf=Tf)):
        drive = servo.Drive(rigid, servo.PID(wcv=100.0, Ti=0.1, wcp=10.0, J=rigid.params["Jm"],
                                             tdo=tdo), Ts=TS)
        for wt in (20.0, 150.0):
            y = drive.simulate(np.zeros(N), tau_load=np.sin(wt * t))["w_m"][late]
            basis = np.column_stack([np.sin(wt * t[late]), np.cos(wt * t[late])])
            b, c = np.linalg.lstsq(basis, y, rcond=None)[0]
            fits[tdo is None, wt] = complex(b, c)       # y = Im(H e^{j w t}): b + jc = H
    for wt in (20.0, 150.0):
        ratio = fits[False, wt] / fits[True, wt]
        assert abs(ratio - design.tdo_high_pass(wt, Tf=Tf, Ts=TS)) <= 1e-7


def test_tdo_on_the_elastic_plant_leaves_the_locked_mode():
    """T_f -> 0: the loop's pole nearest the locked mode approaches it (notes, H_f)."""
    m = PLANT.modes()
    lock = complex(-m["zeta_z"] * m["w_z"], m["w_z"] * math.sqrt(1 - m["zeta_z"] ** 2))
    dist = []
    for k in (8, 1):
        z = servo.Drive(PLANT, presets.pid_tdo(PLANT, Tf=k * TS), Ts=TS).poles()
        s = np.log(z[np.abs(z) > 1e-9].astype(complex)) / TS
        dist.append(np.min(np.abs(s - lock)))
    assert dist[1] < 0.5 * dist[0] and dist[1] < 0.06 * m["w_z"]


def _riccati_iteration(A, B, Q, R, steps=20000):
    P = Q.copy()
    for _ in range(steps):
        S = R + B.T @ P @ B
        P_next = A.T @ P @ A - A.T @ P @ B @ np.linalg.solve(S, B.T @ P @ A) + Q
        if np.max(np.abs(P_next - P)) <= 1e-15 * np.max(np.abs(P)):
            return P_next
        P = P_next
    return P


def test_kalman_gain_equals_the_riccati_difference_equations_limit():
    dp = servo.discretize(PLANT, Ts=TS)
    g = design.kalman_gain(dp, torque_noise=presets.TORQUE_NOISE,
                           load_torque_noise=presets.LOAD_TORQUE_NOISE,
                           encoder_noise=presets.ENCODER_NOISE)
    C = np.eye(4)[:1]
    P = _riccati_iteration(dp.Ad.T, C.T, g["W"], np.array([[g["V"]]]))
    L = -(dp.Ad @ P @ C.T).ravel() / (C @ P @ C.T + g["V"]).item()
    assert np.max(np.abs(L - g["L"])) <= 1e-7 * np.max(np.abs(L))
    assert np.max(np.abs(np.linalg.eigvals(dp.Ad + np.outer(g["L"], C[0])))) < 1


def test_lq_gain_equals_the_riccati_difference_equations_limit():
    dp = servo.discretize(PLANT, Ts=TS)
    g = design.lq_gain(dp, Q=presets.LQ_Q, R=presets.LQ_R)
    F, G = design.augmented(dp)
    P = _riccati_iteration(F, G[:, None], np.diag(presets.LQ_Q) * TS,
                           np.array([[presets.LQ_R * TS]]))
    K = -(G @ P @ F) / (presets.LQ_R * TS + G @ P @ G)
    assert np.max(np.abs(K - np.r_[g["K"], g["kI"]])) <= 1e-7 * np.max(np.abs(K))


def test_feed_forward_is_the_notes_C1_C2():
    """C_1 = G_lm^-1 F^o and C_2 = G_k^-1 G_lm^-1 F^o with G_k = C (sI - (A + B K))^-1 B, for
    any K (here the discrete design's gains taken as continuous ones)."""
    ref = design.reference_model(PLANT, wf=presets.WF, Ts=TS)
    K = servo.Drive(PLANT, presets.pole_placement(), Ts=TS).controller.gains["K"]
    s = 1j * np.geomspace(1.0, 2000.0, 15)
    c1, c2 = ref.compensators(s, K)
    A, B = PLANT.A, PLANT.B_u

    def tf(M, row, v):
        return np.array([np.linalg.solve(x * np.eye(4) - M, B)[row] for x in v])
    glm = tf(A, 2, s) / tf(A, 0, s)
    fo = presets.WF ** 3 / (s + presets.WF) ** 3
    gk = tf(A + np.outer(B, K), 0, s)
    assert np.max(np.abs(c1 / (fo / glm) - 1)) <= 1e-9
    assert np.max(np.abs(c2 / (fo / glm / gk) - 1)) <= 1e-8


def test_feed_forward_tracking_error_is_first_order_in_Ts():
    """The load follows F^o r up to the sampling of u_d: halving Ts about halves the error
    (measured ratios 0.40 at 1 -> 0.5 ms, 0.45 at 0.5 -> 0.25 ms: first order)."""
    err = []
    for Ts in (1e-3, 5e-4):
        drive = servo.Drive(PLANT, presets.pole_placement(), Ts=Ts)
        N = int(0.4 / Ts)
        r = sms.Chain([sms.rectangular(T=0.1), sms.rectangular(T=0.05)], Ts=Ts).process(
            np.r_[0.0, np.full(N - 1, 0.3)])
        out = drive.simulate(r)
        ref = drive.controller.gains["reference_model"]
        xi, fo = np.zeros(ref.Phi.shape[0]), np.empty(N)
        for k in range(N):
            fo[k] = (ref.M @ xi)[2] / PLANT.params["n"]
            xi = ref.Phi @ xi + ref.Gam * r[k] * PLANT.params["n"]
        err.append(np.max(np.abs(out["q_l"] - fo)))
    assert err[0] < 1e-3 * 0.3 and 0.35 < err[1] / err[0] < 0.6


def test_notch_in_the_loop_is_the_library_notch():
    notch = sms.notch(wn=178.0, zeta=0.1, notch_pole_zeta=0.7)
    drive = servo.Drive(PLANT, presets.pid(PLANT, notch=notch), Ts=TS)
    g = drive.controller.gains
    x = np.random.default_rng(1).standard_normal(400)
    y = sms.Chain([notch], Ts=TS).process(x)
    assert np.max(np.abs(lfilter(g["notch_b"], g["notch_a"], x) - y)) <= 1e-12


def test_simulate_from_a_state_continues_the_run():
    drive = servo.Drive(PLANT, presets.lqg(), Ts=TS)
    r = np.linspace(0, 0.1, 300)
    whole = drive.simulate(r)
    X = np.zeros(drive.order)
    for k in range(150):
        X = drive.A @ X + drive.B @ [r[k], 0.0]
    tail = drive.simulate(r[150:], x0=X)
    assert np.max(np.abs(tail["q_l"] - whole["q_l"][150:])) <= 1e-12


@pytest.mark.parametrize("make, parameter", [
    (lambda: servo.elastic_servo(Jm=0.0), "Jm"),
    (lambda: servo.elastic_servo(Kel=float("nan")), "Kel"),
    (lambda: servo.elastic_servo(Del=-1.0), "Del"),
    (lambda: servo.rigid_servo(n=-2.0), "n"),
    (lambda: servo.servo_from_modes(wz=200.0, rho=1.0, zeta_z=1.0), "zeta_z"),
    (lambda: servo.discretize(PLANT, Ts=0.0), "Ts"),
    (lambda: servo.discretize(PLANT, Ts=1.0), "Ts"),
    (lambda: servo.Drive("plant", presets.lqg(), Ts=TS), "plant"),
    (lambda: servo.Drive(PLANT, "lqg", Ts=TS), "controller"),
    (lambda: servo.Drive(PLANT, servo.PID(wcv=10.0, Ti=0.1, wcp=20.0), Ts=TS), "wcp"),
    (lambda: servo.Drive(PLANT, servo.PID(wcv=10.0, Ti=-0.1, wcp=2.0), Ts=TS), "Ti"),
    (lambda: servo.Drive(PLANT, servo.PID(wcv=10.0, Ti=0.1, wcp=2.0, notch_at="x"), Ts=TS),
     "notch_at"),
    (lambda: servo.Drive(PLANT, servo.PID(wcv=10.0, Ti=0.1, wcp=2.0,
                                          notch=sms.shaper("zv", wn=100.0)), Ts=TS), "notch"),
    (lambda: servo.Drive(PLANT, servo.PID(wcv=10.0, Ti=0.1, wcp=2.0, tdo=servo.TDO(Tf=0.0)),
                         Ts=TS), "Tf"),
    (lambda: servo.Drive(PLANT, servo.PolePlacement(poles=(-1, -2, -3, -4), observer_poles=(
        -10, -20, -30, -40)), Ts=TS), "poles"),
    (lambda: servo.Drive(PLANT, servo.PolePlacement(poles=(-1, -2, -3, -4, 5), observer_poles=(
        -10, -20, -30, -40)), Ts=TS), "poles"),
    (lambda: servo.Drive(PLANT, servo.PolePlacement(poles=(-1, -2, -3, -4, -1 + 1j),
                                                    observer_poles=(-10, -20, -30, -40)), Ts=TS),
     "poles"),
    (lambda: servo.Drive(PLANT, servo.PolePlacement(poles=(-1, -2, -3, -4, -5), observer_poles=(
        -10, -10, -30, -40)), Ts=TS), "observer_poles"),
    (lambda: servo.Drive(PLANT, servo.LQG(Q=(1, 1, 1), R=1.0, torque_noise=1.0,
                                          load_torque_noise=1.0, encoder_noise=1e-6), Ts=TS), "Q"),
    (lambda: servo.Drive(PLANT, servo.LQG(Q=(1, 1, 1, 1, -1), R=1.0, torque_noise=1.0,
                                          load_torque_noise=1.0, encoder_noise=1e-6), Ts=TS), "Q"),
    (lambda: servo.Drive(PLANT, servo.LQG(Q=presets.LQ_Q, R=0.0, torque_noise=1.0,
                                          load_torque_noise=1.0, encoder_noise=1e-6), Ts=TS), "R"),
    (lambda: servo.Drive(PLANT, servo.LQG(Q=presets.LQ_Q, R=1.0, torque_noise=0.0,
                                          load_torque_noise=0.0, encoder_noise=1e-6), Ts=TS),
     "torque_noise"),
    (lambda: servo.Drive(PLANT, servo.LQG(Q=presets.LQ_Q, R=1.0, torque_noise=1.0,
                                          load_torque_noise=1.0, encoder_noise=0.0), Ts=TS),
     "encoder_noise"),
    (lambda: servo.Drive(PLANT, presets.lqg(wf=-1.0), Ts=TS), "wf"),
    (lambda: servo.Drive(PLANT, presets.lqg(), Ts=TS).simulate([0.0, float("inf")]), "reference"),
    (lambda: servo.Drive(PLANT, presets.lqg(), Ts=TS).simulate([0.0, 1.0], tau_load=[1.0]),
     "tau_load"),
    (lambda: servo.Drive(PLANT, presets.lqg(), Ts=TS).simulate([0.0], x0=[0.0]), "x0"),
    (lambda: servo.Drive(PLANT, presets.lqg(), Ts=TS).frequency_response(
        [1.0], input="u", output="q_l"), "input"),
])
def test_invalid_configurations_are_refused_naming_the_parameter(make, parameter):
    with pytest.raises(ParameterError) as exc:
        make()
    assert exc.value.parameter == parameter
    assert str(exc.value).startswith(parameter)
