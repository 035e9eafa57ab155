"""Scripts that print the course's speed and memory figures (`make bench`)."""
