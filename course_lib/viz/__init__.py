"""The 3D view: meshcat scene from the MuJoCo model, live updates, recorded replays.

Lesson 3 shows the live view (`course_lib.notebook.start_world`); lesson 7 saves a replay.
"""

import warnings

with warnings.catch_warnings():
    # meshcat 0.3.2 imports zmq.eventloop.ioloop, which pyzmq >= 17 flags as deprecated.
    warnings.filterwarnings("ignore", "zmq.eventloop.ioloop is deprecated", DeprecationWarning)
    import meshcat  # noqa: F401

__all__: list[str] = []
