"""Files written and read safely: atomic writes, YAML read within bounds, live outputs' mark."""
