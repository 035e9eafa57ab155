"""A self-check sent to the class's progress page (on a hub): the wire format and the client.

The hub's progress service (course_lib.hub.progress) implements the other side of this contract."""
