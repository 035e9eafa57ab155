"""What every `ros2` verb is written with: its console, its context, shared options, `@verb`."""
