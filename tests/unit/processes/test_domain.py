"""Domain leases: explicit ids are honoured, free ids are leased, leases exclude others."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
from collections.abc import Iterator

import pytest

from course_lib.processes.domain import (
    candidate_domains,
    domain_in_use,
    isolation_env,
    lease_domain,
    lease_port,
    port_block,
)

HOLDER = (
    "from course_lib.processes.domain import lease_domain; import sys;"
    "l = lease_domain({}); print(l.domain_id, flush=True); sys.stdin.read()"
)


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
        [sys.executable, "-c", HOLDER],
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


def test_lease_port_is_in_the_domains_block_but_no_dds_port() -> None:
    for domain_id in candidate_domains(1):
        block = port_block(domain_id)
        assert lease_port(domain_id) in block
        # Fast DDS binds offsets 0, 1 (multicast) and 10 + 2 i, 11 + 2 i (participant i)
        assert lease_port(domain_id) - block.start not in (0, 1, *range(10, 250))
        assert block.stop <= 65536 and len(block) >= 136  # room for 63 participants


@pytest.fixture
def dds_socket() -> Iterator[tuple[int, socket.socket]]:
    """Bind a UDP socket where a DDS participant of a free domain would (offset 10)."""
    probe = lease_domain({})
    domain_id = probe.domain_id
    probe.release()
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind(("0.0.0.0", port_block(domain_id).start + 10))
    try:
        yield domain_id, sock
    finally:
        sock.close()


def test_a_domain_whose_dds_ports_are_bound_is_skipped(dds_socket) -> None:
    domain_id, _sock = dds_socket
    assert domain_in_use(domain_id)
    lease = lease_domain({}, start=domain_id)
    try:
        assert lease.domain_id != domain_id
    finally:
        lease.release()


def test_a_killed_holders_domain_is_free_again() -> None:
    holder = subprocess.Popen(
        [sys.executable, "-c", HOLDER], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
    )
    held = int(holder.stdout.readline())
    blocked = lease_domain({}, start=held)
    assert blocked.domain_id != held
    blocked.release()
    os.kill(holder.pid, signal.SIGKILL)  # no clean-up code runs: the kernel frees the port
    holder.communicate()
    again = lease_domain({}, start=held)
    try:
        assert again.domain_id == held
    finally:
        again.release()
