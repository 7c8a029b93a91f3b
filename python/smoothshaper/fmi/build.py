# SPDX-License-Identifier: Apache-2.0
"""Build the FMUs with CMake and check their model descriptions (fmpy, fmutool)."""
from __future__ import annotations

import contextlib
import shutil
import subprocess
import sys
from pathlib import Path

from .. import _optional
from ..errors import ParameterError

__all__ = ["repo_root", "FMU_MODELS", "FMI_VERSIONS", "build_fmus", "fmpy_problems",
           "fmutool_problems"]


def repo_root() -> Path:
    """The source checkout this package runs from (where ``fmu/`` and ``c/`` are).

    Returns
    -------
    Path
        The folder three levels above this file (``python/smoothshaper/fmi/``).

    Raises
    ------
    OSError
        The path of this file cannot be resolved.
    """
    return Path(__file__).resolve().parents[3]


#: The FMUs and their model files under fmu/.
FMU_MODELS = {"SmoothShaper": "smoothshaper_model.c", "TrajectoryGenerator": "trajectory_model.c",
              "ElasticPlant": "elastic_plant_model.c", "MultiAxisGenerator": "multi_axis_model.c",
              "ServoDrive": "servo_drive_model.c"}


#: The FMI versions the FMUs are built for, and where each lands in the build folder.
FMI_VERSIONS = {"2.0": "fmus", "3.0": "fmus/3.0"}


def build_fmus(build_dir: Path, *, source_dir: Path | None = None,
               fmi_version: str = "2.0") -> dict[str, Path]:
    """Configure and build the FMUs with CMake.

    Parameters
    ----------
    build_dir : Path
        CMake build folder. A configured one (``CMakeCache.txt``) is reused with its options,
        so the FMUs of a full CMake build (C tests included) are taken as they are.
    source_dir : Path or None, keyword-only
        Source checkout (default: the repository this package is installed from).
    fmi_version : str, keyword-only
        ``"2.0"`` (default; ``fmus/<Model>.fmu``) or ``"3.0"`` (``fmus/3.0/<Model>.fmu``): both
        are built from the same model files.

    Returns
    -------
    dict of str to Path
        Model name -> FMU file, for the FMUs that were built.

    Raises
    ------
    ParameterError
        ``fmi_version`` is not ``"2.0"`` or ``"3.0"``.
    RuntimeError
        No FMU sources under ``source_dir``, or CMake not on PATH.
    subprocess.CalledProcessError
        CMake failed.
    """
    if fmi_version not in FMI_VERSIONS:
        raise ParameterError("fmi_version", f"fmi_version must be one of "
                             f"{', '.join(map(repr, FMI_VERSIONS))}, got {fmi_version!r}")
    source_dir = Path(source_dir) if source_dir else repo_root()
    if not (source_dir / "fmu" / "CMakeLists.txt").is_file():
        raise RuntimeError(f"no FMU sources under {source_dir} (run from a source checkout)")
    cmake = shutil.which("cmake")
    if cmake is None:
        raise RuntimeError("cmake is not on PATH: it is needed to build the FMUs")
    suffix = "_fmu" if fmi_version == "2.0" else "_fmi3_fmu"
    targets = [m + suffix for m, src in FMU_MODELS.items()
               if (source_dir / "fmu" / src).is_file()]
    Path(build_dir).mkdir(parents=True, exist_ok=True)
    # One build of a tree at a time: processes sharing it (parallel test workers, two jobs)
    # wait for each other instead of running CMake in the same tree at once.
    with _tree_lock(Path(build_dir)):
        # A configured tree (its own, or a full build with the C tests) is built as it is:
        # its FMU targets are then up to date or rebuilt, and its options are left alone.
        if not (Path(build_dir) / "CMakeCache.txt").is_file():
            subprocess.run([cmake, "-S", str(source_dir), "-B", str(build_dir),
                            "-DSMS_BUILD_TESTS=OFF", "-DSMS_BUILD_SHARED=OFF",
                            f"-DPython3_EXECUTABLE={sys.executable}"],
                           check=True, stdout=subprocess.DEVNULL)
        subprocess.run([cmake, "--build", str(build_dir), "-j2", "--target", *targets],
                       check=True, stdout=subprocess.DEVNULL)
    found = {m: Path(build_dir) / FMI_VERSIONS[fmi_version] / f"{m}.fmu" for m in FMU_MODELS}
    return {m: p for m, p in found.items() if p.is_file()}


@contextlib.contextmanager
def _tree_lock(build_dir: Path):
    """Hold an exclusive lock on ``build_dir/.build_fmus.lock`` (``fcntl.flock``; where
    ``fcntl`` is missing, as on Windows, no lock is taken)."""
    try:
        import fcntl
    except ImportError:
        yield
        return
    with open(build_dir / ".build_fmus.lock", "a") as f:
        fcntl.flock(f, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(f, fcntl.LOCK_UN)


def fmpy_problems(fmu: Path) -> list[str]:
    """fmpy's validation of the FMU's model description.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.

    Returns
    -------
    list of str
        The problems found (empty: none).

    Raises
    ------
    MissingDependency
        (an ImportError) fmpy is not installed (extra ``validate``).
    """
    _optional.require("fmpy", "checking an FMU's model description")
    from fmpy.validation import validate_fmu
    return list(validate_fmu(str(fmu)))


def fmutool_problems(fmu: Path) -> list[str]:
    """``fmutool -input FMU -check`` (fmu-manipulation-toolbox).

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.

    Returns
    -------
    list of str
        The problems reported (empty: it passed; one entry if fmutool is not installed).

    Raises
    ------
    OSError
        fmutool cannot be started.
    """
    exe = shutil.which("fmutool") or str(Path(sys.executable).with_name("fmutool"))
    if not Path(exe).is_file():
        return [str(_optional.missing("fmu_manipulation_toolbox", "fmutool -check"))]
    run_ = subprocess.run([exe, "-input", str(fmu), "-check"], capture_output=True, text=True)
    text = run_.stdout + run_.stderr
    problems = [line.strip() for line in text.splitlines() if "ERROR" in line or "WARNING" in line]
    if "No semantic error" not in text or "compliant" not in text:
        problems.append("fmutool did not report the FMU compliant")
    return problems
