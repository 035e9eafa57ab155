"""The hub SIGKILLed, then started again on the same state folder (issue 62, item 3): no
progress record the service acknowledged is lost, and the service takes new ones after.

The progress service is not the hub's child but its launcher's (ClassHub stands in for it):
killing JupyterHub takes its proxy with it (tied) and leaves the service running until the
launcher notices, and then stops it (course_lib/hub/launcher.py: run_hub). Meanwhile the
service still answers the kernels, which post to its port directly: a token the service has
checked in the last five minutes (HubAuth's cache) is still taken, any other is refused with
a 500 (the service cannot ask the hub who it is), which the learner's kernel says in one line.
"""

from __future__ import annotations

import contextlib
import signal
from typing import Any

import psutil
import pytest
from progress_hub import ADMIN, ADMIN_PASSWORD, ClassHub

from course_lib.core.waiting import wait_until
from course_lib.hub.progress import PROGRESS_HOLDER_ENV, PROGRESS_URL_ENV, SERVICE_NAME
from course_lib.lessons.progress import client
from course_lib.lessons.progress.record import Record
from course_lib.lessons.report import SelfCheck, check

pytestmark = pytest.mark.slow
PAGE = f"/services/{SERVICE_NAME}/"
BEFORE = (
    Record("alice", 1, True),
    Record("alice", 2, False, "The node runs"),
    Record("bob", 1, False, "Velocity is 0.2"),
    Record("alice", 7, False, "", "07 drive", 1),
    Record("alice", 7, True, "", "07 drive", 2),
    Record("bob", 7, False, "", "07 drive", 1),
)
WHILE_DEAD = Record("alice", 3, True)  # her token was checked minutes ago: still taken


def send(server: dict[str, str], record: Record) -> None:
    """Post `record` as the learner's kernel does; return only once the service said 201."""
    holder = int(server[PROGRESS_HOLDER_ENV])
    token = server["JUPYTERHUB_API_TOKEN"]
    client.send_record(server[PROGRESS_URL_ENV], token, record, holder=holder)


def report(server: dict[str, str], lesson_check: SelfCheck) -> None:
    """Run the reporting client as a learner's kernel does (quietly), and wait for it."""
    client._warned.clear()
    thread = client.report_progress(lesson_check, environ=server)
    assert thread is not None
    thread.join(timeout=10)


def stored(hub: ClassHub) -> dict[str, Any]:
    """Return the records API's answer, as an admin logged in just now sees it."""
    admin = hub.login(ADMIN, ADMIN_PASSWORD)
    page = admin.get(hub.url + PAGE, timeout=10)  # the service's OAuth login, page shown
    assert page.status_code == 200 and all(n in page.text for n in ("alice", "bob", "carol"))
    answer = admin.get(f"{hub.url}{PAGE}api/records", timeout=10)
    assert answer.status_code == 200, answer.text
    return answer.json()


def by_lesson(answer: dict[str, Any]) -> dict[tuple[str, int], dict[str, Any]]:
    """Return each learner's state in each lesson, by (learner, lesson)."""
    return {(r["user"], r["lesson"]): r for r in answer["records"]}


def drive_stats(answer: dict[str, Any]) -> tuple[int, int, float | None]:
    """Return lesson 7's exercise: how many tried it, passed it, the median attempts."""
    (stats,) = [s for s in answer["exercises"] if s["exercise"] == "07 drive"]
    return stats["tried"], stats["passed"], stats["median_attempts"]


def kill_hub(hub: ClassHub) -> tuple[list[psutil.Process], list[psutil.Process]]:
    """SIGKILL JupyterHub as test_hub_killed.py does; return what it had started: its proxy,
    and the rest (the learners' servers)."""
    assert hub.process is not None
    children = psutil.Process(hub.process.pid).children(recursive=True)
    proxies = [c for c in children if "configurable-http-proxy" in " ".join(c.cmdline())]
    hub.process.send_signal(signal.SIGKILL)
    hub.process.wait()
    return proxies, [c for c in children if c not in proxies]


def _alive(process: psutil.Process) -> bool:
    with contextlib.suppress(psutil.Error):
        return process.status() != psutil.STATUS_ZOMBIE
    return False


def test_a_killed_hub_started_again_keeps_every_acknowledged_record(
    tmp_path_factory: pytest.TempPathFactory, proxy: str, capsys: pytest.CaptureFixture[str]
) -> None:
    hub = ClassHub(tmp_path_factory.mktemp("hub-killed-progress"), proxy)
    servers_left: list[psutil.Process] = []
    try:
        hub.start()
        servers = {name: hub.spawn(name) for name in ("alice", "bob", "carol")}
        for record in BEFORE:
            send(servers[record.user], record)
        before = stored(hub)
        assert len(before["records"]) == 3 and drive_stats(before) == (2, 1, 2)

        proxies, servers_left = kill_hub(hub)
        assert proxies and wait_until(lambda: not any(map(_alive, proxies)), 10.0)
        assert hub.service is not None and hub.service.poll() is None, "the launcher's"
        send(servers["alice"], WHILE_DEAD)
        report(servers["carol"], SelfCheck.of(4, [check("The launch file starts", True)]))
        said = capsys.readouterr().err
        assert "did not get this self-check: the service answered 500" in said, said
        assert "Your lesson is not affected" in said and "Traceback" not in said

        hub.stop()  # the launcher's part: the hub is dead already, its service stops now
        hub.start()  # the same state folder: the hub's database, the records
        after = stored(hub)
        states = by_lesson(after)
        taken_while_dead = states.pop(("alice", 3), {})
        assert states == by_lesson(before), "a record acknowledged before the kill changed"
        assert drive_stats(after) == drive_stats(before), "an exercise's attempts changed"
        assert taken_while_dead.get("passed") is True, "the record taken while dead is lost"

        # the learners' servers outlived the hub (the stand-in spawner does not tie them) and
        # the new hub took them back: their tokens are good, new records are taken
        report(servers["carol"], SelfCheck.of(4, [check("The launch file starts", True)]))
        assert capsys.readouterr().err == ""
        send(servers["bob"], Record("bob", 7, True, "", "07 drive", 2))
        again = stored(hub)
        assert by_lesson(again)[("carol", 4)]["passed"] is True
        assert drive_stats(again) == (2, 2, 2)
    finally:
        hub.close()
        for server in servers_left:  # the stand-in servers, if the new hub did not take them
            with contextlib.suppress(psutil.Error):
                server.kill()
