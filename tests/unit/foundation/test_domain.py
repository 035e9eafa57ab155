"""Domain leases: explicit ids are honoured, free ids are locked, locks exclude others."""

from __future__ import annotations

import subprocess
import sys

from course_lib.domain import candidate_domains, isolation_env, lease_domain


def test_explicit_domain_is_used_without_a_lock() -> None:
    lease = lease_domain({"ROS_DOMAIN_ID": "42"})
    assert lease.domain_id == 42
    assert not lease.is_locked


def test_candidates_skip_domain_zero_and_unusable_ports() -> None:
    ids = list(candidate_domains(100))
    assert ids[:4] == [100, 101, 215, 216]
    assert 0 not in ids and 102 not in ids and 233 not in ids
    assert len(ids) == len(set(ids)) == 101 + 18


def test_two_leases_in_one_process_differ() -> None:
    first, second = lease_domain({}), lease_domain({})
    try:
        assert first.domain_id != second.domain_id
    finally:
        first.release()
        second.release()


def test_a_lease_held_by_another_process_is_skipped() -> None:
    holder = subprocess.Popen(
        [
            sys.executable,
            "-c",
            "from course_lib.domain import lease_domain; import sys;"
            "l = lease_domain({}); print(l.domain_id, flush=True); sys.stdin.read()",
        ],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        held = int(holder.stdout.readline())
        leases = [lease_domain({}) for _ in range(5)]
        assert held not in [lease.domain_id for lease in leases]
        for lease in leases:
            lease.release()
    finally:
        holder.communicate("")


def test_isolation_env_keeps_discovery_on_localhost() -> None:
    env = isolation_env(7)
    assert env["ROS_DOMAIN_ID"] == "7"
    assert env["ROS_AUTOMATIC_DISCOVERY_RANGE"] == "LOCALHOST"
