"""The one /proc reader answers for this process as the kernel does, and None for no process."""

from __future__ import annotations

import os

from course_lib.core.host import procfs

UDP = """  sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid
   0: 0100007F:1CE8 00000000:0000 07 00000000:00000000 00:00000000 00000000     0
   1: 00000000000000000000000000000000:6A18 00000000000000000000000000000000:0000 07
"""


def test_this_process_reads_as_itself() -> None:
    me = os.getpid()
    assert procfs.parent_pid(me) == os.getppid()
    assert procfs.pid_alive(me) and procfs.start_time(me) == procfs.holder_start(me)
    assert procfs.owner_uid(me) == os.getuid()
    assert (procfs.cmdline(me) or ("",))[0].rsplit("/", 1)[-1].startswith("python")
    assert procfs.environ(me).get("PATH") == os.environ.get("PATH")
    assert me in procfs.pids()
    assert procfs.network_namespace(me) == procfs.network_namespace()
    assert (procfs.network_namespace(me) or "").startswith("net:[")


def test_a_missing_process_reads_as_none() -> None:
    gone = 2**22 + 1  # above pid_max's largest value
    assert procfs.stat_fields(gone) is None and not procfs.pid_alive(gone)
    assert procfs.parent_pid(gone) == 0 and procfs.cmdline(gone) is None
    assert procfs.environ(gone) == {} and procfs.owner_uid(gone) is None
    assert procfs.network_namespace(gone) is None


def test_udp_tables_give_local_ports_of_ipv4_and_ipv6() -> None:
    assert procfs.udp_ports([UDP]) == {0x1CE8, 0x6A18}
    assert procfs.udp_ports([]) == set()


def test_maps_library_names_what_a_process_has_loaded() -> None:
    me = os.getpid()
    assert procfs.maps_library(me, "libc.so")  # every CPython on glibc
    assert not procfs.maps_library(me, "libno_such_library.so")
    assert not procfs.maps_library(2**22 + 1, "libc.so")  # no such process
