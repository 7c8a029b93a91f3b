# SPDX-License-Identifier: Apache-2.0
"""cffi builder for ``smoothshaper._core`` (double) and ``smoothshaper._core_float`` (float).

API mode, out of line: the extension compiles every C source of ``c/src`` (all its areas:
``core/``, ``filter/``, ``identify/``, ``trajectory/``) straight into the module,
so ``pip install .`` needs only a C compiler. The cdef is generated from the public headers,
never written by hand: the C preprocessor expands ``c/include/smoothshaper/smoothshaper.h``
(``SMS_API`` defined empty, the C library headers replaced by empty stand-ins because cffi
knows ``size_t`` and friends), pycparser re-emits the declarations (function bodies of
``static inline`` helpers dropped), and the ``#define`` constants of the headers are added
(``#define NAME ...`` for integers, ``static const double NAME;`` for floating values) so the
compiler fills in their values. A function added to any
public header therefore appears in Python at the next build.

Run ``python python/smoothshaper/_build_core.py`` to build in place for a quick try; setup.py
uses :data:`ffibuilder` and :data:`ffibuilder_float` through ``cffi_modules``.
"""
from __future__ import annotations

import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

from cffi import FFI

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
INCLUDE_DIR = os.path.join(ROOT, "c", "include")
SRC_DIR = os.path.join(ROOT, "c", "src")
UMBRELLA = os.path.join(INCLUDE_DIR, "smoothshaper", "smoothshaper.h")

# C library headers a public header may include; each becomes an empty file for the
# preprocessor run (cffi declares the standard types itself).
_STD_HEADERS = ("stddef.h", "stdint.h", "stdbool.h", "limits.h", "float.h", "math.h",
                "string.h", "stdlib.h")
# Object-like macros with a value (function-like macros and SMS_API are not constants).
_DEFINE = re.compile(r"^\s*#\s*define\s+(SMS_[A-Z0-9_]+)[ \t]+(\S.*?)\s*(?:/[*/].*)?$")
_FLOAT_LITERAL = re.compile(r"(?<![xX0-9A-Fa-f])(?:\d+\.\d*|\.\d+|\d+[eE][-+]?\d+)"
                            r"|\b0[xX][0-9A-Fa-f.]+[pP][-+]?\d+")


def _compiler() -> list[str]:
    cc = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if not cc:
        raise RuntimeError("smoothshaper needs a C compiler (set CC, or install gcc or clang)")
    return cc.split()


def _preprocess(defines: list[str]) -> str:
    with tempfile.TemporaryDirectory() as fake_std:
        for name in _STD_HEADERS:
            open(os.path.join(fake_std, name), "w").close()
        # SMS_NO_PRECISION_SUFFIX: declare the usual names (precision.h); the compiled module
        # includes the headers without it and so calls the float build's suffixed functions.
        cmd = _compiler() + ["-E", "-P", "-nostdinc", "-I", fake_std, "-I", INCLUDE_DIR,
                             "-DSMS_NO_PRECISION_SUFFIX",
                             "-DSMS_API=", "-D__attribute__(x)=", "-D__extension__=",
                             "-D__inline=inline", "-D__restrict="]
        cmd += [f"-D{d}" for d in defines] + [UMBRELLA]
        out = subprocess.run(cmd, check=True, capture_output=True, text=True)
    return out.stdout


def _declarations(source: str) -> str:
    """Re-emit the preprocessed header as plain declarations: typedefs, structs, enums and
    prototypes; inline function bodies are dropped (non-static ones keep their prototype)."""
    import pycparser
    from pycparser import c_ast
    from pycparser.c_generator import CGenerator

    # pycparser needs the standard typedef names to parse; cffi knows them natively.
    std_types = ("size_t", "ptrdiff_t", "int8_t", "int16_t", "int32_t", "int64_t",
                 "uint8_t", "uint16_t", "uint32_t", "uint64_t", "intptr_t", "uintptr_t")
    prelude = "".join(f"typedef int {t};\n" for t in std_types) + "typedef _Bool bool;\n"
    ast = pycparser.CParser().parse(prelude + source, "smoothshaper.h")
    gen = CGenerator()
    lines = []
    for node in ast.ext[len(std_types) + 1:]:
        if isinstance(node, c_ast.FuncDef):
            if "static" in (node.decl.storage or []):
                continue
            node = node.decl
        if isinstance(node, c_ast.Decl) and "inline" in (node.funcspec or []):
            node.funcspec = [f for f in node.funcspec if f != "inline"]
            if "static" in (node.storage or []):
                continue
        if isinstance(node, c_ast.Pragma):
            continue
        lines.append(gen.visit(node) + ";")
    return "\n".join(lines) + "\n"


def _constants() -> str:
    """cdef lines for the headers' constants: integers as ``#define NAME ...`` (the compiler
    supplies the value), floating ones as ``static const double NAME;``."""
    lines: dict[str, str] = {}
    for header in sorted(glob.glob(os.path.join(INCLUDE_DIR, "smoothshaper", "*.h"))):
        with open(header, encoding="utf-8") as f:
            for line in f:
                m = _DEFINE.match(line)
                if not m or m.group(1) == "SMS_API" or m.group(1) in lines:
                    continue
                name, value = m.groups()
                lines[name] = (f"static const double {name};\n" if _FLOAT_LITERAL.search(value)
                               else f"#define {name} ...\n")
    return "".join(lines.values())


def cdef_text(defines: list[str] | None = None) -> str:
    """The cdef for the given preprocessor defines (e.g. ``["SMS_USE_FLOAT"]``)."""
    return _constants() + _declarations(_preprocess(defines or []))


def _sources() -> list[str]:
    # setuptools wants paths relative to the setup.py directory (the repository root).
    paths = sorted(glob.glob(os.path.join(SRC_DIR, "**", "*.c"), recursive=True))
    if not paths:
        raise RuntimeError(f"no C sources found in {SRC_DIR}")
    return [os.path.relpath(p, ROOT) for p in paths]


def _headers() -> list[str]:
    """Every header a build reads (public and internal): a change rebuilds the modules."""
    return [os.path.relpath(p, ROOT) for p in sorted(
        glob.glob(os.path.join(INCLUDE_DIR, "smoothshaper", "*.h"))
        + glob.glob(os.path.join(SRC_DIR, "**", "*.h"), recursive=True))]


# Binding glue compiled into each module (not part of the C library): Chain.process and
# TunableChain.process in one call. It checks every input sample first (the state stays
# untouched on a bad one), then filters float64 to float64; the float build converts through a
# small block on the stack, so the float path makes no full-size copy of the signal.
_GLUE_CDEF = """
ptrdiff_t smspy_chain_process_f64(sms_chain *chain, const double *in, double *out, size_t n);
ptrdiff_t smspy_tunable_chain_process_f64(sms_tunable_chain *chain, const double *in,
                                          double *out, size_t n);
"""
_GLUE_SOURCE = r"""
#include <float.h>
#include <stddef.h>
#include "smoothshaper/smoothshaper.h"

/* Index of the first sample that is NaN/Inf or beyond limit (the chain's input range), or -1. */
static ptrdiff_t smspy_first_bad_sample(const double *in, size_t n, double limit)
{
    size_t i;
    for (i = 0; i < n; ++i)
        if (!(in[i] >= -limit && in[i] <= limit))
            return (ptrdiff_t)i;
    return -1;
}

typedef void (*smspy_process_fn)(void *chain, const sms_real *in, sms_real *out, size_t n);

/* -1 after filtering all n samples through process (in == out allowed); else the index of the
 * first bad one, and nothing filtered. */
static ptrdiff_t smspy_process_f64(void *chain, smspy_process_fn process, double limit,
                                   const double *in, double *out, size_t n)
{
    const ptrdiff_t bad = smspy_first_bad_sample(in, n, limit);
    if (bad >= 0)
        return bad;
#ifdef SMS_USE_FLOAT
    float block[1024];
    while (n > 0) {
        size_t m = n < 1024 ? n : 1024, i;
        for (i = 0; i < m; ++i)
            block[i] = (float)in[i];
        process(chain, block, block, m);
        for (i = 0; i < m; ++i)
            out[i] = (double)block[i];
        in += m;
        out += m;
        n -= m;
    }
#else
    process(chain, in, out, n);
#endif
    return -1;
}

static void smspy_chain_process(void *chain, const sms_real *in, sms_real *out, size_t n)
{
    sms_chain_process((sms_chain *)chain, in, out, n);
}

static void smspy_tunable_chain_process(void *chain, const sms_real *in, sms_real *out, size_t n)
{
    sms_tunable_chain_process((sms_tunable_chain *)chain, in, out, n);
}

static ptrdiff_t smspy_chain_process_f64(sms_chain *chain, const double *in, double *out, size_t n)
{
    return smspy_process_f64(chain, smspy_chain_process, sms_chain_input_max(chain), in, out, n);
}

/* The input range is that of the chain before the block: a retune (which may narrow it) only
 * happens between calls. */
static ptrdiff_t smspy_tunable_chain_process_f64(sms_tunable_chain *chain, const double *in,
                                                 double *out, size_t n)
{
    return smspy_process_f64(chain, smspy_tunable_chain_process,
                             sms_tunable_chain_input_max(chain), in, out, n);
}
"""


# Symbols private to each module (see make_builder); no debug information, which nothing reads
# and which costs about a sixth of each compile.
_COMPILE_ARGS = [] if sys.platform == "win32" else ["-fvisibility=hidden", "-g0"]


def make_builder(module: str, defines: list[str]) -> FFI:
    ffi = FFI()
    ffi.cdef(cdef_text(defines) + _GLUE_CDEF)
    macros = [(d, None) for d in defines]
    ffi.set_source(
        module,
        _GLUE_SOURCE,
        sources=_sources(),
        # Rebuild when any header changes, not only when a .c file does.
        depends=_headers(),
        include_dirs=[os.path.relpath(INCLUDE_DIR, ROOT), os.path.relpath(SRC_DIR, ROOT)],
        define_macros=macros,
        libraries=[] if sys.platform == "win32" else ["m"],
        # Keep the C symbols private to each module: _core and _core_float define the same
        # sms_* names, and an FMU loaded in the same process defines them too.
        extra_compile_args=_COMPILE_ARGS,
    )
    return ffi


def kinematic_fastpath_extension():
    """The CPython extension ``smoothshaper._kinematic_fastpath`` (design.kinematic's fast
    path, ``_kinematic_fastpath.c``): the C design and the Stage objects in one C function,
    which cffi cannot return. It lists the same C sources as ``_core``; setup.py's build_ext
    (``_build_library``) compiles them once for both, and links only the objects it calls."""
    from setuptools import Extension
    return Extension(
        "smoothshaper._kinematic_fastpath",
        sources=[os.path.relpath(os.path.join(HERE, "_kinematic_fastpath.c"), ROOT)]
        + _sources(),
        depends=_headers(),
        include_dirs=[os.path.relpath(INCLUDE_DIR, ROOT), os.path.relpath(SRC_DIR, ROOT)],
        libraries=[] if sys.platform == "win32" else ["m"],
        extra_compile_args=_COMPILE_ARGS,
    )


ffibuilder = make_builder("smoothshaper._core", [])
ffibuilder_float = make_builder("smoothshaper._core_float", ["SMS_USE_FLOAT"])

if __name__ == "__main__":
    # Quick in-place build: the modules land next to this file.
    os.chdir(ROOT)
    for builder in (ffibuilder, ffibuilder_float):
        builder.compile(tmpdir=os.path.join(ROOT, "build-python-package", "cffi"), verbose=True)
