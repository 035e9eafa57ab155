"""An offline check of a built site: every internal link and anchor resolves.

Every `href` and `src` of every page that is not a whole URL (scheme or `//`) must name a file
of the site (a folder: its index.html), and a `#fragment` must be an `id` (or an `<a name>`)
of the page it points into. Nothing is fetched.
"""

from __future__ import annotations

from dataclasses import dataclass
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

__all__ = ["BrokenLink", "broken_links"]

_LINK_ATTRIBUTES = {"href", "src"}


@dataclass(frozen=True)
class BrokenLink:
    """A link of `page` (relative to the site) that does not resolve, and why."""

    page: str
    link: str
    why: str

    def __str__(self) -> str:
        return f"{self.page}: {self.link}: {self.why}"


class _Page(HTMLParser):
    """Collect a page's anchors (ids, names) and links."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.anchors: set[str] = set()
        self.links: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        for name, value in attrs:
            if value is None:
                continue
            if name == "id" or (tag == "a" and name == "name"):
                self.anchors.add(value)
            elif name in _LINK_ATTRIBUTES:
                self.links.append(value)


def _read(path: Path) -> _Page:
    page = _Page()
    page.feed(path.read_text(encoding="utf-8", errors="replace"))
    page.close()
    return page


def _target(site: Path, page: Path, path: str) -> Path:
    target = (page.parent / unquote(path)).resolve() if path else page.resolve()
    return target / "index.html" if target.is_dir() else target


def broken_links(site: Path) -> list[BrokenLink]:
    """Return every internal link or anchor of the HTML pages under `site` that does not
    resolve (an empty list: the site holds together)."""
    root = site.resolve()
    pages = {path.resolve(): _read(path) for path in sorted(root.rglob("*.html"))}
    broken: list[BrokenLink] = []
    for path, page in pages.items():
        name = path.relative_to(root).as_posix()
        for link in page.links:
            parts = urlsplit(link)
            if parts.scheme or link.startswith("//"):
                continue  # a whole URL: outside the site (data:, https:, mailto:, ...)
            target = _target(root, path, parts.path)
            if not target.is_relative_to(root):
                broken.append(BrokenLink(name, link, "points outside the site"))
            elif not target.is_file():
                broken.append(BrokenLink(name, link, "no such file in the site"))
            elif parts.fragment and target.suffix == ".html":
                anchors = pages[target].anchors if target in pages else _read(target).anchors
                if unquote(parts.fragment) not in anchors:
                    broken.append(BrokenLink(name, link, "no such anchor in that page"))
    return broken
