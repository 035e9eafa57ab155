"""The journal half of the course's client node: each parameter request it sends, written to the
lab's parameter journal (core/param_journal.py) with the values it replaces.

`lesson.history` shows those values as each change's "old", and the first change's old value
is the start-up value `lesson.reset` and `lesson.diff` go back to. They are known without
asking the node: a value is what the journal last recorded of that parameter (a set that was
not refused, a /parameter_events change a listener heard) or what this client last read from
the node or set on it, whichever is newer. Only what the node holds since it started counts:
a node is told from a restarted one by the GIDs of its `set_parameters` reply writers (a
restarted node has new ones), and a value recorded before those GIDs were first seen (by
this client, or named in a journalled set) is not trusted. A value known no other way (the
first change of a parameter this client never read) is read from the node once
(RosClient.set_parameters), as every set used to do.
"""

from __future__ import annotations

import math
import os
import threading
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from ...core import param_journal
from ..results import SetResult
from ..values import NOT_SET, ParamValue, journal_value

__all__ = ["Known", "KnownValues", "SetJournal", "writer_ids"]

Stored = list[Any]  # a value as the journal stores it: [type, plain JSON value]
# A client's first look reads this much of the journal's end (a lab's whole day is ~100 kB;
# what is older says little of what a node holds now, and a node is read when not known).
FIRST_READ_BYTES = 32 << 10


def writer_ids(writers: frozenset[bytes]) -> tuple[str, ...]:
    """Return reply-writer GIDs as the journal writes them (hex, sorted)."""
    return tuple(sorted(gid.hex() for gid in writers))


@dataclass(frozen=True)
class Known:
    """What was known of one parameter's value at one (wall) time."""

    wall: float
    value: Stored | None  # None: the node has no such parameter (as a get answers)
    certain: bool = True  # False: a set whose answer never came (it may have applied)
    request: str | None = None  # the journal's set record it comes from (dropped if refused)


def _after_set(stored: Any) -> Stored | None:
    """Return what a parameter holds once set to `stored`: setting NOT_SET undeclares it."""
    return None if isinstance(stored, list) and stored[:1] == [NOT_SET] else stored


class KnownValues:
    """The newest value of each node's parameters that the journal and this client know
    (pure: records and answers in, values out)."""

    KEEP = 4  # journal facts kept per parameter (a refused set drops its own)

    def __init__(self) -> None:
        self._journal: dict[tuple[str, str], list[Known]] = {}
        self._own: dict[tuple[str, str], Known] = {}
        self._requests: dict[str, tuple[str, str]] = {}  # set record id -> its parameter
        # the earliest journalled set naming a node's reply writers: that node ran since then
        self._named: dict[tuple[str, tuple[str, ...]], float] = {}
        self._seen: dict[str, tuple[tuple[str, ...], float]] = {}  # by this client, since

    def forget_journal(self) -> None:
        """Forget what the journal said (it was cut: it is read again from its start)."""
        self._journal.clear()
        self._requests.clear()
        self._named.clear()

    def read(self, record: Mapping[str, Any]) -> None:
        """Take in one journal record (those of other kinds say nothing about values)."""
        kind, wall = record.get("t"), float(record.get("wall") or 0.0)
        if kind == "set":
            key = (str(record.get("node")), str(record.get("name")))
            request = str(record.get("id"))
            self._add(key, Known(wall, _after_set(record.get("value")), request=request))
            self._requests[request] = key
            writers = tuple(record.get("writers") or ())
            if writers:
                named = (key[0], writers)
                self._named[named] = min(wall, self._named.get(named, math.inf))
        elif kind == "failed":
            key_of = self._requests.pop(str(record.get("id")), None)
            if key_of is not None:
                facts = self._journal.get(key_of, [])
                facts[:] = [k for k in facts if k.request != record.get("id")]
        elif kind == "event":
            node = str(record.get("node"))
            for change in record.get("changes") or []:
                value = None if change.get("kind") == "deleted" else change.get("value")
                self._add((node, str(change.get("name"))), Known(wall, value))

    def _add(self, key: tuple[str, str], known: Known) -> None:
        facts = self._journal.setdefault(key, [])
        facts.append(known)
        del facts[: -self.KEEP]

    def learn(self, node: str, name: str, known: Known) -> None:
        """Take in what this client itself learnt of a value (an answer, or none)."""
        self._own[(node, name)] = known

    def since(self, node: str, writers: tuple[str, ...], now: float) -> float:
        """Return the wall time from which the node with these reply writers is known to have
        run (inf when they are unknown: then nothing is trusted)."""
        if not writers:
            return math.inf
        seen = self._seen.get(node)
        if seen is None or seen[0] != writers:
            seen = self._seen[node] = (writers, now)  # new to this client: a restart
        return min(seen[1], self._named.get((node, writers), math.inf))

    def latest(self, node: str, name: str, since: float) -> Known | None:
        """Return the newest certain thing known of the value since `since`, if any."""
        key = (node, name)
        facts = [k for k in self._journal.get(key, []) if k.wall >= since]
        own = self._own.get(key)
        if own is not None and own.wall >= since:
            facts.append(own)
        newest = max(facts, key=lambda k: k.wall, default=None)
        return newest if newest is not None and newest.certain else None


class SetJournal:
    """Write one client's parameter requests to its domain's journal (thread-safe)."""

    def __init__(self, domain_id: int | None, *, clock: Callable[[], float] = time.time) -> None:
        self._domain = domain_id
        self._tail = (
            None
            if domain_id is None
            else param_journal.JournalTail(domain_id, start_bytes=FIRST_READ_BYTES)
        )
        self._known = KnownValues()
        self._clock = clock
        self._lock = threading.Lock()

    def _catch_up(self) -> None:
        """Read what was journalled since the last look (called with the lock held)."""
        if self._tail is None:
            return
        records, restarted = self._tail.read()
        if restarted:
            self._known.forget_journal()
        for record in records:
            self._known.read(record)

    def learn(
        self,
        node: str,
        names: Sequence[str],
        values: Sequence[ParamValue],
        writers: frozenset[bytes],
    ) -> None:
        """Note what a get answered: a value per name, or (one name, no value) none at all."""
        if len(values) != len(names) and not (len(names) == 1 and not values):
            return  # no value for one of several names: which one is not said
        with self._lock:
            now = self._clock()
            self._known.since(node, writer_ids(writers), now)
            for index, name in enumerate(names):
                value = journal_value(values[index]) if values else None
                self._known.learn(node, name, Known(now, value))

    def old_values(
        self, node: str, names: Sequence[str], writers: frozenset[bytes]
    ) -> dict[str, Stored | None]:
        """Return the value each of `names` is known to have now, as the journal stores it
        (None: no such parameter); a name whose value is not known is left out."""
        with self._lock:
            self._catch_up()
            since = self._known.since(node, writer_ids(writers), self._clock())
            known = {name: self._known.latest(node, name, since) for name in names}
        return {name: k.value for name, k in known.items() if k is not None}

    def record_request(
        self,
        node: str,
        values: Sequence[tuple[str, ParamValue]],
        old: Mapping[str, Stored | None],
        writers: frozenset[bytes],
    ) -> list[str]:
        """Journal a set request with the values it replaces; return each record's id."""
        door = param_journal.current_door()
        named = {"writers": list(writer_ids(writers))} if writers else {}
        marks = []
        for index, (name, value) in enumerate(values):
            mark = f"{os.getpid()}-{time.monotonic_ns()}-{index}"
            record = {
                "t": "set",
                "id": mark,
                "door": door,
                "node": node,
                "name": name,
                "value": journal_value(value),
                "old": old.get(name),
                **named,
            }
            param_journal.append(self._domain, record)
            marks.append(mark)
        return marks

    def record_answer(
        self,
        node: str,
        values: Sequence[tuple[str, ParamValue]],
        marks: Sequence[str],
        results: Sequence[SetResult],
    ) -> None:
        """Journal the requests the node refused; note the values it took."""
        for mark, result in zip(marks, results, strict=False):
            if not result.successful:
                param_journal.append(self._domain, {"t": "failed", "id": mark})
        with self._lock:
            now = self._clock()
            for (name, value), result in zip(values, results, strict=False):
                if result.successful:
                    self._known.learn(node, name, Known(now, _after_set(journal_value(value))))

    def record_lost(self, node: str, names: Sequence[str]) -> None:
        """Note that a set got no answer: whether it applied is not known (read it next)."""
        with self._lock:
            now = self._clock()
            for name in names:
                self._known.learn(node, name, Known(now, None, certain=False))
