# SPDX-License-Identifier: Apache-2.0
"""setuptools ``build_ext`` that compiles each C library source once per configuration.

The extensions ``_core`` (double), ``_core_float`` (float) and ``_kinematic_fastpath``
(double) all list the sources of ``c/src``. Built as plain extensions, the double sources
would be compiled twice, one after the other. Here the library sources of every extension are
grouped by what changes the object code (macros, include folders, flags); each group is
compiled once, the files in parallel, into a static archive; each extension then compiles
only its own sources (the cffi glue, the fast path) and links its group's archive, so the
fast path takes only the objects it calls.
"""
from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor

from setuptools.command.build_ext import build_ext


class BuildExtOnce(build_ext):
    """``build_ext`` with the library sources (those under ``library_dir``) compiled once per
    configuration, in parallel, and linked as static archives."""

    library_dir = ""  # set by with_library_dir(); the absolute c/src

    def finalize_options(self):
        super().finalize_options()
        # The extensions are independent: build them side by side, like the library files.
        if not self.parallel:
            self.parallel = os.cpu_count() or 1

    def _is_library_source(self, path: str) -> bool:
        full = os.path.abspath(path)
        return os.path.commonpath([full, self.library_dir]) == self.library_dir

    def build_extensions(self):
        groups: dict[tuple, list] = {}
        for ext in self.extensions:
            library = [s for s in ext.sources if self._is_library_source(s)]
            if not library:
                continue
            key = (tuple(map(tuple, ext.define_macros)), tuple(ext.include_dirs),
                   tuple(ext.extra_compile_args), tuple(library))
            groups.setdefault(key, []).append(ext)
        with ThreadPoolExecutor(max_workers=self.parallel) as pool:
            jobs = []
            for n, (key, exts) in enumerate(groups.items()):
                macros, include_dirs, flags, sources = key
                out = os.path.join(self.build_temp, "smoothshaper-c", str(n))
                for src in sources:
                    jobs.append((n, pool.submit(
                        self.compiler.compile, [src], output_dir=out, macros=list(macros),
                        include_dirs=list(include_dirs), extra_postargs=list(flags),
                        depends=exts[0].depends, debug=self.debug)))
            objects: dict[int, list[str]] = {}
            for n, job in jobs:
                objects.setdefault(n, []).extend(job.result())
        for n, exts in enumerate(groups.values()):
            out = os.path.join(self.build_temp, "smoothshaper-c", str(n))
            name = f"smoothshaper_c{n}"
            self.compiler.create_static_lib(objects[n], name, output_dir=out, debug=self.debug)
            for ext in exts:
                ext.sources = [s for s in ext.sources if not self._is_library_source(s)]
                # Before libm: the archive's objects call it.
                ext.libraries = [name] + list(ext.libraries)
                ext.library_dirs = [out] + list(ext.library_dirs)
        super().build_extensions()


def with_library_dir(library_dir: str) -> type[BuildExtOnce]:
    """The command class for the library sources under ``library_dir``."""
    return type("BuildExtOnce", (BuildExtOnce,), {"library_dir": os.path.abspath(library_dir)})
