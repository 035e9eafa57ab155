"""ROS 2 parameters, interactively: the library behind the course's notebooks."""

from .errors import CourseError
from .session import Session, get_session

__all__ = ["CourseError", "Session", "get_session"]
