# SPDX-License-Identifier: Apache-2.0
"""What every C-backed object (Chain, TunableChain, ScheduledShaper, Generator,
MultiAxisGenerator, BSpline) shares: a lock that makes it safe to share between threads, and
its copies and pickles.

Threads: cffi releases the GIL around each C call, so two threads calling one object at once
would run the C core on one state together (and corrupt it). Every method that reads or
writes the state holds the object's lock (:func:`locked`); calls on one object then run one
at a time, each on a consistent state, in the order the threads reach it. Different objects
never share a lock, so threads that each use their own object run in parallel.

Copies and pickles: a twin is built from the constructor's arguments (``self._init_args``)
and given the state (``get_state`` / ``set_state``, the same bit-exact route a user has), so
it is independent of the original and continues exactly as it would.
"""
from __future__ import annotations

import functools
import threading

__all__ = ["locked", "new_lock", "Twins"]


def new_lock() -> threading.RLock:
    """The lock of one object (re-entrant: a locked method may call another)."""
    return threading.RLock()


def locked(method):
    """Run ``method`` holding ``self._lock``."""
    @functools.wraps(method)
    def call(self, *args, **kwargs):
        with self._lock:
            return method(self, *args, **kwargs)
    return call


def _restore(cls, init_args: dict, state, counters: dict):
    obj = cls(**init_args)
    obj._set_full_state(state, counters)
    return obj


class Twins:
    """``copy``, ``copy.copy``, ``copy.deepcopy`` and ``pickle`` for a C-backed object.

    A subclass sets ``self._init_args`` (the constructor's keyword arguments, validated) and
    ``self._lock`` in ``__init__`` and provides ``_full_state() -> (state, counters)`` and
    ``_set_full_state(state, counters)``: the saved state, and diagnostic counters that are
    not part of it (e.g. the number of dropped targets)."""

    _init_args: dict
    _lock: threading.RLock

    def copy(self):
        """An independent object with the same configuration and the same current state:
        both continue bit-exactly as this one would, and neither affects the other."""
        with self._lock:
            state, counters = self._full_state()
        return _restore(type(self), self._init_args, state, counters)

    def __copy__(self):
        return self.copy()

    def __deepcopy__(self, memo):
        return self.copy()

    def __reduce__(self):
        with self._lock:
            state, counters = self._full_state()
        return (_restore, (type(self), self._init_args, state, counters))
