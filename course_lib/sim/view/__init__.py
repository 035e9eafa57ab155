"""The simulation's live 3D view and recordings: poses streamed to meshcat, TF frames, replays."""
