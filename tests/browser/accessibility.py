"""axe-core (WCAG 2.1 A and AA rules) run in a page or frame the browser tests drive.

axe-core is installed from npm at the version pinned in `tests/browser/axe/` (once per run,
into a folder the xdist workers share, one install at a time). `audit` runs it in a page or a
frame and returns the violations of impact critical or serious, each with the elements it
found; `within` keeps those inside the course's own parts (JupyterLab's are listed apart).
"""

from __future__ import annotations

import fcntl
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path
from typing import Any

__all__ = [
    "OUTPUTS",
    "PINS",
    "WCAG_TAGS",
    "Violation",
    "audit",
    "audit_lesson",
    "axe_source",
    "report",
    "within",
]

PINS = Path(__file__).resolve().with_name("axe")  # package.json and its lock file
WCAG_TAGS = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa"]
BLOCKING = ("critical", "serious")
OUTPUTS = ".jp-OutputArea-output"  # what a lesson's cells print and show: the course's
VIEW = 'iframe[title="3D view of the simulated robot"]'


@dataclass(frozen=True)
class Violation:
    """One rule broken on one element: the rule's id, its impact, the element's selector
    (a path through frames and shadow roots, axe's own) and its HTML, shortened."""

    rule: str
    impact: str
    target: str
    html: str
    help: str

    def line(self) -> str:
        return f"{self.impact} {self.rule} at {self.target}: {self.help} ({self.html[:120]})"


def axe_source(cache: Path) -> str:
    """Return axe.min.js, installed with `npm ci` into `cache` (again only when the pins
    changed); shared by the xdist workers, one install at a time."""
    cache.mkdir(parents=True, exist_ok=True)
    with open(cache / ".axe.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        script = cache / "node_modules" / "axe-core" / "axe.min.js"
        pins = ("package.json", "package-lock.json")
        same = all(
            (cache / n).exists() and (cache / n).read_bytes() == (PINS / n).read_bytes()
            for n in pins
        )
        if not (same and script.exists()):
            for name in pins:
                shutil.copyfile(PINS / name, cache / name)
            npm = shutil.which("npm")
            assert npm, "npm installs axe-core for the accessibility tests (apt-get install npm)"
            done = subprocess.run(
                [npm, "ci", "--no-audit", "--no-fund", "--loglevel=error"],
                cwd=cache, capture_output=True, text=True, check=False,
            )  # fmt: skip
            assert done.returncode == 0 and script.exists(), done.stderr
        return script.read_text(encoding="utf-8")


_RUN = """async ([include, tags]) => {
  const context = include.length ? {include: include.map((s) => [s])} : document;
  const result = await axe.run(context, {runOnly: {type: 'tag', values: tags}});
  return result.violations.flatMap((v) => v.nodes.map((n) => ({
    rule: v.id, impact: n.impact || v.impact, target: JSON.stringify(n.target),
    html: n.html, help: v.help})));
}"""


def audit(where: Any, source: str, include: list[str] | None = None) -> list[Violation]:
    """Run axe in `where` (a Playwright page or frame) on the elements `include` selects
    (the whole document if none); return its critical and serious violations."""
    if not where.evaluate("() => typeof window.axe === 'object'"):
        where.add_script_tag(content=source)
    found = where.evaluate(_RUN, [include or [], WCAG_TAGS])
    return [Violation(**item) for item in found if item["impact"] in BLOCKING]


def within(violations: list[Violation], *marks: str) -> list[Violation]:
    """Keep the violations whose element's selector or HTML holds one of `marks` (the
    course's own class names, ids or frame titles)."""
    return [v for v in violations if any(m in v.target or m in v.html for m in marks)]


def report(violations: list[Violation]) -> str:
    """Return the violations one per line, with a count per rule first."""
    counts: dict[str, int] = {}
    for v in violations:
        counts[f"{v.impact} {v.rule}"] = counts.get(f"{v.impact} {v.rule}", 0) + 1
    summary = ", ".join(f"{n} {rule}" for rule, n in sorted(counts.items()))
    return "\n".join([summary or "none", *(v.line() for v in violations[:40])])


def audit_lesson(
    page: Any, source: str, *, with_jupyterlab: bool = False
) -> dict[str, list[Violation]]:
    """Audit a JupyterLab page showing a lesson that ran: return the violations in its
    cells' outputs ("outputs") and in its 3D views' frames ("view"); `with_jupyterlab`, also
    JupyterLab's own ("jupyterlab", listed apart: the course does not draw them). The whole
    page's audit grows with every notebook open (about as much as the rest): a walk asks for
    it once, with all its lessons open."""
    course = audit(page, source, [OUTPUTS])
    frames = [h.content_frame() for h in page.locator(VIEW).element_handles()]
    views = [v for frame in frames if frame is not None for v in audit(frame, source)]
    audited = {"outputs": course, "view": views}
    if with_jupyterlab:
        mine = {(v.rule, v.target) for v in course}
        whole = audit(page, source)
        lab = [v for v in whole if (v.rule, v.target) not in mine and "iframe" not in v.target]
        audited["jupyterlab"] = lab
    return audited
