"""Load YAML that a learner (or anyone) wrote, refusing an alias bomb before it expands.

PyPI's PyYAML shares an aliased node instead of copying it, so `safe_load` of 26 levels of
`{a: *x, b: *x}` is quick, but whatever walks the result visits 2**26 values and runs for
minutes. `safe_load_bounded` composes the document first, counts the values it stands for once
expanded (each node counted once, memoised), and refuses past `MAX_VALUES`, naming the line
of the alias that crossed it. Ordinary aliases load as `yaml.safe_load` loads them.
"""

from __future__ import annotations

from typing import IO, Any

import yaml

__all__ = ["MAX_VALUES", "YamlTooLarge", "expanded_size", "safe_load_bounded"]

MAX_VALUES = 100_000  # a params file of the course holds tens


class YamlTooLarge(ValueError):
    """A document whose aliases expand to more than MAX_VALUES values."""

    def __init__(self, name: str, line: int, size: int, limit: int = MAX_VALUES) -> None:
        self.name, self.line, self.size = name, line, size
        super().__init__(
            f"{name}, line {line}: its aliases (*name) expand this YAML to more than "
            f"{limit:,} values ({size:,} or more), which would take minutes to read. "
            "Write the values out instead of repeating aliases."
        )


def expanded_size(node: yaml.Node, name: str = "<yaml>", limit: int = MAX_VALUES) -> int:
    """Return how many nodes `node` stands for once every alias is expanded (<= limit)."""
    sizes: dict[int, int] = {}

    def size(item: yaml.Node) -> int:
        known = sizes.get(id(item))
        if known is not None:
            return known
        total = 1
        # (child, where it is written): an alias's node carries its anchor's mark, so a
        # mapping's value is placed at its key, a sequence's item at the sequence
        if isinstance(item, yaml.SequenceNode):
            children = [(child, item) for child in item.value]
        elif isinstance(item, yaml.MappingNode):
            children = [(part, key) for key, value in item.value for part in (key, value)]
        else:
            children = []
        for child, place in children:
            total += size(child)
            if total > limit:
                raise YamlTooLarge(name, place.start_mark.line + 1, total, limit)
        sizes[id(item)] = total
        return total

    return size(node)


def safe_load_bounded(
    stream: str | IO[str], name: str | None = None, *, limit: int = MAX_VALUES
) -> Any:
    """Return what `yaml.safe_load(stream)` returns; raise YamlTooLarge for an alias bomb."""
    loader = yaml.SafeLoader(stream)
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        label = name or getattr(stream, "name", None) or "<yaml>"
        expanded_size(node, str(label), limit)
        return loader.construct_document(node)
    finally:
        loader.dispose()
