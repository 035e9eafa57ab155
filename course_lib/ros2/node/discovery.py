"""When a client node's view of the ROS graph is complete enough to list it.

A fresh DDS participant learns of the others from their announcements, so it cannot tell
from DDS alone whether it has met everyone. On this host it can count them, though
(participants.py: every participant binds a port /proc lists). A young client waits
until it has seen endpoints of as many participants as are bound, every endpoint's node is
known by name (not `_NODE_NAME_UNKNOWN_`: that node's `ros_discovery_info` has not arrived),
and the graph stayed the same for a moment. Without /proc it falls back on time: the
course's Fast DDS profile makes every course process announce itself every
`leaseAnnouncement` period, and a newcomer learns of the others by their next announcement.
Every wait is bounded by the slowest announcement period Fast DDS uses by default, so
nodes started without the course's profile are listed too and a stuck process costs at
most that. The rules are pure: the graph and the clock are passed in.
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .participants import NEWCOMER_S

__all__ = [
    "DEFAULT_SPIN_TIME",
    "DEFAULT_TIMING",
    "FASTDDS_DEFAULT_ANNOUNCEMENT_S",
    "GHOST_GRACE_S",
    "NAME_WAIT_S",
    "NEWCOMER_QUIET_S",
    "UNKNOWN_NODE",
    "DiscoveryTiming",
    "GraphView",
    "profile_timing",
    "requested_spin_time",
    "timing_from_profile",
    "wait_joined",
    "wait_settled",
    "without_ghosts",
]

UNKNOWN_NODE = "_NODE_NAME_UNKNOWN_"
# Fast DDS's own announcement period (used by processes started without the course profile).
FASTDDS_DEFAULT_ANNOUNCEMENT_S = 3.0
# Endpoint exchange and `ros_discovery_info` after two participants met (measured: under
# 0.05 s on an idle machine, 0.1 s on two busy cores; see bench/ros2_discovery.py).
ENDPOINT_EXCHANGE_S = 0.1
POLL_S = 0.01
# A node seen by its endpoints but not yet by name is running: its name (ros_discovery_info)
# follows, late only on a loaded machine. Waiting that long costs nothing when all is known.
NAME_WAIT_S = 10.0
# A new node creates its endpoints one by one as its constructor runs (its publishers after
# its parameter services): it is taken as whole once it spins (it answers a request) and the
# graph then stayed the same this long (a node without parameter services: this long).
NEWCOMER_QUIET_S = 0.5


class SpinTimeDefault(float):
    """`--spin-time`'s default (0.5 s, as ros2cli's), told apart from a typed `0.5`."""


DEFAULT_SPIN_TIME = SpinTimeDefault(0.5)


def requested_spin_time(args: object) -> float:
    """Return the `--spin-time` the user typed (0 when left at its default)."""
    value = getattr(args, "spin_time", None)
    return 0.0 if value is None or isinstance(value, SpinTimeDefault) else float(value)


@dataclass(frozen=True)
class DiscoveryTiming:
    """How long a fresh client waits for the graph (seconds)."""

    floor_s: float  # a fresh client answers no earlier than this age
    quiet_s: float  # ... and once the graph showed no change for this long
    unknown_wait_s: float  # wait at most this long for nodes whose name is not known yet

    @property
    def warm_s(self) -> float:
        """Return the age from which a client answers at once (its graph is complete)."""
        return self.floor_s + self.quiet_s


@dataclass(frozen=True)
class GraphView:
    """What a client sees: node and topic names, and what it knows it has not seen yet."""

    nodes: frozenset[str]
    topics: frozenset[str]
    unknown_endpoints: int = 0  # endpoints whose node's name has not arrived
    missing_participants: int | None = None  # bound on this host, not seen; None: unknown
    endpoints: int = 0  # every endpoint seen (a new publisher on a known topic is a change)
    # the processes whose participants are seen (Fast DDS: the low 16 bits of each pid)
    participant_pids: frozenset[int] = frozenset()


def _seconds(element: Any) -> float | None:
    if element is None:
        return None
    sec = element.findtext("{*}sec", default="0").strip()
    nanosec = element.findtext("{*}nanosec", default="0").strip()
    return float(sec) + float(nanosec) / 1e9


def timing_from_profile(xml_text: str | None) -> DiscoveryTiming:
    """Return the waits the announcement periods of a Fast DDS profile allow."""
    announce = FASTDDS_DEFAULT_ANNOUNCEMENT_S
    initial = 0.1  # Fast DDS default: 5 announcements 100 ms apart
    if xml_text:
        import xml.etree.ElementTree as ET  # only a fresh client reads the profile

        root = ET.fromstring(xml_text)
        config = root.find(".//{*}discovery_config")
        if config is not None:
            announce = _seconds(config.find("{*}leaseAnnouncement")) or announce
            initial = _seconds(config.find("{*}initialAnnouncements/{*}period")) or initial
    return DiscoveryTiming(
        floor_s=round(announce + ENDPOINT_EXCHANGE_S, 3),
        quiet_s=round(max(2 * initial, ENDPOINT_EXCHANGE_S), 3),
        unknown_wait_s=FASTDDS_DEFAULT_ANNOUNCEMENT_S + 0.5,
    )


def profile_timing(path: str | Path | None) -> DiscoveryTiming:
    """Return the timing of the profile file at `path` (Fast DDS defaults if unreadable)."""
    try:
        text = Path(path).read_text() if path else None
    except OSError:
        text = None
    from xml.etree.ElementTree import ParseError

    try:
        return timing_from_profile(text)
    except ParseError:
        return timing_from_profile(None)


DEFAULT_TIMING = timing_from_profile(None)


def wait_joined(
    view: Callable[[], GraphView],
    timing: DiscoveryTiming,
    starting: Callable[[], frozenset[int]],
    clock: Callable[[], float],
    sleep: Callable[[float], None],
    spinning: Callable[[frozenset[int], float], object] | None = None,
) -> None:
    """Wait (a warm client) until every young process of the domain (`starting()`: their
    pids, re-read as they age) is seen as a participant with its endpoints named, its nodes
    spin (`spinning(pids, timeout)` waits until they answer a request: their constructors,
    which make their publishers, are done), and the graph stayed the same for
    NEWCOMER_QUIET_S since; at most NEWCOMER_S (a process never joining DDS)."""
    start = clock()
    young = {pid & 0xFFFF for pid in starting()}
    if not young:
        return  # no process of the domain is young: nothing is joining
    current = view()
    changed = start
    polls = 0
    asked: set[int] = set()
    while clock() - start < NEWCOMER_S:
        joined = young <= current.participant_pids and not current.unknown_endpoints
        if joined and spinning is not None and not young <= asked:
            # a constructor that pauses (a busy host) between its services and its publisher
            # left the graph quiet for longer than NEWCOMER_QUIET_S: the node itself says when
            # it is done, by answering once it spins
            spinning(frozenset(young - asked), NEWCOMER_S - (clock() - start))
            asked |= young
            current, changed = view(), clock()
            continue
        if joined and clock() - changed >= max(timing.quiet_s, NEWCOMER_QUIET_S):
            return
        sleep(POLL_S)
        polls += 1
        if polls % 10 == 0:  # a process that grew old without joining is no newcomer
            young = {pid & 0xFFFF for pid in starting()}
        seen = view()
        if seen != current:
            current, changed = seen, clock()


def wait_settled(
    view: Callable[[], GraphView],
    *,
    born: float,
    timing: DiscoveryTiming,
    min_age_s: float = 0.0,
    clock: Callable[[], float] = time.monotonic,
    sleep: Callable[[float], None] = time.sleep,
    starting: Callable[[], frozenset[int]] | None = None,
    spinning: Callable[[frozenset[int], float], object] | None = None,
) -> GraphView:
    """Wait until a client node born at `born` sees the whole graph; return that view.

    A warm client with no half-known node answers at once. A young one that can count the
    host's participants waits until it has seen them all and the graph stayed the same for
    `quiet_s`; one that cannot waits until it is `floor_s` old (and quiet). `min_age_s`
    (`--spin-time`) is a minimum age. Nodes known by their endpoints only are waited for,
    and participants not seen yet while the client is young: at most `unknown_wait_s`, or
    NAME_WAIT_S for a node whose endpoints are seen but whose name has not arrived. A warm
    client waits too while a young process of the domain exists (`starting()`): until
    each one's participant is seen, its endpoints named, and the graph stayed the same for
    `quiet_s` once its nodes spin (`spinning`: see wait_joined); at most NEWCOMER_S. So a
    command run moments after a node started counts that node's endpoints, every time.
    """
    if starting is not None and clock() - born >= timing.warm_s:
        wait_joined(view, timing, starting, clock, sleep, spinning)
    start = clock()
    current = view()
    counting = current.missing_participants is not None
    floor = max(0.0 if counting else timing.floor_s, min_age_s)
    changed = start
    while True:
        now = clock()
        age = now - born
        young = age < timing.unknown_wait_s
        # a young client answers only from a view that held still: one taken while
        # participants come and go can count them all with one of them not whole (seen once
        # in the suite, four first calls at once: one listed only its own topics)
        quiet = now - changed >= timing.quiet_s or (not young and age >= floor + timing.quiet_s)
        missing = bool(current.missing_participants) and young
        if age >= floor and quiet and not current.unknown_endpoints and not missing:
            return current
        waited = now - start
        named = not current.unknown_endpoints or waited >= NAME_WAIT_S
        if age >= floor and waited >= timing.unknown_wait_s and named:
            return current
        sleep(POLL_S)
        seen = view()
        if seen != current:
            current, changed = seen, clock()


# A node's name (its participant's `ros_discovery_info`) can arrive moments before its first
# endpoint: a name no seen participant holds is a ghost only once listed this long.
GHOST_GRACE_S = 1.0


def without_ghosts(
    names: Sequence[str],
    holders: Mapping[str, set[tuple[int, ...]]],
    settled: bool,
    *,
    listed_for: Mapping[str, float] | None = None,
) -> list[str]:
    """Return `names` (full node names, in the graph's order) less the ghosts.

    A node that has left can stay in a long-lived client's node list with no participant
    behind it (the graph cache re-adds a participant's node info that arrives after the
    participant's removal; the real daemon shows such ghosts too: ros2/ros2#1413). `holders`
    maps a node name to the participants seen holding its endpoints. Once the graph is
    `settled` (every participant bound on this host has been seen), a name is listed as many
    times as participants hold it; a name none holds is dropped once this client has listed
    it for GHOST_GRACE_S (`listed_for`, seconds; a name not in it is new, and kept once).
    """
    if not settled:
        return list(names)
    ages = listed_for or {}

    def allowed(name: str) -> int:
        held = len(holders.get(name, ()))
        if held:
            return held
        return 0 if ages.get(name, 0.0) >= GHOST_GRACE_S else 1

    counts = Counter(names)
    left = {name: allowed(name) for name in counts}
    if all(left[name] >= count for name, count in counts.items()):
        return list(names)
    kept = []
    for name in names:
        if left[name] > 0:
            kept.append(name)
            left[name] -= 1
    return kept
