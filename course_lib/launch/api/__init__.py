"""The launch API that launch files call: actions, conditions, substitutions."""
