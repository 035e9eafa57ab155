"""The hub's admission: connections counted per account (or address), root held only to the
total, and refusals said in a few lines however many there were (issue 65: 710k lines)."""

from __future__ import annotations

from course_lib.hub.guard.admission import MAX_LINES, Admission
from course_lib.hub.guard.peers import Peer

EVE, ROOT = Peer(uid=4_000_005), Peer(uid=0)  # EVE: a uid no account has


def test_an_account_past_its_limit_is_refused_until_one_closes() -> None:
    admission = Admission(per_peer=3, total=100)
    assert [admission.admit(EVE) for _ in range(5)] == [True, True, True, False, False]
    assert admission.admit(Peer(uid=1006))  # another account has its own count
    admission.release(EVE)
    assert admission.admit(EVE)
    assert admission.held(EVE) == 3 and admission.held() == 4


def test_root_is_held_only_to_the_total() -> None:
    admission = Admission(per_peer=2, total=10)
    assert all(admission.admit(ROOT) for _ in range(10))
    assert not admission.admit(ROOT) and not admission.admit(EVE)
    assert admission.report("The hub", 10.0) == [
        "The hub refused 2 connection(s) in the last 10 s: it held 10, as many as its open "
        "files allow."
    ]


def test_refusals_are_said_in_a_few_lines_then_forgotten() -> None:
    admission = Admission(per_peer=1, total=1_000_000)
    for address in range(50):
        peer = Peer(address=f"10.0.0.{address}")
        for _ in range(1 + address):  # the first is admitted
            admission.admit(peer)
    for _ in range(100_001):
        admission.admit(EVE)
    lines = admission.report("The hub", 10.0)
    assert len(lines) == MAX_LINES + 1
    assert lines[0].startswith("The hub refused 100000 connection(s) of uid 4000005 in the last")
    assert "address 10.0.0.49" in lines[1]
    assert lines[-1] == "The hub refused 1035 more connection(s) of 45 other(s)."
    assert admission.report("The hub", 10.0) == []
