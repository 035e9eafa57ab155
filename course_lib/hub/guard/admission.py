"""How many connections each account (or remote address) holds to the hub, whether it may open
one more, and the refusals said in a few lines however many there are."""

from __future__ import annotations

from collections import Counter

from .peers import Peer

__all__ = ["Admission"]

# Root runs the hub: its proxy, the relays of the labs, the services it starts. It could stop
# the hub anyway; it is held only to the total.
UNLIMITED = Peer(uid=0)
MAX_LINES = 5  # of one report; the rest in one more line


class Admission:
    """Connections held per peer: at most `per_peer` each (root excepted), `total` in all."""

    def __init__(self, per_peer: int, total: int) -> None:
        self.per_peer, self.total = per_peer, total
        self._held: Counter[Peer] = Counter()
        self._total = 0
        self._refused: Counter[Peer] = Counter()
        self._full = 0  # refused since the last report because the total was reached

    def held(self, peer: Peer | None = None) -> int:
        """Return the connections `peer` holds (everyone's, without one)."""
        return self._held[peer] if peer is not None else self._total

    def admit(self, peer: Peer) -> bool:
        """Count one more connection of `peer` and return True; past a limit, count the
        refusal (said by `report`) and return False."""
        if self._total >= self.total:
            self._full += 1
            return False
        if peer != UNLIMITED and self._held[peer] >= self.per_peer:
            self._refused[peer] += 1
            return False
        self._held[peer] += 1
        self._total += 1
        return True

    def release(self, peer: Peer) -> None:
        """Count one connection of `peer` fewer (it has closed)."""
        self._held[peer] -= 1
        self._total -= 1
        if self._held[peer] <= 0:
            del self._held[peer]

    def report(self, where: str, every_s: float) -> list[str]:
        """Return the lines saying what was refused since the last report (at most
        MAX_LINES + 1, whoever tried), and start counting again."""
        lines = [
            f"{where} refused {count} connection(s) of {peer} in the last {every_s:.0f} s: "
            f"it held {self.per_peer} already, the most one account or address may "
            "(connections_per_account in config/hub.yaml)."
            for peer, count in self._refused.most_common(MAX_LINES)
        ]
        others = self._refused.total() - sum(c for _, c in self._refused.most_common(MAX_LINES))
        if others:
            peers = len(self._refused) - MAX_LINES
            lines.append(f"{where} refused {others} more connection(s) of {peers} other(s).")
        if self._full:
            lines.append(
                f"{where} refused {self._full} connection(s) in the last {every_s:.0f} s: it "
                f"held {self.held()}, as many as its open files allow."
            )
        self._refused.clear()
        self._full = 0
        return lines
