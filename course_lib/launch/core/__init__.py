"""The small core of launch: entities, events, the context, descriptions, loading files."""
