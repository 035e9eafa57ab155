# The course in one image, four doors (README: "On macOS, Windows or another Linux"):
#   one learner:     docker run --rm -p 8888:8888 -v ros2-course:/home/jovyan IMAGE
#   Binder:          repo2docker builds this file (NB_USER/NB_UID build arguments)
#   dev container:   .devcontainer/devcontainer.json builds it and forwards port 8888
#   Kubernetes:      the `singleuser` stage is deploy/kubernetes/'s learners' image
# `make image` builds it. Debian 12 and its CPython 3.11, as `make test` proves the course;
# every Python package comes from environment.txt's pins.
FROM debian:bookworm-slim AS course

# g++, make and the Python headers build tf2_msgs in rosject/ (`make setup`); Mesa's EGL
# renders the simulated camera offscreen; tini is PID 1, so SIGTERM reaches the lab and the
# lab's orphans are reaped.
RUN apt-get update \
    && apt-get install -y --no-install-recommends \
        python3 python3-venv python3-dev g++ make ca-certificates \
        libegl1 libegl-mesa0 libgl1-mesa-dri libopengl0 tini \
    && rm -rf /var/lib/apt/lists/*

# Unset on most machines. A build machine whose network re-signs TLS passes its certificate
# bundle (as `make image` does when the host sets one), and may lend uv its package cache.
ARG PIP_CERT
ARG SSL_CERT_FILE
ARG UV_CACHE_DIR

# The course, built as root and read-only for the learner (as on a class hub). The pinned
# packages first, in a layer of their own: a change to the course's files does not download
# them again.
WORKDIR /opt/ros2-params-course
COPY environment.txt ./
RUN python3 -m venv .venv \
    && .venv/bin/python -m pip install --quiet --disable-pip-version-check \
        "$(grep '^uv==' environment.txt)" \
    && { .venv/bin/uv pip install --quiet --python .venv/bin/python --compile-bytecode \
            -r environment.txt \
        || .venv/bin/python -m pip install --quiet --disable-pip-version-check \
            -r environment.txt; } \
    && rm -rf "$HOME/.cache"
COPY . .
# `make doctor` fails the build when the course would not work (rclpy, tf2_msgs, the camera).
RUN make setup PYTHON=python3 && make doctor && rm -rf "$HOME/.cache"

# The learner: uid 1000, as Binder and Zero to JupyterHub run it. Their home holds their work
# (their notebooks, my_files/, their own workspaces): mount a volume there to keep it.
ARG NB_USER=jovyan
ARG NB_UID=1000
RUN useradd --uid "${NB_UID}" --gid 100 --create-home --shell /bin/bash "${NB_USER}"
ENV HOME=/home/${NB_USER} \
    USER=${NB_USER} \
    SHELL=/bin/bash \
    PATH=/opt/ros2-params-course/.venv/bin:${PATH}
USER ${NB_UID}
WORKDIR /home/${NB_USER}
EXPOSE 8888

# With no command, one learner's lab on port 8888 (it prints lesson 1's address and token). A
# command of a Jupyter server (Binder's and the hub's `jupyterhub-singleuser ...`) runs as the
# learner's lab with its options: course_lib/tools/image_entry.py.
ENTRYPOINT ["tini", "--", "/opt/ros2-params-course/.venv/bin/python", "-m", "course_lib", "image"]
CMD []


# The learners' servers of deploy/kubernetes/: jupyterhub-singleuser of the chart's hub's
# JupyterHub release (image-pins.txt, over environment.txt).
FROM course AS singleuser
ARG NB_UID=1000
ARG PIP_CERT
USER root
RUN cd /opt/ros2-params-course \
    && .venv/bin/python -m pip install --quiet --disable-pip-version-check --no-cache-dir \
        --no-deps -r deploy/kubernetes/image-pins.txt
USER ${NB_UID}
# values.yaml's singleuser.cmd, as the local hub's spawner runs it (course_lib/hub/hub_config.py)
CMD ["/opt/ros2-params-course/.venv/bin/python", "-m", "course_lib", "hub-lab"]


# The last stage is what Binder and a plain `docker build .` make: the course.
FROM course
