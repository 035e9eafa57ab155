"""The course's commands behind the Makefile: doctor, stop, config checks, tests, builds."""
