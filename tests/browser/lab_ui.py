"""What a learner does in one JupyterLab with several lessons open, from its menus and tabs.

Every action waits on what the page shows (never on time) and fails, with the dialog's text,
if JupyterLab asks something the learner did not ask for (the "Select Kernel" dialog).
"""

from __future__ import annotations

import contextlib
import re
from dataclasses import dataclass
from typing import Any

from playwright.sync_api import Error as PlaywrightError
from playwright.sync_api import TimeoutError as PlaywrightTimeout
from waits import POLL_MS

__all__ = [
    "Cell",
    "LabPage",
    "UnexpectedDialog",
]

_PANEL = ".jp-NotebookPanel:not(.lm-mod-hidden)"
# The notebook in front, read from JupyterLab's own model (the lab runs with
# --LabApp.expose_app_in_browser): every cell, whether or not the page has drawn it yet.
_FRONT = """const front = () => {
  const widget = window.jupyterapp.shell.currentWidget;
  return widget && widget.content && widget.content.widgets ? widget : null;
};
const codeCells = () => {
  const widget = front();
  return widget ? widget.content.widgets.filter((c) => c.model.type === 'code') : [];
};"""
_CELLS = f"""() => {{
  {_FRONT}
  return codeCells().map((cell) => ({{
    source: cell.model.sharedModel.getSource(),
    count: cell.model.executionCount,
    outputs: cell.model.outputs.toJSON(),
  }}));
}}"""
# Watch the notebook in front: did a cell show `[*]` (queued or running) since armed?
_HAS_SESSION = "() => !!window.jupyterapp.shell.currentWidget?.sessionContext?.session"
_ARM = f"""() => {{
  {_FRONT}
  const panel = document.querySelector('{_PANEL}');
  const busy = () => codeCells().some((c) => c.model.executionState === 'running')
    || [...panel.querySelectorAll('.jp-InputPrompt')].some((p) => p.textContent.includes('*'));
  const counts = () => codeCells().map((c) => c.model.executionCount).join('|');
  const watch = {{seen: busy(), before: counts(), busy, counts}};
  watch.observer = new MutationObserver(() => {{ if (busy()) watch.seen = true; }});
  watch.observer.observe(panel, {{subtree: true, childList: true, characterData: true}});
  window.__walkWatch = watch;
}}"""
# Done: nothing queued or running and something ran (for one cell: or its count changed), or a
# dialog is shown.
_SETTLED = """(oneCell) => {
  const w = window.__walkWatch;
  if (document.querySelector('.jp-Dialog')) return true;
  const busy = w.busy();
  if (busy) w.seen = true;
  const done = !busy && (w.seen || (oneCell && w.counts() !== w.before));
  if (done) w.observer.disconnect();
  return done;
}"""
_KERNEL_STATUS = ".jp-StatusBar-Widget"
_ACTION_TIMEOUT_MS = 120_000
_DRAWN_MS = 30_000  # a cell scrolled into view gets its editor within this, loaded or not


class UnexpectedDialog(AssertionError):
    """JupyterLab showed a dialog the learner did not ask for (e.g. "Select Kernel")."""


@dataclass(frozen=True)
class Cell:
    """One code cell of the notebook in front: its source, execution count and outputs."""

    index: int
    source: str
    count: int | None
    outputs: tuple[dict[str, Any], ...]

    @property
    def ran(self) -> bool:
        """Return True if the cell shows an execution count (`[12]:`)."""
        return self.count is not None

    @property
    def text(self) -> str:
        """Return its outputs' text (streams, plain text of results, error name and value)."""
        return "".join(_output_text(output) for output in self.outputs)

    def first_line(self) -> str:
        """Return the first line of its source (to name it in messages)."""
        return self.source.strip().splitlines()[0] if self.source.strip() else "<empty>"


def _output_text(output: dict[str, Any]) -> str:
    kind = output.get("output_type")
    if kind == "stream":
        text = output.get("text", "")
    elif kind == "error":
        text = f"{output.get('ename')}: {output.get('evalue')}\n"
    else:
        text = output.get("data", {}).get("text/plain", "")
    return "".join(text) if isinstance(text, list) else text


class LabPage:
    """One browser tab on one JupyterLab, with its file browser on the lessons' folder."""

    def __init__(self, page: Any, lab: Any, timeout_s: float = 300.0) -> None:
        self.page, self.lab = page, lab
        self.timeout_ms = timeout_s * 1000
        # A click is done when the page took it: a page drawing a live 3D view in software on
        # a busy machine can take longer than Playwright's default 30 s.
        page.set_default_timeout(_ACTION_TIMEOUT_MS)
        folder = lab.folder.relative_to(_repo_root())
        page.goto(f"{lab.base_url}/lab/tree/{folder}?reset&token={lab.token}")
        page.locator(".jp-DirListing-item").first.wait_for()

    # --- what the page shows ---------------------------------------------------------------
    def cells(self) -> list[Cell]:
        """Return the visible notebook's code cells."""
        return [
            Cell(i, c["source"], c["count"], tuple(c["outputs"]))
            for i, c in enumerate(self.page.evaluate(_CELLS))
        ]

    def cell_with(self, source: str, last: bool = False) -> Cell:
        """Return the (first or last) code cell whose source contains `source`."""
        found = [c for c in self.cells() if source in c.source]
        assert found, f"no cell of {self.current()} contains {source!r}"
        return found[-1] if last else found[0]

    def current(self) -> str:
        """Return the file name of the notebook tab in front."""
        return self.page.evaluate(
            "() => (document.querySelector('.lm-DockPanel-tabBar .lm-TabBar-tab.lm-mod-current"
            " .lm-TabBar-tabLabel') || {}).textContent || ''"
        )

    def kernel_status(self) -> str:
        """Return the status bar's kernel text, e.g. "Python 3 (ipykernel) | Idle"."""
        text = self.page.locator(_KERNEL_STATUS).first.inner_text()
        found = re.search(r"^(.*\|\s*\w+)\s*$", text, re.M)
        return found[1] if found else text

    def dialog_text(self) -> str:
        """Return the text of the dialog JupyterLab shows, or ""."""
        dialogs = self.page.locator(".jp-Dialog")
        return dialogs.first.inner_text() if dialogs.count() else ""

    def fail_on_dialog(self, doing: str) -> None:
        """Fail (closing the dialogs, so a walk can go on) if a dialog is shown."""
        texts = self.dismiss_dialogs()
        if texts:
            raise UnexpectedDialog(f"JupyterLab asked, after {doing}:\n" + "\n".join(texts))

    def dismiss_dialogs(self, most: int = 5) -> list[str]:
        """Close the dialogs shown (Cancel where there is one, else Escape); return their text."""
        texts = []
        dialogs = self.page.locator(".jp-Dialog")
        while (shown := dialogs.count()) and len(texts) < most:
            texts.append(dialogs.first.inner_text())
            reject = dialogs.first.locator("button.jp-mod-reject")
            if reject.count():
                reject.first.click()
            else:
                self.page.keyboard.press("Escape")
            with contextlib.suppress(PlaywrightTimeout):  # another dialog took its place
                self.page.wait_for_function(
                    "(shown) => document.querySelectorAll('.jp-Dialog').length < shown",
                    arg=shown,
                    timeout=10_000,
                    polling=POLL_MS,
                )
        return texts

    # --- opening and switching ------------------------------------------------------------------
    def open(self, name: str) -> None:
        """Open lesson file `name` from the file browser (double-click) and wait for its kernel."""
        named = re.compile(rf"^{re.escape(name)}")
        self.page.locator(".jp-DirListing-item", has_text=named).dblclick()
        self._wait_in_front(name)
        self._wait_kernel(r"\| Idle$", f"opening {name}")

    def show(self, name: str) -> None:
        """Bring the already open notebook `name` to the front by clicking its tab."""
        label = self.page.locator(
            ".lm-TabBar-tabLabel", has_text=re.compile(rf"^{re.escape(name)}$")
        )
        tab = self.page.locator(".lm-DockPanel-tabBar .lm-TabBar-tab").filter(has=label)
        tab.click()
        self._wait_in_front(name)

    def _wait_in_front(self, name: str) -> None:
        self.page.wait_for_function(
            """(name) => {
              const tab = document.querySelector(
                '.lm-DockPanel-tabBar .lm-TabBar-tab.lm-mod-current');
              if (!tab || tab.querySelector('.lm-TabBar-tabLabel').textContent !== name)
                return false;
              const panel = document.querySelector(
                `.jp-NotebookPanel[aria-labelledby="${tab.id}"]`);
              return !!panel && !panel.classList.contains('lm-mod-hidden')
                && !!panel.querySelector('.jp-CodeCell');
            }""",
            arg=name,
            timeout=_ACTION_TIMEOUT_MS,
            polling=POLL_MS,
        )

    def _wait_kernel(self, status: str, doing: str) -> None:
        """Wait until the status bar's kernel text matches `status` (fail on a dialog). A
        pattern that allows "No Kernel" allows a notebook whose session is gone too (its server
        was killed and started again), whatever its status bar still says ("Disconnected"):
        a run starts a kernel there."""
        from playwright.sync_api import TimeoutError as PlaywrightTimeout

        try:
            self.page.wait_for_function(
                """([pattern]) => {
                  if (document.querySelector('.jp-Dialog')) return true;
                  const context = window.jupyterapp?.shell.currentWidget?.sessionContext;
                  if (pattern.includes('No Kernel') && context && !context.session) return true;
                  const bar = document.querySelector('.jp-StatusBar-Widget');
                  return !!bar && bar.innerText.split('\\n').some((l) => RegExp(pattern).test(l));
                }""",
                arg=[status],
                timeout=_ACTION_TIMEOUT_MS,
                polling=POLL_MS,
            )
        except PlaywrightTimeout:
            raise AssertionError(
                f"the kernel never showed {status!r} after {doing}: {self.kernel_status()!r}"
            ) from None
        self.fail_on_dialog(doing)

    # --- running --------------------------------------------------------------------------------
    def _menu(self, menu: str, item: str) -> None:
        self.page.get_by_role("menuitem", name=menu, exact=True).click()
        self.page.get_by_role("menuitem", name=item, exact=True).click()

    def _wait_settled(self, doing: str, one_cell: bool = False) -> None:
        """Wait until what was asked ran (or JupyterLab asked something: a failure)."""
        from playwright.sync_api import TimeoutError as PlaywrightTimeout

        try:
            self.page.wait_for_function(
                _SETTLED, arg=one_cell, timeout=self.timeout_ms, polling=POLL_MS
            )
        except PlaywrightTimeout:
            raise AssertionError(
                f"{doing} still runs after {self.timeout_ms / 1000:g} s: {self.kernel_status()!r}"
            ) from None
        self.fail_on_dialog(doing)

    def start_run_all(self) -> None:
        """Run > Run All Cells on the notebook in front; return once its kernel is busy."""
        doing = f"Run > Run All Cells in {self.current()}"
        self._wait_kernel(r"\| Idle$", doing)
        self._menu("Run", "Run All Cells")
        self._wait_kernel(r"\| Busy$", doing)

    def kernel_id(self) -> str:
        """Return the id of the kernel of the notebook in front ("" with none)."""
        return self.page.evaluate(
            "() => window.jupyterapp.shell.currentWidget?.sessionContext?.session?.kernel?.id"
            " || ''"
        )

    def run_all(self) -> None:
        """Run > Run All Cells on the notebook in front; wait until it ran."""
        doing = f"Run > Run All Cells in {self.current()}"
        self._wait_kernel(r"\| Idle$|^No Kernel", doing)  # a kernel that is not busy, or none
        self.page.evaluate(_ARM)
        self._menu("Run", "Run All Cells")
        self._wait_settled(doing)

    def restart_kernel(self) -> None:
        """Kernel > Restart Kernel…, confirmed; return once the dialog has closed."""
        self._wait_kernel(r"\| Idle$", f"Kernel > Restart Kernel… in {self.current()}")
        self.page.get_by_role("menuitem", name="Kernel", exact=True).click()
        # its name carries the shortcut JupyterLab shows beside it ("0, 0")
        self.page.get_by_role("menuitem", name=re.compile(r"^Restart Kernel…")).first.click()
        dialog = self.page.locator(".jp-Dialog", has_text="Restart Kernel?")
        dialog.get_by_role("button", name="Confirm Kernel Restart").click()
        dialog.wait_for(state="detached")

    def restart_and_run_all(self) -> None:
        """Kernel > Restart Kernel and Run All Cells…, confirmed; wait until it ran. A notebook
        with no kernel (its server was killed and started again) has none to restart: the
        learner runs all its cells instead, which starts one."""
        doing = f"Kernel > Restart Kernel and Run All Cells… in {self.current()}"
        self._wait_kernel(r"\| Idle$|^No Kernel", doing)
        if not self.page.evaluate(_HAS_SESSION):
            self.run_all()
            return
        self.page.evaluate(_ARM)
        self._menu("Kernel", "Restart Kernel and Run All Cells…")
        dialog = self.page.locator(".jp-Dialog", has_text="Restart Kernel?")
        dialog.get_by_role("button", name="Confirm Kernel Restart").click()
        dialog.wait_for(state="detached")
        self._wait_settled(doing)

    def run_cell(self, cell: Cell) -> Cell:
        """Run one code cell again, as Shift+Enter in it does; return it as it then shows."""
        doing = f"Shift+Enter in {self.current()}'s cell `{cell.first_line()}`"
        # a kernel that is not busy, or none (its server was started again): the cell starts one
        self._wait_kernel(r"\| Idle$|^No Kernel", doing)
        self.page.evaluate(_ARM)
        self._click_editor(cell.index)
        self.page.keyboard.press("Shift+Enter")
        self._wait_settled(doing, one_cell=True)
        return self.cells()[cell.index]

    def _click_editor(self, index: int) -> None:
        """Click into the editor of the `index`th code cell, near its top left corner (never
        under a notification). JupyterLab draws a long notebook's cells in idle time: on a
        loaded host the last one had no editor yet (the full walk: "07_move_the_robot.ipynb
        has no code cell 12"), so its editor is waited for, and asked for by scrolling to the
        cell only if it is still missing (a scroll to a cell keeps it pinned while the
        notebook's layout changes: a 3D view's page was then never still enough to click)."""
        editor_of = (
            f"([index, scroll]) => {{ {_FRONT}\n const cell = codeCells()[index];"
            " if (!cell) return null;"
            " const editor = cell.node.querySelector('.jp-InputArea-editor');"
            " if (!editor && scroll) front().content.scrollToCell(cell, 'nearest');"
            " return editor; }"
        )
        for scroll in (False, True):
            with contextlib.suppress(PlaywrightTimeout):
                self.page.wait_for_function(
                    editor_of, arg=[index, scroll], timeout=_DRAWN_MS, polling=POLL_MS
                )
                break
        editor = self.page.evaluate_handle(editor_of, [index, False]).as_element()
        assert editor is not None, f"{self.current()} has no code cell {index}"
        editor.click(position={"x": 8, "y": 8})

    def add_cell(self, code: str) -> Cell:
        """Add a code cell at the end of the notebook in front, run it; return it."""
        count = len(self.cells())
        # a kernel that is not busy, or none (its server was started again): the cell starts one
        self._wait_kernel(
            r"\| Idle$|^No Kernel|\| Disconnected$", f"adding a cell to {self.current()}"
        )
        self._click_editor(count - 1)
        self.page.keyboard.press("Escape")
        self.page.keyboard.press("b")
        self.page.keyboard.press("Enter")
        self.page.keyboard.type(code)
        self.page.evaluate(_ARM)
        self.page.keyboard.press("Control+Enter")  # run it, stay on it (no empty cell after)
        self._wait_settled(f"running the added cell `{code}`", one_cell=True)
        return self.cells()[count]

    def shut_down_all_kernels(self) -> None:
        """Kernel > Shut Down All Kernels…, confirmed; wait until the front notebook has none."""
        self._menu("Kernel", "Shut Down All Kernels…")
        dialog = self.page.locator(".jp-Dialog", has_text="Shut Down All?")
        dialog.get_by_role("button", name="Shut Down All").click()
        dialog.wait_for(state="detached")
        self._wait_kernel(r"^No Kernel", "Kernel > Shut Down All Kernels…")

    def screenshot(self, path: Any) -> None:
        """Keep a screenshot of the page (never fails the caller)."""
        with contextlib.suppress(PlaywrightError):  # a crashed page has nothing to show
            self.page.screenshot(path=str(path))


def _repo_root() -> Any:
    from course_lib.core.paths import REPO_ROOT

    return REPO_ROOT
