# SPDX-License-Identifier: Apache-2.0
"""The cffi extension exposes the whole public C API, generated from the headers."""
import glob
import os
import re

import pytest

from smoothshaper import _build_core
from smoothshaper.filters import _backend

HEADERS = sorted(glob.glob(os.path.join(_build_core.INCLUDE_DIR, "smoothshaper", "*.h")))
# A public function: "SMS_API <return type> name(" possibly with the name on the same line.
API_FUNCTION = re.compile(r"SMS_API\s+[^;(]*?\b(sms_\w+)\s*\(")
INT_DEFINE = re.compile(r"^\s*#\s*define\s+(SMS_[A-Z0-9_]+)\s+(\d+)\s*$", re.M)


def _public_functions():
    names = set()
    for path in HEADERS:
        with open(path, encoding="utf-8") as f:
            names.update(API_FUNCTION.findall(f.read()))
    return sorted(names)


def test_headers_are_found():
    assert os.path.basename(_build_core.UMBRELLA) == "smoothshaper.h"
    assert len(_public_functions()) > 20


@pytest.mark.parametrize("precision", ["double", "float"])
def test_every_public_function_is_bound(precision):
    ffi, lib = _backend(precision)
    missing = [name for name in _public_functions() if not hasattr(lib, name)]
    assert missing == []


@pytest.mark.parametrize("precision, size", [("double", 8), ("float", 4)])
def test_real_type_matches_precision(precision, size):
    ffi, _ = _backend(precision)
    assert ffi.sizeof("sms_real") == size


def test_integer_constants_match_headers():
    _, lib = _backend("double")
    for path in HEADERS:
        with open(path, encoding="utf-8") as f:
            for name, value in INT_DEFINE.findall(f.read()):
                assert getattr(lib, name) == int(value), name


def test_every_object_like_define_is_bound():
    _, lib = _backend("double")
    names = set()
    for path in HEADERS:
        with open(path, encoding="utf-8") as f:
            names.update(m.group(1) for m in map(_build_core._DEFINE.match, f) if m)
    names.discard("SMS_API")
    assert names and [n for n in sorted(names) if not hasattr(lib, n)] == []
    assert lib.SMS_SHAPER_MAX_IMPULSES == lib.SMS_SHAPER_MAX_ORDER + 1   # expression macro


def test_cdef_is_generated_from_the_preprocessed_header():
    text = _build_core.cdef_text([])
    assert "typedef double sms_real;" in text
    assert "typedef float sms_real;" in _build_core.cdef_text(["SMS_USE_FLOAT"])
    # Preprocessor leftovers cffi cannot parse must be gone.
    assert "SMS_API" not in text and "#include" not in text and "__attribute__" not in text


def test_status_strings_cover_every_status():
    ffi, lib = _backend("double")
    statuses = [getattr(lib, n) for n in dir(lib) if n.startswith("SMS_ERR_")]
    assert len(statuses) >= 20
    texts = {ffi.string(lib.sms_status_string(s)).decode() for s in statuses}
    assert len(texts) == len(statuses)          # distinct, so an error says which argument
    assert ffi.string(lib.sms_status_string(lib.SMS_OK)) == b"ok"


def test_kind_names_match_python_kinds():
    from smoothshaper.stages import KINDS
    ffi, lib = _backend("double")
    assert [ffi.string(lib.sms_kind_name(i)).decode() for i in range(lib.SMS_KIND_COUNT)] == list(KINDS)


def test_raise_for_status_names_the_parameter():
    from smoothshaper.filters import ParameterError, raise_for_status
    _, lib = _backend("double")
    raise_for_status(lib.SMS_OK, context="nothing")
    with pytest.raises(ParameterError, match=r"^zeta must") as info:
        raise_for_status(lib.SMS_ERR_ZETA, context="a test", value=1.5)
    assert info.value.parameter == "zeta" and info.value.status == lib.SMS_ERR_ZETA
    assert "1.5" in str(info.value) and "a test" in str(info.value)
    with pytest.raises(ParameterError, match=r"^jmax invalid") as info:
        raise_for_status(lib.SMS_ERR_LIMIT, context="design", parameter="jmax")


def test_every_status_maps_to_the_parameter_it_names():
    from smoothshaper.filters import _STATUS_PARAMETER
    _, lib = _backend("double")
    expected = {
        "SMS_ERR_SAMPLE_PERIOD": "Ts", "SMS_ERR_DURATION": "T", "SMS_ERR_DURATION_BELOW_TS": "T",
        "SMS_ERR_SIGMA": "sigma", "SMS_ERR_WN": "wn", "SMS_ERR_ZETA": "zeta",
        "SMS_ERR_MULTIPLE": "k", "SMS_ERR_EVEN_MULTIPLE": "k", "SMS_ERR_ORDER": "order",
        "SMS_ERR_KIND": "kind", "SMS_ERR_NOTCH_DAMPING": "notch_pole_zeta",
        "SMS_ERR_TOLERANCE": "tolerance", "SMS_ERR_ABOVE_NYQUIST": "wn",
        "SMS_ERR_STATE": "state", "SMS_ERR_BANDWIDTH": "bandwidth", "SMS_ERR_LIMIT": "limits",
        "SMS_ERR_RECORD": "x",
    }
    for name, parameter in expected.items():
        assert _STATUS_PARAMETER[getattr(lib, name)] == parameter, name
    statuses = {getattr(lib, n) for n in dir(lib) if n.startswith("SMS_ERR_")}
    assert statuses <= set(_STATUS_PARAMETER)          # a new status needs a parameter name


def test_declarations_drop_inline_bodies_and_keep_prototypes():
    text = _build_core._declarations(
        "typedef struct s { size_t n; double x[3]; } s;\n"
        "static inline int helper(int a) { return a + 1; }\n"
        "int exported(const s *p, size_t n);\n"
        "inline double scaled(double v) { return 2.0 * v; }\n")
    assert "helper" not in text
    assert "int exported(const s *p, size_t n);" in text
    assert "double scaled(double v);" in text and "return" not in text
    assert "double x[3];" in text and "typedef int" not in text
