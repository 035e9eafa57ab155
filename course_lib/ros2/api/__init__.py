"""The `ros2` verbs as Python functions returning structured results (what lessons call).

By family: `nodes_and_params`, `services_and_topics`. Every function is also a name of
`course_lib.ros2` itself (`from course_lib.ros2 import param_get`), imported when first used.
"""
