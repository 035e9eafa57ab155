"""XML and YAML launch files, read into the actions Python launch files build."""
