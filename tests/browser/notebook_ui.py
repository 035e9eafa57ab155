"""What a learner does in JupyterLab's notebook UI: run all cells, wait until they ran."""

from __future__ import annotations

from pathlib import Path

from waits import POLL_MS

_BUSY_PROMPTS = (
    "() => ![...document.querySelectorAll('.jp-InputPrompt')]"
    ".some(p => p.textContent.includes('*'))"
)
_SHOWN = ".jp-NotebookPanel:not(.lm-mod-hidden)"  # the notebook of the tab in front
# that notebook's own kernel is idle (the status bar may still show another tab's "Idle")
_SHOWN_IDLE = f"{_SHOWN} .jp-Notebook-ExecutionIndicator[data-status='idle']"
# the visible notebook's code cells' prompts: "[ ]:" never ran, "[*]:" queued or running
_PROMPTS = (
    "[...document.querySelectorAll('.jp-NotebookPanel:not(.lm-mod-hidden) .jp-CodeCell "
    ".jp-InputArea-prompt')].map(p => p.textContent.trim())"
)
_STARTED = f"() => {_PROMPTS}.some(t => t !== '[ ]:' && t !== '')"


def run_all_cells(page) -> None:  # type: ignore[no-untyped-def]
    """Wait for an idle kernel, then Run > Run All Cells from the menu.

    A dialog instead (JupyterLab's "Select Kernel", asked when the notebook has no kernel) is a
    failure, never clicked away: a learner's Run All runs every cell without asking.
    """
    idle = page.locator(_SHOWN_IDLE)
    dialog = page.locator(".jp-Dialog")
    idle.or_(dialog).first.wait_for(timeout=60_000)
    fail_on_dialog(page, "opening the notebook")
    # the Run menu acts on the notebook that has the focus, as a learner's click gives it
    page.locator(f"{_SHOWN} .jp-Cell").first.click()
    page.get_by_role("menuitem", name="Run", exact=True).click()
    page.get_by_role("menuitem", name="Run All Cells", exact=True).click()
    fail_on_dialog(page, "Run > Run All Cells")
    # a cell is queued, running or done
    page.wait_for_function(_STARTED, timeout=30_000, polling=POLL_MS)


def fail_on_dialog(page, after: str) -> None:  # type: ignore[no-untyped-def]
    """Fail, with its text, if JupyterLab shows a dialog (e.g. "Select Kernel")."""
    dialog = page.locator(".jp-Dialog")
    if dialog.count():
        raise AssertionError(f"JupyterLab asked, after {after}:\n{dialog.first.inner_text()}")


def wait_all_ran(page, artifacts: Path) -> None:  # type: ignore[no-untyped-def]
    """Wait until no cell runs, keep a full-page screenshot, and fail if a cell failed."""
    page.wait_for_function(_BUSY_PROMPTS, timeout=90_000, polling=POLL_MS)
    page.screenshot(path=str(artifacts / "page_done.png"), full_page=True)
    fail_on_dialog(page, "Run All")
    errors = page.locator('[data-mime-type="application/vnd.jupyter.error"]')
    assert errors.count() == 0, f"a cell failed: {errors.first.inner_text()[:2000]}"
    never_ran = page.evaluate(f"() => {_PROMPTS}.filter(t => t === '[ ]:').length")
    assert never_ran == 0, (
        f"{never_ran} code cells never ran: {artifacts / 'page_done.png'}\n{_what_ran_where(page)}"
    )


def _what_ran_where(page) -> str:  # type: ignore[no-untyped-def]
    """Say which notebook is in front, its prompts, and the server's sessions and kernels (a
    run whose kernel was replaced or restarted ends with its cells cleared and no error)."""
    return page.evaluate(
        f"""async () => {{
          const tab = document.querySelector('#jp-main-dock-panel .lm-TabBar-tab.lm-mod-current');
          const config = document.getElementById('jupyter-config-data');
          const base = JSON.parse(config.textContent).baseUrl;
          const reply = await fetch(`${{base}}api/sessions`);
          const sessions = await reply.json();
          return JSON.stringify({{
            front: tab && tab.textContent, prompts: {_PROMPTS},
            // what the server said instead, if not a list (ci76: a page of a hub's server)
            sessions: Array.isArray(sessions)
              ? sessions.map(s => [s.path, s.kernel.id, s.kernel.execution_state,
                                   s.kernel.connections, s.kernel.last_activity])
              : [reply.status, sessions],
          }}, null, 1);
        }}"""
    )


def run_cell(page, source: str) -> None:  # type: ignore[no-untyped-def]
    """Run the code cell whose text contains `source` again, as Shift+Enter does."""
    cell = page.locator(".jp-CodeCell", has_text=source).first
    cell.locator(".jp-InputArea-editor").click()
    page.keyboard.press("Shift+Enter")
    page.wait_for_function(_BUSY_PROMPTS, timeout=60_000, polling=POLL_MS)


def open_notebook(page, base_url: str, path: str, token: str) -> None:  # type: ignore[no-untyped-def]
    """Open another notebook in a new tab of the same JupyterLab (the others stay open)."""
    page.goto(f"{base_url}/lab/tree/{path}?token={token}")
    show_tab(page, Path(path).name, timeout_ms=60_000)
    choose = page.get_by_role("button", name="Select", exact=True)
    if choose.is_visible():  # a slow kernel list makes JupyterLab ask; a learner picks Python 3
        choose.click()


def show_tab(page, name: str, timeout_ms: int = 90_000) -> None:  # type: ignore[no-untyped-def]
    """Put the notebook `name` (opened, maybe behind a restored tab) in front, as a learner's
    click on its tab does, and wait until its own kernel is idle or JupyterLab asks."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    tab = page.locator("#jp-main-dock-panel .lm-TabBar-tab").filter(has_text=name).first
    try:
        tab.click(timeout=60_000)
    except PlaywrightTimeout:  # a dialog over the tab (seen once on a busy host): say which
        fail_on_dialog(page, f"opening {name}")
        raise
    front = page.locator("#jp-main-dock-panel .lm-TabBar-tab.lm-mod-current")
    front.filter(has_text=name).wait_for(timeout=30_000)
    page.locator(f"{_SHOWN} .jp-CodeCell").first.wait_for(timeout=60_000)
    page.locator(_SHOWN_IDLE).or_(page.locator(".jp-Dialog")).first.wait_for(timeout=timeout_ms)


def add_cell(page, code: str) -> str:  # type: ignore[no-untyped-def]
    """Add a cell at the end of the visible notebook, run it, return its output's text."""
    cells = page.locator(".jp-NotebookPanel:visible .jp-CodeCell")
    count = cells.count()
    cells.last.locator(".jp-InputArea-editor").click()
    page.keyboard.press("Escape")
    page.keyboard.press("b")
    page.keyboard.press("Enter")
    page.keyboard.type(code)
    page.keyboard.press("Shift+Enter")
    page.wait_for_function(_BUSY_PROMPTS, timeout=60_000, polling=POLL_MS)
    return cells.nth(count).locator(".jp-OutputArea").inner_text()


def shut_down_kernel_of(page, base_url: str, token: str, name: str) -> int:  # type: ignore[no-untyped-def]
    """Shut down the kernel of the open notebook whose path contains `name`; return how many."""
    return page.evaluate(
        """async ([base, token, name]) => {
          const auth = {headers: {Authorization: `token ${token}`}};
          const sessions = await (await fetch(`${base}/api/sessions`, auth)).json();
          const mine = sessions.filter((s) => s.path.includes(name));
          for (const s of mine) {
            await fetch(`${base}/api/sessions/${s.id}`, {...auth, method: 'DELETE'});
          }
          return mine.length;
        }""",
        [base_url, token, name],
    )
