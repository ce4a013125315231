# The one front door. `make run` flies the main job; `make test` installs, builds and passes
# every test. Components add bench-<c> and verify-<c> in <folder>/make.mk and declare their EVA
# and fuzz inputs there; tools/kit.mk makes verify-<c>-eva, fuzz-<c> and fuzz-smoke-<c>.
SHELL := /bin/bash
.DEFAULT_GOAL := help
ROOT := $(abspath $(dir $(lastword $(MAKEFILE_LIST))))
WS := $(ROOT)/.build/ws
VENV := $(ROOT)/.venv
# Which Python runs what: cmake/python.cmake. PYTHON is catkin's PYTHON_EXECUTABLE (ROS's Python);
# ROSENV puts the venv first on PATH, so `python3` in a target is the venv's.
PYTHON := /usr/bin/python3
JOBS ?= 2
# The one aircraft (aircraft/<name>/) a build is for: catkin's drone_ros_AIRCRAFT and the kit's.
AIRCRAFT ?= DG808
# Every ROS-aware command runs with the workspace sourced and the venv's Python first on PATH.
ROSENV := source $(WS)/devel/setup.bash && export PATH=$(VENV)/bin:$$PATH &&
# Every other recipe too has the venv first on PATH, so the scripts' `python3` is the venv's
# (Debian's Python and its ROS modules, plus PyPI's) and never a python3 that happens to be first
# on a user's PATH (a pyenv build without genmsg stopped make due-image, coverage-ha and
# verify-ha-m3). Before make deps makes the venv, the entry names nothing and PATH is as it was.
export PATH := $(VENV)/bin:$(PATH)

VERIFY_TARGETS :=
VERIFY_FIRST :=
VERIFY_PREP :=
BENCH_TARGETS :=
FUZZ_TARGETS :=
FUZZ_SMOKE_TARGETS :=
-include $(sort $(wildcard $(ROOT)/*/make.mk $(ROOT)/*/*/make.mk))
# The verify and fuzz kit: turns the components' declarations into verify-<c>-eva, fuzz-<c> and
# fuzz-smoke-<c> (before the aggregate targets below, which list them).
include $(ROOT)/tools/kit.mk

.PHONY: help deps build test test-each run lint verify verify-each bench fuzz fuzz-smoke check-user-ws check-install check-workspaces check-aircraft-folder clean
help:
	@echo "make run    set up and fly the main job"
	@echo "make test   set up, build and run every test"
	@echo "make verify | bench | fuzz    static analysis, benchmarks, fuzzing"

deps:
	@$(ROOT)/tools/install_deps.sh

$(WS)/src/drone_ros:
	@mkdir -p $(WS)/src && ln -sfn ../../.. $(WS)/src/drone_ros && touch $(ROOT)/.build/CATKIN_IGNORE

build: deps $(WS)/src/drone_ros
	@cd $(WS) && PATH=/usr/bin:$$PATH catkin_make -j$(JOBS) -DPYTHON_EXECUTABLE=$(PYTHON) -Ddrone_ros_AIRCRAFT=$(AIRCRAFT) \
	  -DCATKIN_ENABLE_TESTING=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
	  > $(ROOT)/.build/build.log 2>&1 \
	  || { tail -n 60 $(ROOT)/.build/build.log; echo "build failed: full log in .build/build.log"; exit 1; }
	@echo "build: ok (log in .build/build.log)"

# uninstalled_script is ignored on purpose: the executables it names are developer tools
# (verify, bench, install and test-summary scripts) that have no place in an install space.
# tools/lint.sh: clang-format on the listed files, clang-tidy naming on the C++ nodes (it
# reads the build's compile_commands.json), pyflakes, and function length (lizard).
lint: build
	@cd $(WS)/src && ROS_PACKAGE_PATH=$(WS)/src $(VENV)/bin/catkin_lint --strict -W2 --offline --ignore uninstalled_script drone_ros 2>&1 | grep -v rosdep; exit $${PIPESTATUS[0]}
	@$(ROOT)/tools/lint.sh $(WS)

test: build lint
	@$(ROSENV) $(ROOT)/tools/run_tests.sh $(WS) $(VENV)

# Each Python test file alone, in a process of its own (tools/run_tests_each.sh).
test-each: build
	@$(ROSENV) $(ROOT)/tools/run_tests_each.sh $(WS) $(VENV)

# The build's aircraft flies its own case study (make run AIRCRAFT=<name>).
run: build
	@$(ROSENV) $(ROOT)/tools/run_main.sh $(WS) --aircraft $(AIRCRAFT)

# The analyses run JOBS at a time, each one's output kept together: the firmware loop's EVA alone
# takes ~17 min on the slow CI machine, the rest ~12 min, which ran after it in turn (29 min).
# VERIFY_FIRST (components' make.mk) names the longest, started first: deps and VERIFY_PREP (what
# it needs made) are made before, or make would fill both slots with later targets meanwhile.
verify:
	@$(MAKE) --no-print-directory deps $(VERIFY_PREP)
	@$(MAKE) --no-print-directory -j$(JOBS) --output-sync=target -o deps verify-each
verify-each: $(VERIFY_FIRST) $(VERIFY_TARGETS)
bench: $(BENCH_TARGETS)
fuzz: $(FUZZ_TARGETS)
fuzz-smoke: $(FUZZ_SMOKE_TARGETS)

# A fresh clone of HEAD built the way README's "your own catkin workspace" says: make deps, then
# plain catkin_make in a new workspace (tools/check_user_workspace.sh). CI runs it.
check-user-ws:
	@$(ROOT)/tools/check_user_workspace.sh

# Both on one fresh clone, as CI runs them: the user's workspace, then its `catkin_make install`
# (tools/check_workspaces.sh): one full build fewer.
check-workspaces:
	@JOBS=$(JOBS) $(ROOT)/tools/check_workspaces.sh

# An aircraft is a folder: a fresh clone with a new aircraft folder (a changed copy of the DG808)
# designs, builds and flies it, and nothing else in its tree changes (tools/check_aircraft_folder.sh).
check-aircraft-folder:
	@JOBS=$(JOBS) $(ROOT)/tools/check_aircraft_folder.sh

# The install space alone (a fresh clone's `catkin_make install`) resolves the flight launch.
check-install:
	@JOBS=$(JOBS) $(ROOT)/tools/check_install_space.sh

clean:
	rm -rf $(ROOT)/.build
