"""Self-check results and how they read: what passed, and for what did not, what to try (pure)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from .catalogue.spec import Check, check

__all__ = ["Check", "SelfCheck", "check"]


@dataclass(frozen=True)
class SelfCheck:
    """The self-check at the end of a lesson; its plain text is stable, so nbval can compare it."""

    lesson: int
    checks: tuple[Check, ...]

    @classmethod
    def of(cls, lesson: int, checks: Sequence[Check]) -> SelfCheck:
        """Return the self-check of `lesson` from its checks."""
        return cls(lesson, tuple(checks))

    @property
    def passed(self) -> bool:
        """Return True when every check passed."""
        return all(c.passed for c in self.checks)

    def text(self) -> str:
        """Return the report: one line per check, a `Try:` line under each failure, a verdict."""
        lines = [f"Self-check, lesson {self.lesson}"]
        for item in self.checks:
            # the word says it too: a sign alone is read out as "check mark" or not at all
            lines.append(f"  {'✓ passed' if item.passed else '✗ not yet'}: {item.what}")
            if not item.passed and item.hint:
                lines.append(f"      Try: {item.hint}")
        good = sum(c.passed for c in self.checks)
        if self.passed:
            lines.append(f"Everything passed ({good} of {good}). On to the next lesson!")
        else:
            lines.append(
                f"{good} of {len(self.checks)} checks passed: "
                "fix what is not yet passed above, then run this cell again."
            )
        return "\n".join(lines) + "\n"

    def __repr__(self) -> str:
        return self.text()
