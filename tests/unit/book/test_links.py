"""The book's offline link checker (course_lib.book.links) on small hand-made sites."""

from __future__ import annotations

from pathlib import Path

from course_lib.book.links import BrokenLink, broken_links

HOME = """<html><head><link rel="stylesheet" href="_static/site.css"></head><body>
<h1 id="top">Home</h1>
<a href="#top">top</a>
<a href="guides/">guides</a>
<a href="guides/intro.html#why">why</a>
<a href="my%20notes.html">notes</a>
<img src="_static/robot.svg" alt="robot">
</body></html>"""
INTRO = """<html><body><h2 id="why">Why</h2><a name="old-anchor"></a>
<a href="../index.html#top">home</a> <a href="index.html">guides</a>
<a href="#old-anchor">old</a></body></html>"""


def _site(root: Path, extra: dict[str, str] | None = None) -> Path:
    """Write a small site that holds together (plus `extra` pages) under `root`."""
    files = {
        "index.html": HOME,
        "guides/index.html": '<html><body><a href="intro.html">intro</a></body></html>',
        "guides/intro.html": INTRO,
        "my notes.html": '<html><body><p id="n">notes</p></body></html>',
        "_static/site.css": "body {}",
        "_static/robot.svg": "<svg/>",
        **(extra or {}),
    }
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text, encoding="utf-8")
    return root


def _page_linking(*hrefs: str) -> str:
    return "<html><body>" + "".join(f'<a href="{h}">x</a>' for h in hrefs) + "</body></html>"


def test_a_site_that_holds_together_has_no_broken_link(tmp_path: Path) -> None:
    assert broken_links(_site(tmp_path)) == []


def test_a_link_to_a_missing_file_is_reported(tmp_path: Path) -> None:
    site = _site(tmp_path, {"lessons/one.html": _page_linking("../guides/outro.html")})
    assert broken_links(site) == [
        BrokenLink("lessons/one.html", "../guides/outro.html", "no such file in the site")
    ]


def test_a_missing_image_is_reported(tmp_path: Path) -> None:
    site = _site(tmp_path, {"a.html": '<html><body><img src="_static/gone.png"></body></html>'})
    assert broken_links(site) == [
        BrokenLink("a.html", "_static/gone.png", "no such file in the site")
    ]


def test_a_link_to_a_missing_anchor_is_reported(tmp_path: Path) -> None:
    site = _site(tmp_path, {"a.html": _page_linking("guides/intro.html#how", "#nowhere")})
    assert broken_links(site) == [
        BrokenLink("a.html", "guides/intro.html#how", "no such anchor in that page"),
        BrokenLink("a.html", "#nowhere", "no such anchor in that page"),
    ]


def test_a_link_outside_the_site_is_reported(tmp_path: Path) -> None:
    site = tmp_path / "www" / "book"
    (tmp_path / "etc").mkdir()
    (tmp_path / "etc" / "passwd").write_text("root:x:0:0")  # it exists, but not in the site
    _site(site, {"a.html": _page_linking("../../etc/passwd")})
    assert broken_links(site) == [
        BrokenLink("a.html", "../../etc/passwd", "points outside the site")
    ]


def test_a_folder_link_without_an_index_page_is_reported(tmp_path: Path) -> None:
    site = _site(tmp_path, {"a.html": _page_linking("_static/", "_static")})
    assert broken_links(site) == [
        BrokenLink("a.html", "_static/", "no such file in the site"),
        BrokenLink("a.html", "_static", "no such file in the site"),
    ]


def test_whole_urls_are_not_checked(tmp_path: Path) -> None:
    page = _page_linking(
        "https://docs.ros.org/en/jazzy/missing.html#nowhere",
        "mailto:teacher@example.org",
        "data:image/png;base64,AAAA",
        "//cdn.example.org/lib.js",
    )
    assert broken_links(_site(tmp_path, {"a.html": page})) == []


def test_an_anchor_of_the_page_itself_resolves(tmp_path: Path) -> None:
    page = '<html><body><h1 id="top">A</h1><a href="#top">up</a></body></html>'
    assert broken_links(_site(tmp_path, {"a.html": page})) == []


def test_percent_encoded_names_and_anchors_resolve(tmp_path: Path) -> None:
    pages = {
        "a.html": _page_linking("my%20notes.html#n", "b.html#step%201"),
        "b.html": '<html><body><h2 id="step 1">Step 1</h2></body></html>',
    }
    assert broken_links(_site(tmp_path, pages)) == []


def test_a_broken_link_reads_as_page_link_and_why() -> None:
    link = BrokenLink("a.html", "b.html", "no such file in the site")
    assert str(link) == "a.html: b.html: no such file in the site"
