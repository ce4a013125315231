# microhard_gs targets, included by the root Makefile.
#   make fuzz-gs         libFuzzer (clang, ASan+UBSan) over the link bytes, GS_FUZZ_SECONDS long
#   make fuzz-gs-smoke   the same for 20 s
#   make bench-gs        telemetry rate held and CPU share of the node at 10 Hz and 50 Hz
GS_DIR := $(ROOT)/microhard_gs
GS_FUZZ_DIR ?= $(ROOT)/.build/fuzz_gs
GS_FUZZ_BIN := $(GS_FUZZ_DIR)/fuzz_gs_core
GS_CLANGXX ?= $(shell command -v clang++-14 || command -v clang++)
GS_FUZZ_SECONDS ?= 300
GS_FUZZ_SOURCES := $(GS_DIR)/fuzz/fuzz_gs_core.cpp $(GS_DIR)/src/core/gs_core.cpp \
  $(GS_DIR)/src/core/mission.cpp $(GS_DIR)/src/core/mission_frames.cpp $(GS_DIR)/src/core/modes.cpp \
  $(GS_DIR)/src/core/geo.cpp $(GS_DIR)/src/core/gs_home.cpp $(GS_DIR)/src/core/params.cpp \
  $(GS_DIR)/src/core/signing_key.cpp
# The stack's one lat/lon <-> north/east module (C99, in the HA core), compiled as C.
GS_GEO_C := $(ROOT)/arduino_ha/src/core/geo_wgs84.c
GS_GEO_OBJ = $(GS_FUZZ_DIR)/geo_wgs84.o

.PHONY: fuzz-gs fuzz-gs-smoke bench-gs
FUZZ_TARGETS += fuzz-gs
FUZZ_SMOKE_TARGETS += fuzz-gs-smoke
BENCH_TARGETS += bench-gs

# The MAVLink headers are generated from the installed pymavlink here too, never checked in.
$(GS_FUZZ_DIR)/mavlink/development/mavlink.h:
	@$(VENV)/bin/python -c "import pymavlink" 2>/dev/null || { echo "fuzz-gs: no pymavlink in $(VENV): run make deps"; exit 1; }
	@rm -rf $(GS_FUZZ_DIR)/mavlink && mkdir -p $(GS_FUZZ_DIR)
	@$(VENV)/bin/python -m pymavlink.tools.mavgen --lang=C --wire-protocol=2.0 -o $(GS_FUZZ_DIR)/mavlink \
	  "$$($(VENV)/bin/python -c 'import os, pymavlink; print(os.path.join(os.path.dirname(pymavlink.__file__), "dialects/v20/development.xml"))')" > /dev/null

# The parameter table is the aircraft's tunables list, written by the controller's generator.
GS_FUZZ_AIRCRAFT ?= DG808
$(GS_FUZZ_DIR)/tunables/tunables_table.h: $(ROOT)/tools/gen_tunables.py $(ROOT)/aircraft/$(GS_FUZZ_AIRCRAFT)/tunables.yaml $(ROOT)/aircraft/$(GS_FUZZ_AIRCRAFT)/controller_param.yaml
	@$(VENV)/bin/python $(ROOT)/tools/gen_tunables.py $(ROOT)/aircraft/$(GS_FUZZ_AIRCRAFT)/tunables.yaml \
	  $(ROOT)/aircraft/$(GS_FUZZ_AIRCRAFT)/controller_param.yaml $@

$(GS_GEO_OBJ): $(GS_GEO_C) $(ROOT)/arduino_ha/src/core/geo_wgs84.h
	@mkdir -p $(GS_FUZZ_DIR)
	$(subst clang++,clang,$(GS_CLANGXX)) -std=c99 -g -O1 -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all \
	  -Wall -Wextra -Werror -c $(GS_GEO_C) -o $@

$(GS_FUZZ_BIN): $(GS_FUZZ_SOURCES) $(GS_GEO_OBJ) $(wildcard $(GS_DIR)/src/core/*.h) $(GS_FUZZ_DIR)/mavlink/development/mavlink.h $(GS_FUZZ_DIR)/tunables/tunables_table.h
	@test -n "$(GS_CLANGXX)" || { echo "fuzz-gs: clang++ not found (microhard_gs/apt-packages.txt)"; exit 1; }
	$(GS_CLANGXX) -std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
	  -Wall -Wextra -Werror -I$(GS_DIR)/src/core -I$(GS_FUZZ_DIR)/tunables -I$(ROOT)/drone_ros/common/include -I$(ROOT)/arduino_ha/src/core -isystem $(GS_FUZZ_DIR)/mavlink $(GS_FUZZ_SOURCES) $(GS_GEO_OBJ) -o $@

# The full log goes to a file; the console gets the verdict and the run count, and on a crash the
# log's tail with the reproducer's path.
fuzz-gs: $(GS_FUZZ_BIN)
	@mkdir -p $(GS_FUZZ_DIR)/corpus
	@echo "fuzz-gs: gs_core for $(GS_FUZZ_SECONDS) s (log: $(GS_FUZZ_DIR)/fuzz.log)"
	@$(GS_FUZZ_BIN) -max_total_time=$(GS_FUZZ_SECONDS) -print_final_stats=1 -artifact_prefix=$(GS_FUZZ_DIR)/ \
	  $(GS_FUZZ_DIR)/corpus $(GS_DIR)/fuzz/corpus > $(GS_FUZZ_DIR)/fuzz.log 2>&1 \
	  || { tail -n 40 $(GS_FUZZ_DIR)/fuzz.log; echo "fuzz-gs: crash, see $(GS_FUZZ_DIR)/fuzz.log"; exit 1; }
	@grep -E 'stat::(number_of_executed_units|average_exec_per_sec)' $(GS_FUZZ_DIR)/fuzz.log | sed 's/^/  /'
	@echo "fuzz-gs: no crash in $(GS_FUZZ_SECONDS) s"

fuzz-gs-smoke:
	@$(MAKE) --no-print-directory -f $(ROOT)/Makefile fuzz-gs GS_FUZZ_SECONDS=20

bench-gs: build
	@$(ROSENV) DRONE_ROS_WS=$(WS) $(VENV)/bin/python $(GS_DIR)/bench/bench_gs.py
