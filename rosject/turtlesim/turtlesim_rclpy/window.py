"""The node's window: the course's page in the browser, when the course's library is here."""

from .canvas import to_pixel


def open_window():
    """Serve the window and print its address (the node's first line); None without course_lib."""
    try:
        from course_lib.turtlesim_view import WindowServer, window_url
    except ImportError:  # a ROS machine without the course: no window, as headless turtlesim
        return None
    server = WindowServer()
    print(f"TurtleSim window (the course's, in your browser): {window_url(server.port)}",
          flush=True)
    return server


def window_scene(background, canvas, turtles):
    """Return the window's scene: background, pen lines and turtles, in window pixels."""
    from course_lib.turtlesim_view import PenLine, Scene, TurtlePose

    lines = tuple(PenLine(colour, width, tuple(points)) for colour, width, points in canvas.lines)
    poses = tuple(
        TurtlePose(t.name, *to_pixel(t.turtle.x, t.turtle.y), t.turtle.theta) for t in turtles)
    return Scene(background=background, lines=lines, turtles=poses)
