# microhard_gs targets, included by the root Makefile.
#   make fuzz-gs         libFuzzer (clang, ASan+UBSan) over the link bytes, FUZZ_SECONDS long (tools/kit.mk)
#   make fuzz-smoke-gs   the same for FUZZ_SMOKE_SECONDS (CI)
#   make bench-gs        telemetry rate held and CPU share of the node at 10 Hz and 50 Hz
GS_DIR := $(ROOT)/microhard_gs
GS_FUZZ_DIR := $(ROOT)/.build/fuzz/gs/gen
# The stack's one lat/lon <-> north/east module (C99, common/src) comes along, compiled as C.
GS_FUZZ_SOURCES := $(GS_DIR)/fuzz/fuzz_gs_core.cpp $(sort $(wildcard $(GS_DIR)/src/core/*.cpp)) \
  $(ROOT)/common/src/geo_wgs84.c

.PHONY: bench-gs
BENCH_TARGETS += bench-gs

FUZZ_COMPONENTS += gs
FUZZ_gs_HARNESSES := gs_core
FUZZ_gs_gs_core_SOURCES := $(GS_FUZZ_SOURCES)
FUZZ_gs_gs_core_FLAGS := -I$(GS_DIR)/src/core -I$(GS_DIR)/test -I$(GS_FUZZ_DIR)/tunables -I$(GS_FUZZ_DIR)/generated \
  -I$(ROOT)/drone_ros/common/include -I$(ROOT)/common/src -isystem $(GS_FUZZ_DIR)/mavlink
FUZZ_gs_gs_core_SEEDS := $(GS_DIR)/fuzz/corpus
FUZZ_gs_DEPS = $(wildcard $(GS_DIR)/src/core/*.h) $(GS_FUZZ_DIR)/mavlink/development/mavlink.h \
  $(GS_FUZZ_DIR)/tunables/tunables_table.h $(GS_FUZZ_DIR)/generated/decision_status_names.h

# The MAVLink headers are generated from the installed pymavlink here too, never checked in.
$(GS_FUZZ_DIR)/mavlink/development/mavlink.h:
	@$(VENV)/bin/python -c "import pymavlink" 2>/dev/null || { echo "fuzz-gs: no pymavlink in $(VENV): run make deps"; exit 1; }
	@rm -rf $(GS_FUZZ_DIR)/mavlink && mkdir -p $(GS_FUZZ_DIR)
	@$(VENV)/bin/python -m pymavlink.tools.mavgen --lang=C --wire-protocol=2.0 -o $(GS_FUZZ_DIR)/mavlink \
	  "$$($(VENV)/bin/python -c 'import os, pymavlink; print(os.path.join(os.path.dirname(pymavlink.__file__), "dialects/v20/development.xml"))')" > /dev/null

# The parameter table is the aircraft's tunables list, written by the controller's generator.
$(GS_FUZZ_DIR)/tunables/tunables_table.h: $(ROOT)/tools/gen_tunables.py $(ROOT)/aircraft/$(AIRCRAFT)/tunables.yaml $(ROOT)/aircraft/$(AIRCRAFT)/controller_param.yaml
	@$(PYTHON) $(ROOT)/tools/gen_tunables.py $(ROOT)/aircraft/$(AIRCRAFT)/tunables.yaml \
	  $(ROOT)/aircraft/$(AIRCRAFT)/controller_param.yaml $@

$(GS_FUZZ_DIR)/generated/decision_status_names.h: $(ROOT)/tools/gen_decision_status.py $(ROOT)/msg/DecisionStatus.msg
	@$(PYTHON) $(ROOT)/tools/gen_decision_status.py --cpp $(ROOT)/msg/DecisionStatus.msg $@

bench-gs: build
	@$(ROSENV) DRONE_ROS_WS=$(WS) $(VENV)/bin/python $(GS_DIR)/bench/bench_gs.py
