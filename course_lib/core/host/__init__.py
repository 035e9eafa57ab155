"""The machine's processes, signals and ports: the one `/proc` reader, signals sent and logged,
free ports."""
