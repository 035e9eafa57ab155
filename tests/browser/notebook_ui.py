"""What a learner does in JupyterLab's notebook UI: run all cells, wait until they ran."""

from __future__ import annotations

from pathlib import Path

_BUSY_PROMPTS = (
    "() => ![...document.querySelectorAll('.jp-InputPrompt')]"
    ".some(p => p.textContent.includes('*'))"
)


def run_all_cells(page) -> None:  # type: ignore[no-untyped-def]
    """Wait for an idle kernel, then Run > Run All Cells from the menu."""
    page.get_by_text("Python 3 (ipykernel) | Idle").wait_for(timeout=60_000)
    page.get_by_role("menuitem", name="Run", exact=True).click()
    page.get_by_role("menuitem", name="Run All Cells", exact=True).click()


def wait_all_ran(page, artifacts: Path) -> None:  # type: ignore[no-untyped-def]
    """Wait until no cell runs, keep a full-page screenshot, and fail if a cell failed."""
    page.wait_for_function(_BUSY_PROMPTS, timeout=90_000)
    page.screenshot(path=str(artifacts / "page_done.png"), full_page=True)
    errors = page.locator('[data-mime-type="application/vnd.jupyter.error"]')
    assert errors.count() == 0, f"a cell failed: {errors.first.inner_text()[:2000]}"


def run_cell(page, source: str) -> None:  # type: ignore[no-untyped-def]
    """Run the code cell whose text contains `source` again, as Shift+Enter does."""
    cell = page.locator(".jp-CodeCell", has_text=source).first
    cell.locator(".jp-InputArea-editor").click()
    page.keyboard.press("Shift+Enter")
    page.wait_for_function(_BUSY_PROMPTS, timeout=60_000)
