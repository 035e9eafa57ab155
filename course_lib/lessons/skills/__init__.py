"""An exercise for every skill of the tutorial, each judged from the robot's measured motion.

- lesson 7, `DriveExercise`: set `velocity` while the node runs, so the robot drives a given
  distance in a given time;
- lesson 9, `ParamsFileExercise`: dump, edit, restart with `--params-file`: the robot starts at
  the new speed from its first second;
- lesson 10, `LaunchExercise`: a launch file of the learner's starts the node at a speed;
- lesson 11, `SavedPanelExercise`: a value set with the panel and saved survives a restart of
  the node because the learner passes the saved file.

`judge` holds the verdicts and the hints (pure), `measure` what is measured (/odom, the node's
log lines and files), `attempts` the attempt counts kept in the learner's folder, `exercises`
the classes a lesson arms. Lesson 11's travel exercise (`lessons/exercise.py`) shares the
verdict, the attempt log and the hub's report.
"""
