# SPDX-License-Identifier: Apache-2.0
"""Messages for saved C states of another configuration.

Every saved state of the C core starts with its configuration identity (``config.h``,
``trajectory.h``, ``multi_generator.h``): the state tag, the format version, the precision
(``sizeof(sms_real)``), the kind of object, ``Ts``, then the object's own fields. The C core
refuses a state whose identity differs from the object's with a status naming the field;
:func:`mismatch` turns the two identities into the message the Python wrappers raise, e.g.
``"state is from vmax=2.0 (this Generator: vmax=1.0)"``.
"""
from __future__ import annotations

import textwrap
import types

import numpy as np

#: The common head of every identity, in order.
HEAD_FIELDS = ("tag", "version", "precision", "kind", "Ts")
#: Kind field of the objects that are not stages (``SMS_STATE_KIND_...``).
OBJECT_KINDS = {100.0: "Generator", 101.0: "BSpline", 102.0: "MultiAxisGenerator"}
_PRECISIONS = {8.0: "double", 4.0: "float"}


def _whole(value: float) -> bool:
    """``value`` is a finite integral number (int() of NaN or inf raises)."""
    return bool(np.isfinite(value)) and value == int(value)


def _show(field: str, value: float, choices: dict[str, tuple[str, ...]]):
    """A field's value for the message: names for enumerations, ints for counts."""
    base = field.split("[")[0]
    if field == "precision":
        return repr(_PRECISIONS.get(value, value))
    if field == "kind":
        if value in OBJECT_KINDS:
            return f"a {OBJECT_KINDS[value]}"
        from .stages import KINDS
        return (f"a stage of kind {KINDS[int(value)]!r}"
                if _whole(value) and 0 <= value < len(KINDS) else f"kind={float(value)!r}")
    if base in choices:
        names = choices[base]
        return (repr(names[int(value)]) if _whole(value) and 0 <= value < len(names)
                else repr(float(value)))
    if base in ("degree", "axes", "n_stages") and _whole(value):
        return str(int(value))
    return repr(float(value))


def mismatch(saved: np.ndarray, mine, fields: tuple[str, ...], owner: str,
             choices: dict[str, tuple[str, ...]] | None = None) -> str | None:
    """Why ``saved`` is not a state of the object whose identity is ``mine``, or None.

    Parameters
    ----------
    saved : ndarray of float64, shape (n,)
        The state offered to ``set_state``.
    mine : sequence of float
        The object's identity (``HEAD_FIELDS`` then ``fields``).
    fields : tuple of str
        Names of the object's own identity fields, after the head.
    owner : str
        The class name for the message (``"Generator"``).
    choices : dict, optional
        For enumerated fields, the names of their values (``{"profile": PROFILES}``).

    Returns
    -------
    str or None
        ``"state is from vmax=2.0 (this Generator: vmax=1.0)"`` for the first field that
        differs (the order the C core checks them in), None when the identity matches.
    """
    mine = np.asarray(mine, dtype=np.float64)
    names = HEAD_FIELDS + tuple(fields)
    choices = choices or {}
    if saved.size < 2 or saved[0] != mine[0]:
        return (f"state is not a saved {owner} state: it does not start with the state tag "
                f"{float(mine[0])!r} (was it saved by {owner}.get_state?)")
    if saved[1] != mine[1]:
        return (f"state has format version {float(saved[1])!r}, this library reads version "
                f"{float(mine[1])!r}")
    for i in range(2, mine.size):
        if i >= saved.size:
            return f"state is truncated inside its configuration identity ({saved.size} values)"
        if not saved[i] == mine[i]:
            name = names[i]
            theirs, ours = _show(name, saved[i], choices), _show(name, mine[i], choices)
            if name == "kind":
                return f"state is from {theirs} (this is a {owner})"
            return f"state is from {name}={theirs} (this {owner}: {name}={ours})"
    return None


def restore(owner: str, ffi, lib, setter: str, c_obj, state, fields: tuple[str, ...],
            choices: dict[str, tuple[str, ...]] | None = None) -> None:
    """``set_state`` of a C-backed object: load ``state`` through ``lib.<setter>(c_obj, ptr, n)``.

    The object's identity is read from ``c_obj.identity`` (its C struct field).

    Raises
    ------
    ParameterError
        Naming ``state``: the field that differs for a state of another configuration (see
        :func:`mismatch`), else why the C core refused it; the object is then untouched.
    """
    from ._checks import real_array
    from .errors import ParameterError
    s = np.ascontiguousarray(real_array("state", state, ndim=1), dtype=np.float64)
    # every saved value is finite (NaN would come out of every later sample); a non-finite
    # identity field is a state of another configuration, which the message below names
    bad = np.flatnonzero(~np.isfinite(s[len(c_obj.identity):]))
    if bad.size:
        i = int(bad[0]) + len(c_obj.identity)
        raise ParameterError("state", f"state must be finite: state[{i}] = {float(s[i])!r}")
    st = getattr(lib, setter)(c_obj, ffi.from_buffer("double[]", s), s.size)
    if st == 0:
        return
    why = mismatch(s, list(c_obj.identity), fields, owner, choices)
    if why is not None:
        raise ParameterError("state", why, st)
    if lib.SMS_ERR_STATE_STAGES <= st <= lib.SMS_ERR_STATE_FORMAT:
        # the object's own identity matches: a vibration stage saved by another configuration
        text = ffi.string(lib.sms_status_string(st)).decode()
        raise ParameterError("state", f"state does not match this {owner}: a vibration stage "
                             f"differs ({text})", st)
    raise ParameterError("state", f"state does not match this {owner} (wrong length, "
                         "non-finite values, counts out of range, or a motion beyond its limits)",
                         st)


# The docstrings of SavedState's methods, one paragraph a line, wrapped for each class.
_GET_STATE_DOC = """The dynamic state, tagged with the configuration it belongs to (a copy); \
:meth:`set_state` on this or an identically configured {what} continues bit-exactly.

Returns
-------
ndarray of float64, shape (n,)
    {layout}
"""

_SET_STATE_DOC = """Restore a state saved by :meth:`get_state`.

Parameters
----------
state : array_like of float, shape (n,)
    A state of this {what} or of an identically configured one: same {same}, ``Ts`` and \
``precision`` (compared exactly). ``q0`` is not part of it: it is only where :meth:`reset` \
returns to.

Raises
------
ParameterError
    Naming ``state`` if it comes from another configuration (the message says which field \
differs, e.g. {example}), has the wrong size, non-finite fields, counts out of range, or a \
motion beyond this {what}'s limits; then nothing is changed.
"""


def _wrapped(text: str) -> str:
    """Each line of ``text`` filled to 88 columns, continuation lines at its indent."""
    out = []
    for line in text.splitlines():
        indent = line[:len(line) - len(line.lstrip())]
        out.append(textwrap.fill(line, 88, subsequent_indent=indent,
                                   break_on_hyphens=False) if line else line)
    return "\n".join(out) + "\n"


class SavedState:
    """``get_state`` / ``set_state`` of a C-backed generator (one implementation for all).

    A subclass holds its C object in ``self._gen`` (with ``self._ffi``, ``self._lib``, and the
    object's lock ``self._lock``, :mod:`smoothshaper._shared`) and
    sets, as class attributes: ``_STATE_C``, the C prefix (``"sms_generator"``: the functions
    ``<prefix>_state_count``, ``_get_state``, ``_set_state``); ``_STATE_FIELDS`` and
    ``_STATE_CHOICES``, its identity fields after the head and the names of enumerated ones
    (:func:`mismatch`); and for the two docstrings ``_STATE_DOC``: ``what`` (``"generator"``),
    ``layout`` (the saved values, in order), ``same`` (the configuration that must match) and
    ``example`` (a mismatch message); optionally ``_STATE_ALIASES``, old names of the two.
    """

    _STATE_C: str
    _STATE_FIELDS: tuple[str, ...]
    _STATE_CHOICES: dict[str, tuple[str, ...]]
    _STATE_DOC: dict[str, str]

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        doc = cls.__dict__.get("_STATE_DOC")
        if doc is None:
            return
        for name, template in (("get_state", _GET_STATE_DOC), ("set_state", _SET_STATE_DOC)):
            shared = getattr(SavedState, name)
            # a copy of the shared function, so that each class documents its own layout
            method = types.FunctionType(shared.__code__, shared.__globals__, name,
                                        shared.__defaults__, shared.__closure__)
            method.__annotations__ = dict(shared.__annotations__)
            method.__qualname__ = f"{cls.__qualname__}.{name}"
            method.__module__ = cls.__module__
            method.__doc__ = _wrapped(template.format(**doc))
            setattr(cls, name, method)
        for alias, name in cls.__dict__.get("_STATE_ALIASES", {}).items():
            setattr(cls, alias, getattr(cls, name))

    def get_state(self) -> np.ndarray:
        """The dynamic state, tagged with the configuration it belongs to (a copy)."""
        with self._lock:        # the object's lock (smoothshaper._shared)
            out = np.empty(getattr(self._lib, self._STATE_C + "_state_count")(self._gen),
                           dtype=np.float64)
            getattr(self._lib, self._STATE_C + "_get_state")(
                self._gen, self._ffi.from_buffer("double[]", out))
            return out

    def set_state(self, state) -> None:
        """Restore a state saved by :meth:`get_state`."""
        with self._lock:
            restore(type(self).__name__, self._ffi, self._lib, self._STATE_C + "_set_state",
                    self._gen, state, self._STATE_FIELDS, self._STATE_CHOICES)
