# SPDX-License-Identifier: Apache-2.0
"""The win64 binary of SmoothShaper.fmu (cross-compiled with mingw-w64) run under wine by a
minimal FMI 2.0 importer (tests/fmu/fmi2_host.c, cross-compiled too): same output as the NumPy
reference, so as the linux64 binary.

The importer is ours rather than fmpy's TCP remoting: the remoting client waits for a server
that wine may never start, so every wine failure looked like a stall, with nothing said about
why. Run directly, wine's own messages reach the failure report. The same importer built
natively must reproduce fmpy bit for bit on the linux64 binary, which checks that it imports as
fmpy does."""
from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
from smoothshaper import fmi  # noqa: E402
from smoothshaper.stages import rectangular, shaper  # noqa: E402
from test_fmu_smoothshaper import fmus  # noqa: E402,F401

HOST = Path(__file__).resolve().parents[1] / "fmu" / "fmi2_host.c"
FMI_HEADERS = Path(fmpy.__file__).parent / "c-code"
WINE_DIRS = ("/usr/lib/wine", "/usr/lib64/wine", "/opt/wine-stable/bin")
MINGW = "x86_64-w64-mingw32-gcc"
TS, T, WN = 1e-3, 0.012, 180.0   # T/Ts integer: the test is about the binary, not timing
START = {"Ts": TS, "stage[0].T": T, "stage[1].wn": WN}


def wine_path() -> str | None:
    """PATH with a directory holding wine64, or None without wine."""
    if shutil.which("wine64"):
        return os.environ["PATH"]
    for d in WINE_DIRS:
        if os.access(os.path.join(d, "wine64"), os.X_OK):
            return d + os.pathsep + os.environ["PATH"]
    return None


def compile_host(compiler: str, exe: Path, *libs: str) -> None:
    """Build tests/fmu/fmi2_host.c against fmpy's FMI 2.0 headers."""
    cmd = [compiler, "-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", f"-I{FMI_HEADERS}",
           str(HOST), "-o", str(exe), *libs]
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 0, f"{' '.join(cmd)}\n{r.stdout}{r.stderr}"


def host_args(unzipdir: str, binary: str, tmp: Path, t, u, to_host=str) -> list[str]:
    """The host's arguments: the binary, the GUID, the files, and the value references."""
    md = fmpy.read_model_description(unzipdir)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    np.savetxt(tmp / "in.txt", np.column_stack([t, u]), fmt="%.17g")
    return [to_host(binary), md.guid, to_host(tmp / "in.txt"), to_host(tmp / "out.txt"),
            str(vr["u"]), str(vr["y"])] + [f"{vr[k]}={v!r}" for k, v in START.items()]


def run(cmd: list[str], env=None, timeout=300) -> None:
    """Run cmd; a failure or a timeout reports everything it printed."""
    try:
        r = subprocess.run(cmd, env=env, timeout=timeout, capture_output=True, text=True)
    except subprocess.TimeoutExpired as e:
        pytest.fail(f"{cmd[0]} did not finish in {timeout} s:\n{e.stdout}\n{e.stderr}")
    assert r.returncode == 0, f"{' '.join(cmd)} exited with {r.returncode}:\n{r.stdout}{r.stderr}"


@pytest.fixture(scope="module")
def case(fmus, tmp_path_factory):  # noqa: F811
    """The unpacked SmoothShaper FMU, its input, and the NumPy reference's output."""
    unzipdir = fmpy.extract(str(fmus["SmoothShaper"]), str(tmp_path_factory.mktemp("ss")))
    t = fmi.communication_points(step=TS, stop_time=0.08)
    u = fmi.test_input(t)
    ref = fmi.expected_output([rectangular(T=T), shaper("zv", wn=WN)], t, u, Ts=TS)
    return unzipdir, t, u, ref


def test_native_host_imports_as_fmpy_does(case, tmp_path):
    if shutil.which("cc") is None:
        pytest.skip("no native C compiler (cc)")
    unzipdir, t, u, ref = case
    exe = tmp_path / "fmi2_host"
    compile_host("cc", exe, "-ldl")
    binary = Path(unzipdir) / "binaries" / "linux64" / "SmoothShaper.so"
    run([str(exe), *host_args(unzipdir, str(binary), tmp_path, t, u)])
    y = np.loadtxt(tmp_path / "out.txt")
    sig = np.zeros(len(t), dtype=[("time", float), ("u", float)])
    sig["time"], sig["u"] = t, u
    r = fmpy.simulate_fmu(unzipdir, stop_time=float(t[-1]), output_interval=TS, input=sig,
                          output=["y"], start_values=START)
    np.testing.assert_array_equal(y, r["y"])          # %.17g round-trips a double exactly
    assert np.max(np.abs(y - ref)) <= fmi.REL_TOL * np.max(np.abs(ref))


def test_win64_binary_runs_under_wine(case, tmp_path):
    unzipdir, t, u, ref = case
    dll = Path(unzipdir) / "binaries" / "win64" / "SmoothShaper.dll"
    if not dll.exists():
        pytest.skip(f"no win64 binary: {MINGW} was not found when the FMU was built "
                    "(scripts/install-cross-tools.sh installs it)")
    if shutil.which(MINGW) is None:
        pytest.skip(f"{MINGW} is not installed (scripts/install-cross-tools.sh installs it)")
    path = wine_path()
    if path is None:
        pytest.skip("wine64 is not installed (scripts/install-cross-tools.sh installs it)")
    exe = tmp_path / "fmi2_host.exe"
    compile_host(MINGW, exe)
    # A prefix of our own: nothing depends on the user's ~/.wine (its owner, its state).
    env = {**os.environ, "PATH": path, "WINEDEBUG": "-all", "WINEPREFIX": str(tmp_path / "wine")}
    env.pop("DISPLAY", None)   # no window to open: wine must not wait for an X server

    def windows(p) -> str:      # wine maps the Unix root to drive Z:
        return "Z:" + str(Path(p).resolve()).replace("/", "\\")

    try:
        # First the importer alone (it prints its usage and exits 1): this also creates the
        # prefix. A wine that cannot start a program at all is a broken tool, not a broken
        # binary: skipped with what wine said, as a missing wine is.
        try:
            probe = subprocess.run(["wine64", windows(exe)], env=env, timeout=600,
                                   capture_output=True, text=True)
            said = probe.stdout + probe.stderr
        except subprocess.TimeoutExpired as e:
            said = f"no answer in 600 s: {e.stdout} {e.stderr}"
        if "usage: fmi2_host" not in said:
            pytest.skip(f"wine64 cannot run a win64 program on this machine: {said[-1000:]}")
        run(["wine64", windows(exe), *host_args(unzipdir, str(dll), tmp_path, t, u, windows)],
            env=env, timeout=600)
    finally:
        subprocess.run(["wineserver", "-k"], env=env, capture_output=True, timeout=60)
    y = np.loadtxt(tmp_path / "out.txt")
    assert y.shape == ref.shape
    assert np.max(np.abs(y - ref)) <= fmi.REL_TOL * np.max(np.abs(ref))
