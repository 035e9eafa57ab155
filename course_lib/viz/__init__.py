"""The 3D view: meshcat scene from the MuJoCo model, live updates, recorded replays.

Lesson 3 shows the live view (`course_lib.notebook.start_world`); lesson 7 saves a replay.
meshcat is imported by the modules that use it, never here: a kernel that only shows the view's
iframe (`viewer`) does not load it.
"""

import warnings

# meshcat 0.3.2 imports zmq.eventloop.ioloop, which pyzmq >= 17 flags as deprecated.
warnings.filterwarnings("ignore", "zmq.eventloop.ioloop is deprecated", DeprecationWarning)

__all__: list[str] = []
