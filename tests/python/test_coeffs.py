# SPDX-License-Identifier: Apache-2.0
"""smoothshaper.coeffs, the firmware path from Python: the C source it writes compiles with the
library in both precisions (strict C99), and the chain a C program builds from it with
sms_chain_init_coeffs outputs, bit for bit, what the Python Chain outputs for the same stages;
coefficients() holds the C values; bad names are refused; the shipped example's coefficients
are what the exporter writes today."""
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import smoothshaper as sms
from smoothshaper import coeffs
from smoothshaper.errors import ParameterError

ROOT = Path(__file__).resolve().parents[2]
TS = 1e-3
CC = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
N = 600

# Every family, on and off the sample grid, with and without direct taps.
CHAINS = {
    "readme": [sms.for_mode("harmonic", wn=100.0), sms.shaper("zv", wn=100.0, zeta=0.05)],
    "smoothers": [sms.rectangular(T=0.0234), sms.damped_harmonic(T=0.0377, sigma=-5.0),
                  sms.exponential(T=0.05, sigma=-20.0, timing="bounded"),
                  sms.harmonic(T=0.03, timing="paper")],
    "shapers": [sms.shaper("zvd", wn=90.0, zeta=0.05), sms.shaper("ei3", wn=160.0, zeta=0.02),
                sms.shaper("gmzv", wn=120.0, order=4, duration=1.2)],
    "notches": [sms.notch(wn=200.0, zeta=0.05), sms.exponential(T=0.02, sigma=-3.0),
                sms.notch(wn=300.0, discretization="tustin")],
    # an input smoother's table has a tap per sample (here 99, above any shaper's 45)
    "fir": [sms.shaper("si", wn=150.0, zeta=0.05, order=5, duration=1.5),
            sms.impulse_shaper(amplitudes=[0.3, 0.4, 0.3], times=[0.0013, 0.0061, 0.0112]),
            sms.input_smoother("smooth_ei", wn=2 * np.pi * 10.0, zeta=0.05)],
}

MAIN = r"""
#include <stdio.h>
#include <stdlib.h>
#include "smoothshaper/coeffs.h"
extern const sms_stage_coeffs chain_under_test[];
extern const size_t chain_under_test_stages;
static sms_memory_cell memory[20000];
int main(int argc, char **argv)
{
    sms_stage stages[SMS_CHAIN_MAX_STAGES];
    sms_chain chain;
    size_t n = chain_under_test_stages, need, i;
    (void)argc;
    if (n != (size_t)atoi(argv[1]))
        return 3;
    if (sms_chain_coeffs_memory_size(chain_under_test, n, &need) != SMS_OK || need > 20000
        || sms_chain_init_coeffs(&chain, stages, chain_under_test, n, memory, need) != SMS_OK)
        return 2;
    for (i = 0; i < %d; ++i) {
        sms_real x = (sms_real)((double)((i * 7919u) %% 1000u) / 100.0 - 5.0);
        sms_chain_step(&chain, &x);
        printf("%%a\n", (double)x);
    }
    return 0;
}
""" % N


def _input(precision):
    i = np.arange(N, dtype=np.uint64)
    x = ((i * 7919) % 1000).astype(np.float64) / 100.0 - 5.0
    return x.astype(np.float32).astype(np.float64) if precision == "float" else x


@pytest.fixture(scope="module")
def objects(tmp_path_factory):
    """The library compiled once per precision (object files)."""
    if CC is None:
        pytest.skip("needs a C compiler")
    out = {}
    sources = [str(p) for p in sorted((ROOT / "c" / "src").rglob("*.c"))]
    for precision in ("double", "float"):
        d = tmp_path_factory.mktemp(precision)
        flag = ["-DSMS_USE_FLOAT"] if precision == "float" else []
        # one compiler run per precision (the sources' names are unique across the areas)
        subprocess.run([CC, "-std=c99", "-O0", *flag, "-I", str(ROOT / "c" / "include"),
                        "-I", str(ROOT / "c" / "src"), "-c", *sources], check=True, cwd=d)
        out[precision] = (d, flag, sorted(str(p) for p in d.glob("*.o")))
    return out


@pytest.mark.parametrize("which", sorted(CHAINS))
def test_the_chain_built_from_the_c_source_is_the_python_chain(objects, tmp_path, which):
    stages = CHAINS[which]
    source = tmp_path / "coeffs.c"
    source.write_text(coeffs.c_source(stages, Ts=TS, name="chain_under_test"))
    (tmp_path / "main.c").write_text(MAIN)
    for precision, (d, flag, objs) in objects.items():
        exe = tmp_path / f"run_{precision}"
        subprocess.run([CC, "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", *flag,
                        "-I", str(ROOT / "c" / "include"), str(tmp_path / "main.c"),
                        str(source), *objs, "-lm", "-o", str(exe)], check=True)
        run = subprocess.run([str(exe), str(len(stages))], check=True, capture_output=True,
                             text=True)
        got = np.array([float.fromhex(v) for v in run.stdout.split()])
        want = sms.Chain(stages, Ts=TS, precision=precision).process(_input(precision))
        assert got.size == N
        assert np.array_equal(got, want), precision


def test_coefficients_are_the_c_values():
    (sm, zv) = coeffs.coefficients(CHAINS["readme"], Ts=TS, precision="float")
    assert sm["kind"] == "harmonic" and zv["kind"] == "zv"
    assert sm["identity"][2] == 4.0            # sizeof(sms_real) of the float build
    assert sm["length"] == sm["window"] + 1 and sm["correction_delay"] == [93, 94]
    assert np.float32(sm["gain"]) == sm["gain"]  # float values, held exactly
    assert [d for d, _ in zv["taps"]] == [0, 31, 32]
    assert abs(sum(g for _, g in zv["taps"]) - 1.0) < 1e-6
    (_, zv_double) = coeffs.coefficients(CHAINS["readme"], Ts=TS, precision="double")
    assert zv_double["identity"][2] == 8.0
    # the impulse response carries each tap after delay 0 as it is (tap 0 comes out as
    # 1 minus the others: the shaper subtracts the newest input, shaper.h)
    taps = sms.Chain([CHAINS["readme"][1]], Ts=TS).impulse_response(40)
    assert [g for d, g in zv_double["taps"] if d] == [taps[d] for d, _ in zv_double["taps"] if d]


@pytest.mark.parametrize("name", ["", "1x", "a-b", "x" * 57, None])
def test_a_bad_name_is_refused(name):
    with pytest.raises(ParameterError, match="^name must be a C identifier"):
        coeffs.c_source(CHAINS["readme"], Ts=TS, name=name)


def test_bad_stages_and_precision_are_refused():
    with pytest.raises(ParameterError, match="^wn"):
        coeffs.c_source([sms.shaper("zv", wn=5000.0)], Ts=TS)
    with pytest.raises(ParameterError, match="^precision"):
        coeffs.coefficients(CHAINS["readme"], Ts=TS, precision="half")


def test_the_shipped_firmware_example_is_current():
    """examples/firmware/chain_coeffs.c is what c_source writes for the README's chain."""
    shipped = (ROOT / "examples" / "firmware" / "chain_coeffs.c").read_text()
    body = shipped[shipped.index("/* Precomputed coefficients"):]
    assert body == coeffs.c_source(CHAINS["readme"], Ts=TS, name="axis_x")
    assert re.search(r"Written by: smoothshaper design .*--c-coeffs", shipped)
