"""A lesson's run log: the latest run only, from where the lesson marked its start."""

from __future__ import annotations

from course_lib.sim.view.run_log import PoseLog, PoseSample


def _pose(seconds: float, x: float) -> PoseSample:
    return PoseSample(seconds, (x, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0), (0.0, 0.0), 0.1)


def test_a_lesson_reads_its_run_from_its_mark_and_a_world_restart_starts_a_new_one() -> None:
    log = PoseLog(fps=25)
    for seconds, x in ((10.0, 1.0), (10.02, 1.1), (10.04, 1.2)):
        log.add(_pose(seconds, x))
    since = log.mark()  # a lesson starts its run here
    log.add(_pose(10.08, 1.3))
    assert [s.pose[0] for s in log.run()] == [1.0, 1.2, 1.3]  # 10.02: within 1/25 s
    assert [s.pose[0] for s in log.run(since)] == [1.3]
    for seconds, x in ((2.0, 0.0), (2.04, 0.1)):  # the world restarted: time went back
        log.add(_pose(seconds, x))
    assert [(s.time_s, s.pose[0]) for s in log.run(since)] == [(2.0, 0.0), (2.04, 0.1)]
    assert log.epoch == 1


def test_the_log_is_bounded() -> None:
    log = PoseLog(fps=10, max_s=2.0)
    for i in range(100):
        log.add(_pose(i * 0.1, float(i)))
    assert len(log.run()) == 20 and log.run()[-1].pose[0] == 99.0
