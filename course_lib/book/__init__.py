"""`make book`: the lessons and the guides as a static site anyone can read, offline.

The lessons' pages show their stored outputs (the ones nbval checks); the driving lessons'
3D replays and speed plots are recorded at build time from a real run of each lesson
(`recording`), kept per lesson input so a rebuild of one commit gives the same pages. The
pages are made by Sphinx with MyST-NB (`build`), then every internal link is checked (`links`).
"""

from __future__ import annotations

__all__: list[str] = []
