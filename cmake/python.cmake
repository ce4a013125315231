# Which Python runs what, decided here and nowhere else. The rule:
#  1. ROS's Python, /usr/bin/python3 on Debian 12, is catkin's PYTHON_EXECUTABLE: it runs every
#     build step below and is the interpreter catkin_install_python writes into the nodes it
#     installs. Whoever runs catkin_make passes it (-DPYTHON_EXECUTABLE=/usr/bin/python3: the
#     Makefile's PYTHON, tools/check_install_space.sh, tools/check_user_workspace.sh,
#     arduino_ha/tools/coverage_ha.sh).
#  2. Everything else runs `python3` from PATH: scripts start with `#!/usr/bin/env python3`, shell
#     scripts call `python3`, a Python process starts its children with sys.executable. The
#     Makefile's targets source the workspace and put the venv (.venv, made by `make deps` from
#     /usr/bin/python3 with --system-site-packages, so ROS's modules stay visible) first on PATH:
#     there `python3` is the venv's, which adds the PyPI packages (jsbsim, pymavlink, pytest-xdist).
#  3. One node needs a PyPI package while catkin gives it ROS's Python: hil/scripts/hil_sim.py
#     (jsbsim) re-runs itself under $DRONE_ROS_VENV, else the package's .venv.
# The stack's own modules are packages (setup.py, catkin_python_setup): with the workspace sourced
# every interpreter above imports them by name; nothing edits sys.path.
#
# Every generator (tools/gen_*.py, arduino_ha's config and message generators) needs only the
# standard library, PyYAML and jsonschema (Debian python3-yaml, python3-jsonschema: the aircraft's
# YAML files are read through tools/check_config.py, against aircraft/schema/), and runs with
# catkin's PYTHON_EXECUTABLE:
# the Makefile passes -DPYTHON_EXECUTABLE=/usr/bin/python3, as a user's own workspace does with
# `catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3` (ROS 1 on Debian 12 is Python 3).
#
# One step needs a PyPI package: mavgen (pymavlink, microhard_gs/requirements.txt) writes the
# MAVLink headers. DRONE_ROS_PYMAVLINK_PYTHON is the first of -D${PROJECT_NAME}_PYMAVLINK_PYTHON,
# PYTHON_EXECUTABLE and this clone's .venv (made by `make deps`) that imports pymavlink;
# microhard_gs calls find_pymavlink_python(), so a build without it does not need pymavlink.
if(NOT PYTHON_EXECUTABLE)
  message(FATAL_ERROR "PYTHON_EXECUTABLE is unset: configure through catkin (find_package(catkin) sets it)")
endif()

execute_process(COMMAND ${PYTHON_EXECUTABLE} -c "import jsonschema, yaml"
  RESULT_VARIABLE _generator_modules_rc OUTPUT_QUIET ERROR_QUIET)
if(NOT _generator_modules_rc EQUAL 0)
  message(FATAL_ERROR "${PYTHON_EXECUTABLE} cannot import jsonschema and yaml: run `make deps` "
    "(apt-get install python3-jsonschema python3-yaml)")
endif()
# What a generator reading an aircraft's YAML depends on besides the file: the checker and schemas.
set(${PROJECT_NAME}_CONFIG_CHECK_DEPENDS
  ${PROJECT_SOURCE_DIR}/tools/stack_tools/check_config.py
  ${PROJECT_SOURCE_DIR}/tools/stack_tools/gen_limits_ranges.py
  ${PROJECT_SOURCE_DIR}/tools/stack_tools/generated_file.py
  ${PROJECT_SOURCE_DIR}/tools/stack_tools/paths.py
  ${PROJECT_SOURCE_DIR}/aircraft/schema/airframe.schema.json
  ${PROJECT_SOURCE_DIR}/aircraft/schema/controller_param.schema.json
  ${PROJECT_SOURCE_DIR}/aircraft/schema/gains.schema.json
  ${PROJECT_SOURCE_DIR}/aircraft/schema/ground_station.schema.json
  ${PROJECT_SOURCE_DIR}/aircraft/schema/limits.schema.json
  ${PROJECT_SOURCE_DIR}/aircraft/schema/tunables.schema.json)

set(${PROJECT_NAME}_PYMAVLINK_PYTHON "" CACHE FILEPATH
    "Python with pymavlink for mavgen (found automatically when empty)")
# Sets DRONE_ROS_PYMAVLINK_PYTHON and DRONE_ROS_PYMAVLINK_DIR (the package folder), or stops.
function(find_pymavlink_python)
  set(_candidates "${${PROJECT_NAME}_PYMAVLINK_PYTHON}" "${PYTHON_EXECUTABLE}" "${PROJECT_SOURCE_DIR}/.venv/bin/python")
  set(_found "")
  foreach(_candidate ${_candidates})
    if(_found STREQUAL "" AND EXISTS "${_candidate}")
      execute_process(
        COMMAND ${_candidate} -c "import os, pymavlink; print(os.path.dirname(pymavlink.__file__))"
        RESULT_VARIABLE _rc OUTPUT_VARIABLE _pymavlink_dir ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
      if(_rc EQUAL 0)
        set(DRONE_ROS_PYMAVLINK_PYTHON ${_candidate} PARENT_SCOPE)
        set(_found ${_candidate})
        set(DRONE_ROS_PYMAVLINK_DIR ${_pymavlink_dir} PARENT_SCOPE)
      endif()
    endif()
  endforeach()
  if(_found STREQUAL "")
    message(FATAL_ERROR "no Python with pymavlink (tried: ${_candidates}). Run `make deps` in the "
      "source folder (it makes .venv from microhard_gs/requirements.txt) or pass "
      "-D${PROJECT_NAME}_PYMAVLINK_PYTHON=/path/to/python.")
  endif()
  message(STATUS "${PROJECT_NAME}: generators with ${PYTHON_EXECUTABLE}, mavgen with ${_found}")
endfunction()
