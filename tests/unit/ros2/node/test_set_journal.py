"""A set's journal record names the values it replaces without asking the node (issue 63).

The node here is scripted (a dict of parameters behind a fake calls layer, its reply writers'
GIDs new at each restart), the journal is a real file in a folder of the test's own. Each set
record's "old" must be what the node held just before, as the `get_parameters` every set used
to make read it; the node is asked only for a value nothing else knows.
"""

from __future__ import annotations

import itertools
import os
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import pytest

from course_lib.core import param_journal
from course_lib.notebook.history import build_history
from course_lib.ros2.node.client import RosClient, ServiceCallError
from course_lib.ros2.node.set_journal import KnownValues, SetJournal
from course_lib.ros2.results import SetResult
from course_lib.ros2.values import ParamValue, journal_value

DOMAIN = 7
NODE = "/param_vel_node"
_stamps = itertools.count(1)


class _Node:
    """A node's parameters, what each set replaced, and the requests it answered."""

    def __init__(self, **params: Any) -> None:
        self.params: dict[str, Any] = {}
        self.replaced: list[Any] = []  # per set request and name: the value before it
        self.gets = self.sets = 0
        self.listened = True  # a kernel hears its /parameter_events and journals them
        self.lost = False  # the next set gets no answer (it applies all the same)
        self.restart(**params)

    def restart(self, **params: Any) -> None:
        self.params = dict(params)
        self.gids = frozenset({os.urandom(16)})

    def changed(self, name: str, value: Any) -> None:
        """Take a new value (None: delete it), from a set or another node: its event, if heard."""
        self.params[name] = value
        kind = "changed"
        if value is None:
            kind = "deleted"
            del self.params[name]
        if self.listened:
            change = {"kind": kind, "name": name, "value": journal_value(ParamValue.of(value))}
            event = {"t": "event", "node": NODE, "stamp": next(_stamps), "changes": [change]}
            param_journal.append(DOMAIN, event)


class _Calls:
    """ParamCalls over a scripted node."""

    def __init__(self, node: _Node) -> None:
        self.node = node

    def reply_writers(self, node_name: str, service: str = "set_parameters") -> frozenset[bytes]:
        return self.node.gids

    def get_parameters(self, node_name: str, names: list[str]) -> list[ParamValue]:
        self.node.gets += 1
        if any(name not in self.node.params for name in names):
            return []  # as rclpy answers when one name is not declared
        return [ParamValue.of(self.node.params[name]) for name in names]

    def set_parameters(
        self, node_name: str, values: list[tuple[str, ParamValue]], *, writers: Any = None
    ) -> list[SetResult]:
        self.node.sets += 1
        results = []
        for name, value in values:
            before = self.node.params.get(name)
            self.node.replaced.append(
                None if before is None else journal_value(ParamValue.of(before))
            )
            ok = name in self.node.params and (
                value.type == 0 or isinstance(before, type(value.value))
            )
            if ok:
                self.node.changed(name, None if value.type == 0 else value.value)
            results.append(SetResult(ok, "" if ok else "Wrong parameter type", name))
        if self.node.lost:
            self.node.lost = False
            raise ServiceCallError("no answer within 10 s")
        return results


def _client(node: _Node) -> RosClient:
    fake = SimpleNamespace(context=SimpleNamespace(get_domain_id=lambda: DOMAIN))
    client = RosClient(fake, lambda future, timeout: None)
    client.calls = _Calls(node)  # type: ignore[assignment]
    return client


def _set(client: RosClient, value: Any, name: str = "velocity") -> bool:
    (result,) = client.set_parameters(NODE, [(name, ParamValue.of(value))])
    return result.successful


def _olds() -> list[Any]:
    return [r["old"] for r in param_journal.read_journal(DOMAIN) if r["t"] == "set"]


@pytest.fixture(autouse=True)
def _own_journal(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setattr(param_journal, "runtime_dir", lambda: tmp_path)


def test_only_the_first_set_of_a_parameter_asks_the_node() -> None:
    node = _Node(velocity=0.0)
    client = _client(node)
    for n in range(1, 51):
        assert _set(client, n / 100)
    assert (node.gets, node.sets) == (1, 50)  # before: a get for every set
    assert _olds() == node.replaced


def test_a_value_read_before_or_changed_by_another_door_is_known() -> None:
    node = _Node(velocity=0.05)
    client = _client(node)
    assert client.get_parameters(NODE, ["velocity"]) == [ParamValue.of(0.05)]
    assert _set(client, 0.1)
    node.changed("velocity", 0.25)  # another node: only its event tells
    assert _set(client, 0.3)
    assert not _set(client, 1)  # refused (an integer for a double): the value stays
    assert _set(client, 0.4)
    assert node.gets == 1  # the reader's own
    assert _olds() == node.replaced == [[3, 0.05], [3, 0.25], [3, 0.3], [3, 0.3]]


def test_a_restarted_node_is_asked_again() -> None:
    node = _Node(velocity=0.0)
    client = _client(node)
    assert _set(client, 0.1)
    node.restart(velocity=0.07)  # new reply writers; its declaration was not heard
    assert _set(client, 0.2)
    assert _set(client, 0.3)
    assert node.gets == 2
    assert _olds() == node.replaced == [[3, 0.0], [3, 0.07], [3, 0.2]]


def test_a_set_without_answer_is_not_taken_for_known() -> None:
    node = _Node(velocity=0.0)
    client = _client(node)
    assert _set(client, 0.1)
    node.listened = False
    node.lost = True
    with pytest.raises(ServiceCallError):
        _set(client, 0.2)
    assert _set(client, 0.3)
    assert node.gets == 2
    assert _olds() == node.replaced


def test_a_new_client_trusts_what_the_journal_says_of_the_same_node() -> None:
    node = _Node(velocity=0.0)
    assert _set(_client(node), 0.1)  # a kernel
    daemon = _client(node)  # the terminal's `ros2`, in its daemon
    assert _set(daemon, 0.15)
    node.restart(velocity=0.0)
    assert _set(_client(node), 0.2)
    assert node.gets == 2  # the kernel's first set, and the first after the restart
    assert _olds() == node.replaced == [[3, 0.0], [3, 0.1], [3, 0.0]]


def test_a_deleted_or_undeclared_parameter_has_no_old_value() -> None:
    node = _Node(velocity=0.0, extra=1)
    client = _client(node)
    assert _set(client, 2, name="extra")
    assert _set(client, None, name="extra")  # `ros2 param delete`: it is undeclared
    assert not _set(client, 3, name="extra")  # refused: no such parameter any more
    assert not _set(client, 0.5, name="nope")
    assert node.gets == 2  # extra's first set, and nope's
    assert _olds() == node.replaced == [[2, 1], [2, 2], None, None]


def test_the_history_and_reset_see_the_same_changes_as_with_a_get_per_set() -> None:
    node = _Node(velocity=0.05)
    client = _client(node)
    for value in (0.1, 0.15, 1, 0.2):
        _set(client, value)
    node.changed("velocity", 0.25)
    _set(client, 0.3)
    records = param_journal.read_journal(DOMAIN)
    sets = [r for r in records if r["t"] == "set"]
    assert [r["old"] for r in sets] == node.replaced  # what a get before each set read
    history = build_history(records, NODE)
    rows = [(e.old and e.old.value, e.new and e.new.value, e.source) for e in history.entries]
    assert rows == [
        (0.05, 0.1, "Python (course API)"),
        (0.1, 0.15, "Python (course API)"),
        (0.15, 0.2, "Python (course API)"),
        (0.2, 0.25, "the node itself or another node"),
        (0.25, 0.3, "Python (course API)"),
    ]
    assert history.startup_value("velocity") == ParamValue.of(0.05)


def test_known_values_forget_what_a_refused_set_asked() -> None:
    known = KnownValues()
    change = {"kind": "changed", "name": "velocity", "value": [3, 0.1]}
    known.read({"t": "event", "wall": 1.0, "node": NODE, "changes": [change]})
    request = {"t": "set", "id": "a", "node": NODE, "name": "velocity", "value": [2, 1]}
    known.read({**request, "wall": 2.0, "writers": ["ab"]})
    since = known.since(NODE, ("ab",), now=5.0)
    assert since == 2.0  # a journalled set named these writers at 2.0: that node ran then
    assert known.latest(NODE, "velocity", since=0.0).value == [2, 1]  # type: ignore[union-attr]
    known.read({"t": "failed", "id": "a", "wall": 2.1})
    assert known.latest(NODE, "velocity", since=0.0).value == [3, 0.1]  # type: ignore[union-attr]
    assert known.latest(NODE, "velocity", since=since) is None  # before this node: not trusted
    assert known.since(NODE, (), now=6.0) == float("inf")  # writers unknown: trust nothing


def test_a_journal_without_a_domain_records_nothing() -> None:
    journal = SetJournal(None)
    assert journal.old_values(NODE, ["velocity"], frozenset({b"x"})) == {}
    journal.record_request(NODE, [("velocity", ParamValue.of(0.1))], {}, frozenset())
