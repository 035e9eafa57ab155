# Start-up file of a lab's bash terminal (course_lib/lab/jupyterlab.py starts `bash --rcfile <this> -i`).
#
# The lab's terminal already has ROS 2 Jazzy: `ros2`, rclpy and the course's workspace come
# with the lab's environment (ROS_DISTRO=jazzy). The ROS 2 docs start every tutorial with
# `source /opt/ros/jazzy/setup.bash`, a file this machine does not have (it would need a
# system-wide ROS install). So `source` and `.` of a ROS install's set-up script under
# /opt/ros that does not exist print one line instead of failing; everything else (your
# workspace's `source install/setup.bash` included) is bash's own `source`.

_course_ros_install_script() {
  # True when $1 is a ROS install's set-up script under /opt/ros that this machine lacks.
  case "$1" in
    /opt/ros/*/setup.*sh | /opt/ros/*/local_setup.*sh) [ ! -e "$1" ] ;;
    *) return 1 ;;
  esac
}

_course_ros_install_note() {
  local distro="${1#/opt/ros/}"
  distro="${distro%%/*}"
  if [ "$distro" = "${ROS_DISTRO:-jazzy}" ]; then
    echo "ROS 2 ${ROS_DISTRO:-jazzy} is already set up in this lab's terminal (ROS_DISTRO=${ROS_DISTRO:-jazzy}): nothing to source."
    return 0
  fi
  echo "This lab has ROS 2 ${ROS_DISTRO:-jazzy} only, already set up; there is no $1: use the ${ROS_DISTRO:-jazzy} tutorials." >&2
  return 1
}

source() {
  if [ $# -eq 0 ]; then
    builtin source
    return
  fi
  if _course_ros_install_script "$1"; then
    _course_ros_install_note "$1"
    return
  fi
  local _course_script="$1"
  shift
  builtin source "$_course_script" "$@"
}

.() {
  source "$@"
}

# The lab's `ros2` daemon starts with its first terminal (course_lib/lab/daemon_keeper.py),
# in the background: the prompt does not wait, and the first command finds it warm.
if [ -n "${COURSE_LAB_SOCKET:-}" ]; then
  (python -m course_lib.lab.daemon_keeper >/dev/null 2>&1 &)
fi

# Then what an interactive bash reads anyway.
if [ -f "$HOME/.bashrc" ]; then
  source "$HOME/.bashrc"
fi
