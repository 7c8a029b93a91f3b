# SPDX-License-Identifier: Apache-2.0
""":class:`TunableChain`: stages in series that can be retuned while they run (C
``sms_tunable_chain``, ``c/include/smoothshaper/tunable.h``).

A retune replaces one stage's configuration (a shaper's ``wn`` and ``zeta``, a smoother's
``T``, a notch; any family for any other) from the next sample on. Every input increment is
filtered by the stage that was active when it arrived, so the output moves at the switch by
at most one sample's motion of that stage's input, and once both lengths have passed it is
exactly the new stage's output (docs/retune.md has the proof; the NumPy oracle is
:func:`smoothshaper.reference.switched`).

Memory follows the C house style: every stage has two slots sized up front for the largest
configuration it is declared for (``capacity``); a retune to anything larger is refused.
"""
from __future__ import annotations

from typing import Iterable, Sequence

import numpy as np

from . import filters as _filters
from .filters import (PRECISIONS, ParameterError, _backend, _cells, _check_input,
                      _process_checked, _raise_status, _validated_configs, check_memory)
from .stages import Stage
from ._shared import locked as _locked, new_lock as _new_lock
from ._checks import (choice as _choice, finite as _finite, finite_array as _finite_array,
                      integer as _integer, positive as _positive, real_array as _real_array,
                      show as _show)

__all__ = ["TunableChain"]

_SMS_ERR_RETUNE_BUSY = -45
_SMS_ERR_BUFFER_TOO_SMALL = -11
_SMS_ERR_KIND = -12
#: Saved TunableChain states start with this tag (then the format version, precision, Ts, the
#: number of stages and each stage's slot size in cells), then the C core's state.
STATE_TAG = 5460308.0          # "SMT" read as a 24-bit integer
STATE_VERSION = 1
_STATE_HEAD = 5


def _capacity_lists(stages: tuple, capacity) -> list[tuple[Stage, ...]]:
    """Per stage, the stages its slot must hold: its own and those declared in ``capacity``."""
    if capacity is None:
        return [(s,) for s in stages]
    try:
        items = list(capacity)
    except TypeError:
        raise ParameterError("capacity", f"capacity must be None or a sequence with one entry "
                             f"per stage, got {_show(capacity)}") from None
    if len(items) != len(stages):
        raise ParameterError("capacity", f"capacity must have one entry per stage "
                             f"({len(stages)}), got {len(items)}")
    out = []
    for i, (stage, item) in enumerate(zip(stages, items)):
        declared = () if item is None else _filters._as_stage_list(item)
        for j, d in enumerate(declared):
            if not isinstance(d, Stage):
                raise ParameterError(f"capacity[{i}]", f"capacity[{i}][{j}] must be a Stage")
        out.append((stage, *declared))
    return out


class TunableChain:
    """Stages in series that can be retuned while they run, filtered by the C core.

    Parameters
    ----------
    stages : Stage or sequence of Stage
        1 to 16 initial stage descriptions, first stage first.
    Ts : float, keyword-only
        Sample period [s], finite and > 0.
    capacity : sequence or None, keyword-only
        The largest configurations each stage may be retuned to: one entry per stage, each
        None (the stage's own size), a Stage, or a sequence of Stages (any families); the
        stage's memory is sized for the largest of them and its initial stage. Default None:
        every stage only for configurations no larger than its initial one (e.g. a shaper at
        a higher ``wn``, a shorter smoother).
    precision : {'double', 'float'}, keyword-only
        Which build of the C core filters the signal.

    The chain starts at rest at 0; every stage has unit DC gain.

    Raises
    ------
    ParameterError
        Naming the invalid parameter (``Ts``, ``stages``, ``capacity``, a stage field such as
        ``wn``), as :class:`smoothshaper.Chain` does.

    Notes
    -----
    A chain may be shared between threads: its methods hold the chain's lock, so calls run
    one at a time, each on a consistent state (docs/python.md). ``copy.copy``,
    ``copy.deepcopy`` and ``pickle`` give independent chains that continue bit-exactly (a
    pickle is rebuilt from the initial stages and the capacity, then given the state).
    """

    def __init__(self, stages: Stage | Iterable[Stage], *, Ts: float,
                 capacity: Sequence | None = None, precision: str = "double"):
        self.Ts = _positive("Ts", Ts)
        self._lock = _new_lock()
        self.precision = _choice("precision", precision, PRECISIONS)
        self._stages = list(_filters._as_stage_list(stages))
        ffi, lib = _backend(self.precision)
        self._ffi, self._lib = ffi, lib
        n = len(self._stages)
        if not 1 <= n <= lib.SMS_CHAIN_MAX_STAGES:
            raise ParameterError(
                "stages", f"stages: a chain needs 1 to {lib.SMS_CHAIN_MAX_STAGES} stages, got {n}")
        configs, _ = _validated_configs(tuple(self._stages), self.Ts, ffi, lib)
        slots = ffi.new("size_t[]", n)
        reals = 0
        declared_lists = _capacity_lists(tuple(self._stages), capacity)
        # what a pickle rebuilds the chain from: the initial stages and the declared capacity
        self._init_args = dict(stages=tuple(self._stages), Ts=self.Ts,
                               capacity=[tuple(d[1:]) for d in declared_lists],
                               precision=self.precision)
        for i, declared in enumerate(declared_lists):
            try:
                cd, sizes = _validated_configs(declared, self.Ts, ffi, lib)
            except ParameterError as exc:
                raise ParameterError(exc.parameter, f"capacity[{i}]: {exc}") from None
            reals += 2 * max(sizes)
            cells = ffi.new("size_t *")
            st = lib.sms_tunable_slot_cells(cd, len(declared), self.Ts, cells)
            if st != 0:
                _raise_status(st, lib, ffi, f"capacity[{i}], Ts={self.Ts!r}")
            slots[i] = cells[0]
        check_memory("capacity", reals, "the stages' slots")
        total = ffi.new("size_t *")
        st = lib.sms_tunable_chain_memory_size(slots, n, total)
        if st != 0:
            _raise_status(st, lib, ffi, "capacity: the slots' memory")
        self._slots = [int(slots[i]) for i in range(n)]
        self._memory, self._memory_c = _cells(ffi, total[0])
        self._tunables = ffi.new("sms_tunable[]", n)
        self._chain = ffi.new("sms_tunable_chain *")
        st = lib.sms_tunable_chain_init(self._chain, self._tunables, configs, slots, n, self.Ts,
                                        self._memory_c, total[0])
        if st != 0:
            _raise_status(st, lib, ffi, f"chain of {n} stages, Ts={self.Ts!r}")

    # -- description ----------------------------------------------------------------------

    @property
    def stages(self) -> tuple[Stage, ...]:
        """The active stage of every position (the last retune's, or the initial one)."""
        return tuple(self._stages)

    @property
    @_locked
    def switching(self) -> tuple[bool, ...]:
        """Per stage: True while its last retune is still in progress (the old filter is
        fading out and a further retune of it would be refused)."""
        return tuple(bool(self._lib.sms_tunable_switching(self._tunables + i))
                     for i in range(len(self._stages)))

    @_locked
    def switch_left(self, index: int) -> float:
        """Samples until the switch of stage ``index`` ends, at most.

        Parameters
        ----------
        index : int
            The stage position.

        Returns
        -------
        float
            0 when no switch is running; for a FIR old stage exactly the samples left (its
            length minus 2, counted down); for an old notch an upper bound from its poles and
            its current free response (docs/retune.md).

        Raises
        ------
        ParameterError
            Naming ``index`` when it is not a stage position.
        """
        i = self._index(index)
        return float(self._lib.sms_tunable_switch_left(self._tunables + i))

    @property
    @_locked
    def input_max(self) -> float:
        """Largest ``|x|`` the chain keeps every output and state finite for, now (C
        ``sms_tunable_chain_input_max``: during a switch, over both filters of the stage):
        ``min(input_max(), min_i L_i / R_i)``, ``L_i`` each stage's limit before the cap (the
        smaller of its two filters' during a switch), ``R_0 = 1``,
        ``R_i = 1 + 2 G_0 ... G_(i-1)`` with ``G_j`` each stage's gain bound (both filters
        together ``1 + 2 G_A + 2 G_B`` during a switch)."""
        return float(self._lib.sms_tunable_chain_input_max(self._chain))

    @property
    @_locked
    def lag(self) -> float:
        """The lag of the active stages [s] (C ``sms_chain_lag`` of them): what a
        constant-speed motion is delayed by once every switch has passed."""
        from .align import lag
        return lag(self.stages, Ts=self.Ts)

    @property
    @_locked
    def length(self) -> int:
        """FIR length of the active stages in series (notches count 0)."""
        return int(self._lib.sms_tunable_chain_length(self._chain))

    def _index(self, index) -> int:
        i = _integer("index", index)
        if not 0 <= i < len(self._stages):
            raise ParameterError("index", f"index must be a stage position in [0, "
                                 f"{len(self._stages)}), got {i}")
        return i

    # -- retune ---------------------------------------------------------------------------

    @_locked
    def retune(self, index: int, stage: Stage) -> None:
        """Replace stage ``index`` by ``stage`` from the next sample on.

        Every input increment from then on is filtered by ``stage``, those before by the old
        one: the output moves by at most one sample's motion of this stage's input at the
        switch, and once both lengths have passed it is ``stage``'s output exactly.

        Parameters
        ----------
        index : int
            The stage position, ``0 <= index < len(stages)``.
        stage : Stage
            The new configuration (any family); it must fit the memory declared by
            ``capacity``.

        Raises
        ------
        ParameterError
            Naming ``index`` (no such stage, or its previous switch is still in progress:
            :attr:`switching`, :meth:`switch_left`), ``stage`` (not a Stage, or larger than
            the declared capacity) or the stage field that is invalid at ``Ts``; nothing
            changes then.
        """
        i = self._index(index)
        if not isinstance(stage, Stage):
            raise ParameterError("stage", f"stage must be a smoothshaper.Stage, got "
                                 f"{_show(stage)}")
        ffi, lib = self._ffi, self._lib
        configs, _ = _validated_configs((stage,), self.Ts, ffi, lib)
        st = lib.sms_tunable_chain_retune(self._chain, i, configs)
        if st == _SMS_ERR_RETUNE_BUSY:
            raise ParameterError(
                "index", f"index: stages[{i}] is still switching from its previous retune "
                f"(at most {self.switch_left(i):.0f} more samples); retune it once "
                f"switching[{i}] is False", st)
        if st == _SMS_ERR_BUFFER_TOO_SMALL:
            need = ffi.new("size_t *")
            lib.sms_stage_memory_size(configs, self.Ts, need)
            raise ParameterError(
                "stage", f"stage: {stage.kind} needs {need[0]} memory cells at Ts={self.Ts!r}, "
                f"more than the {self._slots[i]} that stages[{i}] was built with; declare it "
                f"(or a larger one) in capacity=", st)
        if st == _SMS_ERR_KIND and "impulses" in (stage.kind, self._stages[i].kind):
            # a saved state names user-defined impulses by a checksum only: a switch to or
            # from them could not be restored, so the C library refuses it
            raise ParameterError(
                "stage", f"stage: user-defined impulses cannot be retuned to or from "
                f"(stages[{i}] is {self._stages[i].kind}, stage is {stage.kind}); build the "
                f"chain with them, they run as built", st)
        if st != 0:
            _raise_status(st, lib, ffi, f"retuning stages[{i}] to {stage.kind}")
        self._stages[i] = stage

    # -- filtering ------------------------------------------------------------------------

    @_locked
    def process(self, u) -> np.ndarray:
        """Filter a block of samples, continuing from the current state.

        Parameters
        ----------
        u : array_like of float, shape (n,)
            Input samples at ``Ts``; not modified.

        Returns
        -------
        ndarray of float64, shape (n,)
            The output.

        Raises
        ------
        ParameterError
            Naming ``u`` if it is not 1-D real, holds NaN/Inf, or a sample beyond
            :attr:`input_max`; the state is then untouched.
        """
        return _process_checked(self._ffi, self._lib.smspy_tunable_chain_process_f64,
                                self._chain, u, self.precision, self.input_max)

    @_locked
    def step(self, x: float) -> float:
        """Filter one sample.

        Parameters
        ----------
        x : float
            The input sample.

        Returns
        -------
        float
            The output sample.

        Raises
        ------
        ParameterError
            Naming ``x`` if it is not finite or beyond :attr:`input_max`; the state is then
            untouched.
        """
        v = _finite("x", x)
        limit = self.input_max
        if abs(v) > limit:
            _check_input("x", np.float64(v), self.precision, limit)
        cell = self._ffi.new("sms_real *", v)
        self._lib.sms_tunable_chain_step(self._chain, cell)
        return float(cell[0])

    @_locked
    def reset(self, rest: float = 0.0) -> None:
        """Put every stage at rest at ``rest``, as if the input had been ``rest`` forever; any
        switch in progress ends, the active stages stay.

        Parameters
        ----------
        rest : float
            The rest value (default 0).

        Raises
        ------
        ParameterError
            Naming ``rest`` if it is not finite or beyond :attr:`input_max`.
        """
        v = _finite("rest", rest)
        _check_input("rest", np.float64(v), self.precision, self.input_max)
        self._lib.sms_tunable_chain_reset(self._chain, v)

    # -- state ----------------------------------------------------------------------------

    def _header(self) -> np.ndarray:
        return np.array([STATE_TAG, STATE_VERSION, float(PRECISIONS.index(self.precision)),
                         self.Ts, float(len(self._stages)), *map(float, self._slots)])

    @_locked
    def get_state(self) -> np.ndarray:
        """The full dynamic state: a header (tag, version, precision, Ts, number of stages,
        each stage's slot size) and the C state (each stage's active and, during a switch,
        old configuration and filter state).

        Returns
        -------
        ndarray of float64
            A copy; :meth:`set_state` of this chain or of one built with the same Ts,
            precision, number of stages and capacity restores it, whatever the stages were
            retuned to since.
        """
        head = self._header()
        core = np.zeros(int(self._lib.sms_tunable_chain_state_count(self._chain)))
        if core.size:
            self._lib.sms_tunable_chain_get_state(self._chain,
                                                  self._ffi.from_buffer("double[]", core))
        return np.concatenate([head, core])

    @_locked
    def set_state(self, state) -> None:
        """Restore a state saved by :meth:`get_state`: the stages become those it was saved
        with (also in the middle of a switch) and continue bit for bit.

        Parameters
        ----------
        state : array_like of float, shape (n,)
            A state from :meth:`get_state` of a chain with the same Ts, precision, number of
            stages and capacity.

        Raises
        ------
        ParameterError
            Naming ``state`` when it is not 1-D real, is from another precision, Ts, number of
            stages or capacity (the message says which), or does not fit; then nothing
            changes.
        """
        s = np.array(_finite_array("state", _real_array("state", state, ndim=1)))
        head = self._header()
        if s.size < head.size or s[0] != STATE_TAG or s[1] != STATE_VERSION:
            raise ParameterError("state", "state is not a saved TunableChain state (no tag or "
                                 "another format version; was it saved by get_state?)")
        for k, what in ((2, "precision"), (3, "Ts"), (4, "number of stages")):
            if s[k] != head[k]:
                raise ParameterError("state", f"state is from another configuration: its "
                                     f"{what} is {float(s[k])!r}, this chain's {float(head[k])!r}")
        if not np.array_equal(s[_STATE_HEAD:head.size], head[_STATE_HEAD:]):
            raise ParameterError("state", "state is from another configuration: its stages' "
                                 "capacity (slot sizes) differs from this chain's")
        twin = self._twin_for(s[head.size:])
        core = s[head.size:]
        st = self._lib.sms_tunable_chain_set_state(twin._chain,
                                                    self._ffi.from_buffer("double[]", core),
                                                    core.size)
        if st != 0:
            _raise_status(st, self._lib, self._ffi, "it does not fit this chain", "state")
        self.__dict__.update(twin.__dict__)

    state = property(get_state, set_state, doc="The dynamic state (see get_state/set_state).")

    def _twin_for(self, core: np.ndarray) -> "TunableChain":
        """A chain like this one, brought to the configurations the C state ``core`` was saved
        in (each stage built with its old configuration and retuned to the active one when it
        was saved during a switch)."""
        ffi, lib = self._ffi, self._lib
        twin = self.copy()
        offset = 0
        for i in range(len(self._stages)):
            part = core[offset:]
            active = ffi.new("sms_stage_config *")
            old = ffi.new("sms_stage_config *")
            switching = ffi.new("int *")
            st = lib.sms_tunable_state_configs(ffi.from_buffer("double[]", part), part.size,
                                               active, old, switching)
            if st == _SMS_ERR_KIND and self._stages[i].kind == "impulses":
                # the state names the impulses by a checksum: build this chain's own, and
                # sms_tunable_chain_set_state refuses a state of other impulses
                active = _validated_configs((self._stages[i],), self.Ts, ffi, lib)[0]
                switching[0] = 0
                st = 0
            if st != 0:
                _raise_status(st, lib, ffi, f"stage {i} of the saved state", "state")
            first = old if switching[0] else active
            cell = twin._tunables + i
            mem = twin._memory_c + (2 * sum(self._slots[:i]))
            st = lib.sms_tunable_init(cell, first, self.Ts, self._slots[i], mem,
                                      2 * self._slots[i])
            if st == 0 and switching[0]:
                st = lib.sms_tunable_retune(cell, active)
            if st != 0:
                _raise_status(st, lib, ffi, f"stages[{i}] of the saved state does not fit this "
                              f"chain's capacity", "state")
            twin._stages[i] = (self._stages[i] if self._stages[i].kind == "impulses"
                               else _filters._stage_from_config(active[0]))
            # the part's length as the saving stage had it (a saved switch whose rebuilt old
            # notch is at rest begins none here, and the part still holds the old values)
            offset += int(lib.sms_tunable_saved_state_count(cell, ffi.from_buffer("double[]", part),
                                                            part.size))
        return twin

    @_locked
    def copy(self) -> "TunableChain":
        """An independent chain with the same stages, capacity and state (the C instances and
        their memory copied, nothing designed again).

        Returns
        -------
        TunableChain
            The copy; filtering one does not affect the other.
        """
        ffi, lib = self._ffi, self._lib
        twin = TunableChain.__new__(TunableChain)
        twin.__dict__.update(self.__dict__)
        twin._lock = _new_lock()
        twin._stages = list(self._stages)
        twin._memory, twin._memory_c = _cells(ffi, int(self._chain.memory_len))
        twin._memory[:] = self._memory
        n = len(self._stages)
        twin._tunables = ffi.new("sms_tunable[]", n)
        ffi.memmove(twin._tunables, self._tunables, ffi.sizeof("sms_tunable") * n)
        twin._chain = ffi.new("sms_tunable_chain *")
        twin._chain[0] = self._chain[0]
        lib.sms_tunable_chain_rebind(twin._chain, twin._tunables, twin._memory_c)
        return twin

    __copy__ = copy

    def __deepcopy__(self, memo) -> "TunableChain":
        return self.copy()

    def __reduce__(self):
        # the constructor's arguments and the state, never the pointers
        return (_restore_tunable, (self._init_args, self.get_state()))

    def __repr__(self) -> str:
        kinds = ", ".join(s.kind for s in self._stages)
        return f"TunableChain([{kinds}], Ts={self.Ts!r}, precision={self.precision!r})"


def _restore_tunable(init_args: dict, state) -> TunableChain:
    chain = TunableChain(**init_args)
    chain.set_state(state)
    return chain
