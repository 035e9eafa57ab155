"""`ros2 topic echo --csv`'s line, against rosidl_runtime_py 0.13.1's `message_to_csv`.

Each expected line is what the real function printed for the same message and options
(nested messages flattened in place, arrays element by element, bytes as `b'..'`, no comma
after an empty first value); the first three also came out of the real
`ros2 topic echo --csv` on a live topic.
"""

from __future__ import annotations

import pytest
from rcl_interfaces.msg import Parameter, ParameterEvent, ParameterValue
from sensor_msgs.msg import JointState, NavSatFix
from std_msgs.msg import Byte, MultiArrayDimension, MultiArrayLayout, String, UInt8MultiArray

from course_lib.ros2.msgcsv import message_to_csv

_EVENT = ParameterEvent(
    node="/n",
    new_parameters=[
        Parameter(
            name="p",
            value=ParameterValue(
                type=5,
                byte_array_value=[b"a", b"\x00"],
                double_array_value=[0.1, 1e-9, 1e20],
                string_array_value=["abc", "y"],
            ),
        )
    ],
)
CASES = {
    "joint_state": (
        JointState(name=["a", "b, c", "q'uote"], position=[1.0, 2.5], effort=[0.125]),
        {},
        "0,0,,a,b, c,q'uote,1.0,2.5,,0.125",
    ),
    "nested_array_of_messages": (
        UInt8MultiArray(
            layout=MultiArrayLayout(
                dim=[MultiArrayDimension(label="x", size=3, stride=3)], data_offset=1
            ),
            data=[1, 2, 255],
        ),
        {},
        "x,3,3,1,1,2,255",
    ),
    "byte": (Byte(data=b"\x02"), {}, "b'\\x02'"),
    "numpy_array": (
        NavSatFix(latitude=1.5, position_covariance=[0.25] + [0.0] * 8),
        {},
        "0,0,,-2,0,1.5,0.0,0.0,0.25,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0",
    ),
    "empty_string": (String(data=""), {}, ""),
    "empty_first_value": (Parameter(name=""), {}, "0,False,0,0.0,,,,,,"),
    "truncated": (
        _EVENT,
        {"truncate_length": 2},
        "0,0,/n,p,5,False,0,0.0,,b'a',b'\\x00',,,0.1,1e-09,...,ab...,y,,",
    ),
    "no_arr_no_str": (
        ParameterEvent(node="/n", new_parameters=[Parameter(name="p")]),
        {"no_arr": True, "no_str": True},
        "0,0,<string length: <2>>,<sequence type: rcl_interfaces/msg/Parameter, length: 1>,"
        "<sequence type: rcl_interfaces/msg/Parameter, length: 0>,"
        "<sequence type: rcl_interfaces/msg/Parameter, length: 0>",
    ),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_csv_line_is_rosidl_runtime_pys(name: str) -> None:
    msg, options, expected = CASES[name]
    assert message_to_csv(msg, **options) == expected
