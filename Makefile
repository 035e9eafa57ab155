# The newcomer's menu. `make lab` starts the course, `make test` runs every test.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP_ENV := $(VENV)/.installed
STAMP_WS := rosject/install/.built
STAMP_ROS2 := $(VENV)/.ros2-launcher
# colcon --symlink-install links every source and installed file, so editing one needs no
# rebuild: only the build description does (CMake packages: their interface files and
# templates too), and a launch/ or config/ folder whose files were added or removed (setup.py
# installs them by glob).
ROSJECT_SOURCES := $(shell find rosject -path rosject/build -prune -o -path rosject/install -prune -o -path rosject/log -prune -o \( -name package.xml -o -name setup.py -o -name setup.cfg -o -name CMakeLists.txt -o -name '*.in' -o -name '*.msg' -o -name '*.srv' -o -name '*.action' -o -path '*/resource/*' -o -type d \( -name launch -o -name config \) \) -print 2>/dev/null)

.PHONY: lab setup hub image test test-fast soak chaos bench book notebooks check-config lint format clean doctor stop smoke-python

lab: setup  ## Check config/, then start JupyterLab on the first lesson (EXTRA=... passes options to jupyter lab)
	$(PY) -m course_lib lab $(EXTRA)

setup: $(STAMP_ENV) $(STAMP_WS) $(STAMP_ROS2)  ## Build the environment and the ROS workspace
	@# The course's bytecode, compiled here once: no command depends on writing a cache (a
	@# hub's shared environment is read-only to learners; PYTHONDONTWRITEBYTECODE may be set).
	@$(PY) -m compileall -q -j 0 course_lib

hub: setup  ## Start the class's JupyterHub (as root: `sudo make hub`; settings in config/hub.yaml)
	$(PY) -m course_lib hub $(EXTRA)

image:  ## Build the course's image (Dockerfile: a learner's lab, Binder, dev container; IMAGE=name:tag, TARGET=singleuser for Kubernetes)
	scripts/build_image.sh

test: setup  ## Run the whole test suite (unit, integration, notebooks, browser)
	$(PY) tests/harness/run_suite.py

test-fast: setup  ## Unit tests only (no ROS, milliseconds)
	$(PY) -m pytest tests/unit -q

soak: setup  ## A long random walk through the lessons in one lab at a person's pace (WALK_STEPS=100, WALK_SEED=random, WALK_PACE=person|ci|none)
	WALK_SOAK=1 WALK_STEPS=$(or $(WALK_STEPS),100) WALK_SEED=$(WALK_SEED) WALK_PACE=$(WALK_PACE) $(PY) -m pytest tests/browser/test_lab_random_walk.py -k soak -s

chaos: setup  ## The lessons' random walk in one lab with a fault between steps (CHAOS_FAULTS=100, CHAOS_SEED=random): processes killed or stopped, the page reloaded
	CHAOS_FAULTS=$(or $(CHAOS_FAULTS),100) CHAOS_SEED=$(CHAOS_SEED) $(PY) -m pytest tests/browser/test_lab_chaos.py -k test_chaos_walk -s

bench: setup  ## Print the course's speed and memory figures
	$(PY) -m bench

book: setup  ## Build the course as a static site, build/book/html/index.html (ARGS=--rerecord runs the driving lessons again)
	$(PY) -m course_lib.book $(ARGS)

notebooks: setup  ## Check config/, render the lessons from it, re-execute them (ARGS="--all", "--config DIR", names; ARGS=--help)
	$(PY) -m course_lib notebooks $(ARGS)

check-config: setup  ## Check every file of config/, alone and together (ARGS="--config DIR")
	$(PY) -m course_lib check-config $(ARGS)

smoke-python:  ## Prove CPython 3.12 as well: fresh venv, environment.txt, rclpy + MuJoCo smoke
	scripts/smoke_python.sh $(SMOKE_PYTHON)

lint: setup  ## ruff lint and format check; the layers contract (imports only point down); mypy
	$(VENV)/bin/ruff check . && $(VENV)/bin/ruff format --check . && $(VENV)/bin/lint-imports --no-cache && $(VENV)/bin/mypy course_lib

format: setup
	$(VENV)/bin/ruff format . && $(VENV)/bin/ruff check --fix .

doctor:  ## Check the install works (rclpy, tf2_msgs, the camera), say what is stale and what runs; non-zero if broken
	@test -x $(PY) || { echo "No environment in $(VENV)/ yet: run \`make setup\`."; exit 1; }
	@$(PY) -m course_lib doctor

stop: ## Stop the course processes this clone started (labs, simulations, viewers, nodes, daemons; ARGS=--all: every clone's)
	$(PY) -m course_lib stop $(ARGS)

# slim_imports.pth: packages load without the parts of their __init__ a process never uses
# (a message generator, IPython, httpx's CLI, every message of a package; course_lib/tools/slim_imports.py).
$(STAMP_ENV): environment.txt pyproject.toml scripts/check_platform.py course_lib/tools/slim_imports.py course_lib/tools/kernelspec.py
	@$(PYTHON) scripts/check_platform.py
	@test -x $(PY) || $(PYTHON) -m venv $(VENV)
	@# uv installs environment.txt's pins in parallel; pip is the fallback (uv reads no pip
	@# configuration: a machine that reaches packages only through pip's index settings).
	$(PY) -m pip install --quiet --disable-pip-version-check "$$(grep '^uv==' environment.txt)"
	$(VENV)/bin/uv pip install --quiet --python $(PY) --compile-bytecode -r environment.txt \
	  || $(PY) -m pip install --quiet --disable-pip-version-check -r environment.txt
	$(PY) -m pip install --quiet --disable-pip-version-check --no-deps --no-build-isolation -e .
	$(PY) -c "from course_lib.tools.slim_imports import install_pth; install_pth()"
	@# The python3 kernel without debugpy (8 MiB a kernel): course_lib/notebook/kernel_launcher.py
	$(PY) -c "from course_lib.tools.kernelspec import install_kernelspec; install_kernelspec()"
	@# jsonschema's optional IRI check (jupyter_events asks for jsonschema[format-nongpl]) builds
	@# a grammar at import: 20 MiB and 1 s in every Jupyter server. Nothing here validates IRIs.
	$(PY) -m pip uninstall --quiet --yes rfc3987-syntax
	@touch $@

# The venv's `ros2` starts Python once (course_lib/ros2/command/quick.py): after every pip
# install, which writes its own console script there.
$(STAMP_ROS2): $(STAMP_ENV) course_lib/ros2/command/quick.py
	$(PY) -m course_lib.ros2.command.quick --install-launcher
	@touch $@

$(STAMP_WS): $(STAMP_ENV) $(ROSJECT_SOURCES) course_lib/tools/workspace.py course_lib/cmake/wheel_fixups.cmake
	$(PY) -m course_lib build

clean:  ## Remove the environment and the built workspace
	rm -rf $(VENV) rosject/build rosject/install rosject/log
