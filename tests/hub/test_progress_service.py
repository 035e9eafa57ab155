"""The course-progress service on a real JupyterHub: who may post, who may see, what is kept.

Learners' tokens are real server tokens (JUPYTERHUB_API_TOKEN) from real spawns, so these
tests also prove that the `server` role of course_lib.hub.progress.roles() lets a kernel post.
"""

from __future__ import annotations

import time
from html.parser import HTMLParser

import pytest
import requests
from progress_hub import ADMIN, ADMIN_PASSWORD, PASSWORD, ClassHub

from course_lib.hub.progress import SERVICE_NAME
from course_lib.hub.progress.app import MAX_BODY_BYTES, MAX_READ_BYTES
from course_lib.lessons.progress import client as progress_report
from course_lib.lessons.report import SelfCheck, check

pytestmark = pytest.mark.slow
PAGE = f"/services/{SERVICE_NAME}/"


class _Table(HTMLParser):
    """The page's rows: learner name -> the text and class of each lesson's cell."""

    def __init__(self) -> None:
        super().__init__()
        self.rows: dict[str, list[tuple[str, str]]] = {}
        self._row: list[tuple[str, str]] | None = None
        self._cell: list[str] | None = None
        self._class = ""

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if tag == "tr":
            self._row = []
        elif tag == "td" and self._row is not None:
            self._cell, self._class = [], dict(attrs).get("class") or ""

    def handle_data(self, data: str) -> None:
        if self._cell is not None:
            self._cell.append(data)

    def handle_endtag(self, tag: str) -> None:
        if tag == "td" and self._row is not None and self._cell is not None:
            self._row.append(("".join(self._cell), self._class))
            self._cell = None
        elif tag == "tr" and self._row:
            (name, _), *cells = self._row
            self.rows[name] = cells
            self._row = None


def rows_of(html: str) -> dict[str, list[tuple[str, str]]]:
    """Return the progress page's rows: name -> [(cell text, cell class)] for lessons 1-11."""
    table = _Table()
    table.feed(html)
    return table.rows


@pytest.fixture(scope="module")
def admin(hub: ClassHub) -> requests.Session:
    """Return the admin's browser-like session, logged in to the hub and to the service."""
    session = hub.login(ADMIN, ADMIN_PASSWORD)
    page = session.get(hub.url + PAGE, timeout=10)  # the OAuth login to the service
    assert page.status_code == 200, page.text
    return session


def servers(hub: ClassHub) -> dict[str, dict[str, str]]:
    """Return each learner's server environment, spawning each server once per hub start."""
    cache = hub.__dict__.setdefault("envs", {})
    for name in ("alice", "bob"):
        if name not in cache:
            cache[name] = hub.spawn(name)
    return cache


def post(hub: ClassHub, token: str | None, body: object, *, raw: bytes | None = None):
    """POST to the records API directly (as a kernel does) with `token`."""
    headers = {"Authorization": f"token {token}"} if token else {}
    url = hub.service_url + "api/records"
    if raw is not None:
        return requests.post(url, data=raw, headers=headers, timeout=10)
    return requests.post(url, json=body, headers=headers, timeout=10)


def records(admin: requests.Session, hub: ClassHub) -> list[dict]:
    """Return every stored record (the admin's view of the API, through the hub's proxy)."""
    answer = admin.get(f"{hub.url}{PAGE}api/records", timeout=10)
    assert answer.status_code == 200, answer.text
    return answer.json()["records"]


def report(env: dict[str, str], lesson_check: SelfCheck) -> None:
    """Run the lessons' reporting client as a learner's kernel does, and wait for it."""
    progress_report._warned.clear()
    thread = progress_report.report_progress(lesson_check, environ=env)
    assert thread is not None, "the client sent nothing with the server's environment"
    thread.join(timeout=10)


def test_a_self_check_reaches_the_admins_page(hub: ClassHub, admin: requests.Session) -> None:
    alice = servers(hub)["alice"]
    report(alice, SelfCheck.of(7, [check("The robot drives at 0.2 m/s", True)]))
    page = admin.get(hub.url + PAGE, timeout=10)
    assert page.status_code == 200 and page.url == hub.url + PAGE, page.url
    rows = rows_of(page.text)
    text, kind = rows["alice"][6]
    assert kind == "passed" and "✓" in text, rows["alice"]
    assert {"alice", "bob", "carol"} <= set(rows), "every learner the hub knows has a row"
    assert ADMIN not in rows, "the admin is not a learner"
    assert all(kind == "empty" for _, kind in rows["carol"])


def test_a_failed_check_shows_what_failed(hub: ClassHub, admin: requests.Session) -> None:
    alice = servers(hub)["alice"]
    checks = [check("The node runs", True), check("Velocity <b>is</b> 0.2", False, "set it")]
    report(alice, SelfCheck.of(5, checks))
    page = admin.get(hub.url + PAGE, timeout=10)
    text, kind = rows_of(page.text)["alice"][4]
    assert kind == "failed" and "Velocity <b>is</b> 0.2" in text, text
    assert "Velocity <b>" not in page.text, "the failed check's text must be escaped"


def test_a_token_cannot_post_for_another_learner(
    hub: ClassHub, admin: requests.Session, capsys: pytest.CaptureFixture[str]
) -> None:
    bob = servers(hub)["bob"]
    answer = post(hub, bob["JUPYTERHUB_API_TOKEN"], {"user": "alice", "lesson": 3,
                                                     "passed": True, "failed": ""})  # fmt: skip
    assert answer.status_code == 403, answer.text
    assert "bob" in answer.json()["error"]
    # the client says so in one line when its environment names someone else
    report({**bob, "JUPYTERHUB_USER": "alice"}, SelfCheck.of(3, [check("x", True)]))
    said = capsys.readouterr().err
    assert "did not get this self-check" in said and "403" in said, said
    assert not [r for r in records(admin, hub) if r["lesson"] == 3], "nothing may be stored"


@pytest.mark.parametrize("token", [None, "not-a-token-the-hub-issued"])
def test_no_or_unknown_token_is_refused(
    hub: ClassHub, admin: requests.Session, token: str | None
) -> None:
    answer = post(hub, token, {"user": "alice", "lesson": 2, "passed": True, "failed": ""})
    assert answer.status_code == (401 if token is None else 403), answer.text
    assert not [r for r in records(admin, hub) if r["lesson"] == 2]


@pytest.mark.parametrize(
    ("body", "says"),
    [
        (b"{not json", "not JSON"),
        (b'{"user": "alice", "lesson": 12, "passed": true, "failed": ""}', "1 to 11"),
        (b'{"user": "alice", "lesson": 0, "passed": true, "failed": ""}', "1 to 11"),
        (b'{"user": "alice", "lesson": 4, "passed": "yes", "failed": ""}', '"passed"'),
        (b'{"user": "alice", "lesson": 4, "passed": true, "score": 1}', "score"),
    ],
)
def test_a_bad_record_is_400(
    hub: ClassHub, admin: requests.Session, body: bytes, says: str
) -> None:
    alice = servers(hub)["alice"]
    answer = post(hub, alice["JUPYTERHUB_API_TOKEN"], None, raw=body)
    assert answer.status_code == 400, answer.text
    assert says in answer.json()["error"]
    assert not [r for r in records(admin, hub) if r["lesson"] in (0, 4, 12)]


@pytest.mark.parametrize("size", [MAX_BODY_BYTES + 1, 10 * MAX_READ_BYTES])
def test_a_huge_body_is_refused_before_anything_is_read_or_stored(
    hub: ClassHub, admin: requests.Session, size: int
) -> None:
    """Anyone on the host can reach the service: a body of any size must not cost it memory."""
    padding = "x" * size
    body = f'{{"user": "alice", "lesson": 5, "passed": true, "failed": "{padding}"}}'.encode()
    try:
        answer = post(hub, None, None, raw=body)
    except (requests.ConnectionError, requests.exceptions.ChunkedEncodingError):  # refused unread
        answer = None
    if answer is not None:
        assert answer.status_code in (400, 413), answer.text
        if size <= MAX_READ_BYTES:
            assert answer.status_code == 413 and "at most 4096 bytes" in answer.text
    assert not [r for r in records(admin, hub) if padding[:100] in str(r)]


def test_a_learner_cannot_see_the_page(hub: ClassHub) -> None:
    bob = hub.login("bob", PASSWORD)
    page = bob.get(hub.url + PAGE, timeout=10)
    assert page.status_code == 403, (page.status_code, page.url)
    assert "alice" not in page.text
    listing = bob.get(f"{hub.url}{PAGE}api/records", timeout=10)
    assert listing.status_code == 403 and "alice" not in listing.text


def test_anonymous_is_sent_to_the_hub_login(hub: ClassHub) -> None:
    page = requests.get(hub.url + PAGE, timeout=10)
    assert page.url.startswith(f"{hub.url}/hub/login"), page.url
    assert "alice" not in page.text


def test_records_survive_a_restart_of_the_hub(hub: ClassHub, admin: requests.Session) -> None:
    bob = servers(hub)["bob"]
    report(bob, SelfCheck.of(9, [check("The file sets velocity", True)]))
    before = records(admin, hub)
    assert any(r["user"] == "bob" and r["lesson"] == 9 and r["passed"] for r in before)
    started = time.monotonic()
    hub.stop()
    hub.start()
    hub.__dict__.pop("envs", None)  # the servers (and their tokens) stopped with the hub
    restarted = time.monotonic() - started
    again = hub.login(ADMIN, ADMIN_PASSWORD)
    page = again.get(hub.url + PAGE, timeout=10)  # the OAuth login to the new service
    assert rows_of(page.text)["bob"][8][1] == "passed", page.text
    assert records(again, hub) == before, f"records changed across a restart ({restarted:.1f} s)"


def test_exercise_pass_rates_and_median_attempts_from_two_learners(hub: ClassHub) -> None:
    """Each attempt goes as a skill exercise's check sends it, with the learner's own token."""
    admin = hub.login(ADMIN, ADMIN_PASSWORD)  # its own login: an earlier test restarts the hub
    assert admin.get(hub.url + PAGE, timeout=10).status_code == 200  # the service's OAuth
    envs = servers(hub)
    attempts = {"alice": [False, True], "bob": [False, False, False, True]}
    for user, verdicts in attempts.items():
        for number, passed in enumerate(verdicts, 1):
            thread = progress_report.report_attempt(
                9, "09 params file", number, passed, envs[user]
            )
            assert thread is not None
            thread.join(timeout=10)
    progress_report.report_attempt(10, "10 launch file", 1, False, envs["bob"]).join(10)
    answer = admin.get(f"{hub.url}{PAGE}api/records", timeout=10).json()["exercises"]
    stats = {s["exercise"]: s for s in answer}
    assert stats["09 params file"]["pass_rate"] == 1.0
    assert stats["09 params file"]["median_attempts"] == 3.0  # 2 and 4
    assert (stats["10 launch file"]["tried"], stats["10 launch file"]["passed"]) == (1, 0)
    page = admin.get(hub.url + PAGE, timeout=10).text
    assert "09 params file" in page and "100 %" in page and ">3<" in page
    assert "0 of 1" in page
