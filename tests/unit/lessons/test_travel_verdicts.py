"""Lesson 11's travel verdicts (issue 59): the real cause in the learner's words (pure)."""

from __future__ import annotations

import pytest

from course_lib.config.trip import Trip
from course_lib.lessons.judging import (
    Held,
    Request,
    TravelAttempt,
    TravelVerdict,
    double,
    holds_text,
    judge_travel,
    refusal,
    replay,
)

ANSWER = Trip(5.0, 0.2)
INTEGER_5 = Request("travel_time", "5", "integer", 5, refused=True)


def _judge(attempt: TravelAttempt, number: int = 1) -> TravelVerdict:
    return judge_travel(
        attempt, target_m=1.0, tolerance_m=0.05, number=number, show_hints=True, answer=ANSWER
    )


def _double(name: str, value: float, *, refused: bool = False) -> Request:
    return Request(name, repr(value), "double", value, refused)


@pytest.mark.parametrize(
    ("request_", "held", "why"),
    [
        (INTEGER_5, Held(0.0, 0.0), "it is an integer; write 5.0"),
        (
            Request("velocity", '"fast"', "string", "fast", refused=True),
            Held(0.0, 0.0),
            "it is a string, and velocity is a double; write a number like 0.2",
        ),
        (_double("velocity", 0.3), Held(0.0, 0.0), "velocity goes from 0.0 to 0.26 m/s"),
        (_double("travel_time", 5.05), Held(0.0, 0.0), "travel_time goes in steps of 0.1 s"),
        (
            _double("velocity", 0.2),
            Held(0.0, 10.0),
            "a trip of 0.2 m/s for 10 s is 2.00 m, longer than max_travel (1.5 m)",
        ),
        (_double("max_travel", 2.0), Held(0.0, 0.0), "max_travel is read-only"),
        (
            _double("travel_tim", 5.0),
            Held(0.0, 0.0),
            "/descriptor_vel_node has no parameter travel_tim",
        ),
    ],
)
def test_a_refusal_names_what_the_learner_typed_and_why(
    request_: Request, held: Held, why: str
) -> None:
    said = refusal(request_, held)
    assert said.startswith(f"Your `{request_.name} {request_.text}` was refused: {why}"), said


def test_replay_keeps_the_trips_velocity_and_judges_each_refusal_in_its_moment() -> None:
    requests = [
        _double("travel_time", 10.0),
        _double("velocity", 0.2, refused=True),  # 2.0 m with travel_time 10.0
        _double("travel_time", 5.0),
        _double("velocity", 0.2),
        _double("velocity", 0.0),  # the learner stopped it by hand: the trip was at 0.2
        INTEGER_5,
        INTEGER_5,  # the cell run twice: said once
    ]
    held, refusals = replay(requests, Held(0.0, 2.5))
    assert held == Held(0.2, 5.0)
    assert refusals == (
        "Your `velocity 0.2` was refused: a trip of 0.2 m/s for 10 s is 2.00 m, longer than "
        "max_travel (1.5 m).",
        "Your `travel_time 5` was refused: it is an integer; write 5.0.",
    )


def test_an_endless_trip_cut_short_names_the_refused_integer_and_the_missing_limit() -> None:
    held, refusals = replay([INTEGER_5, _double("velocity", 0.2)], Held(0.0, 0.0))
    attempt = TravelAttempt(True, False, 1.07, passed_m=1.05, held=held, refusals=refusals)
    verdict = _judge(attempt, number=2)
    assert verdict.message == (
        "Attempt 2: not yet. The robot passed 1.05 m (the target 1.00 m + 5 cm) still moving, "
        "so the check stopped it, at 1.07 m. /descriptor_vel_node held velocity 0.2 and "
        "travel_time 0.0, and travel_time 0.0 means no limit: the trip never ends by itself. "
        "Your `travel_time 5` was refused: it is an integer; write 5.0."
    )
    assert verdict.hint.startswith("velocity and travel_time are doubles (write 5.0, not 5)")
    assert "Set parameter successful" in _judge(attempt, number=1).hint


def test_an_endless_trip_without_a_refusal_hints_at_travel_time_first() -> None:
    attempt = TravelAttempt(True, False, 0.25, waited_s=5.0, held=Held(0.05, 0.0))
    verdict = _judge(attempt)
    assert "still moving at 0.25 m when the check's 5 s ran out" in verdict.message
    assert "travel_time 0.0 means no limit" in verdict.message
    assert verdict.hint.startswith("set travel_time before velocity")


def test_a_finite_trip_says_what_the_node_held_and_the_product() -> None:
    attempt = TravelAttempt(
        True, True, 0.79, held=Held(0.2, 4.0), refusals=(refusal(INTEGER_5, Held()),)
    )
    message = _judge(attempt).message
    assert "0.21 m short of" in message
    assert "held velocity 0.2 and travel_time 4.0: 0.2 × 4.0 = 0.80 m." in message
    assert message.endswith("Your `travel_time 5` was refused: it is an integer; write 5.0.")


def test_no_motion_from_a_refused_velocity_names_the_refusal_not_generic_advice() -> None:
    refused = Request("velocity", "1", "integer", 1, refused=True)
    attempt = TravelAttempt(
        False, False, 0.0, held=Held(0.0, 5.0), refusals=(refusal(refused, Held()),)
    )
    message = _judge(attempt).message
    assert message == (
        "Attempt 1: the robot did not move. /descriptor_vel_node held velocity 0.0 and "
        "travel_time 5.0. Your `velocity 1` was refused: it is an integer; write 1.0."
    )


def test_what_the_node_holds_is_said_for_the_next_trip() -> None:
    assert holds_text(Held(0.0, 0.0)) == (
        "/descriptor_vel_node holds velocity 0.0 and travel_time 0.0 (no limit: a trip started "
        "now never ends; set travel_time first)"
    )
    assert holds_text(Held(0.0, 4.0)).endswith("(setting velocity starts a trip of 4.0 s)")
    verdict = TravelVerdict(False, "Attempt 1: not yet.", "a hint", then="Next attempt: ...")
    assert repr(verdict) == "Attempt 1: not yet.\nHint: a hint\nNext attempt: ...\n"


@pytest.mark.parametrize(
    ("value", "text"), [(0.2, "0.2"), (5.0, "5.0"), (0.0, "0.0"), (0.26, "0.26")]
)
def test_doubles_read_as_the_learner_writes_them(value: float, text: str) -> None:
    assert double(value) == text
