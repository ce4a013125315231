# arduino_ha targets (included by the root Makefile).
#   make verify-ha   Frama-C EVA over the HA core and over the firmware loop with all it runs
#                    (no alarms allowed), Cortex-M3 cross-compile
#                    with flash/RAM/stack figures, and the Due sketch built against an Arduino
#                    API shim (-Werror) and run on the host with a fake Arduino. Deterministic;
#                    fails on any alarm, unproven assertion, warning or failed check.
#   make sketch-ha   assemble the sketch arduino-cli compiles into .build/sketch/arduino_ha, with
#                    the limits of the build's aircraft (AIRCRAFT=<name>; also due-image, pil-image)
#   make due-image   build that sketch into the Due's .elf and .bin (.build/due_image) the way
#                    arduino-cli does, against the real SAM core 1.6.12, Wire and Servo; prints
#                    flash, RAM and the largest stack frame. Part of `make verify`.
#   make pil-image   the firmware for QEMU mps2-an385 (.build/pil/ha_pil.elf): processor in the loop
#   make bench-ha    instructions per control step on a Cortex-M3 under QEMU, ns per step on
#                    the host.
#   make prove-ha    Frama-C WP over the core's ACSL contracts (src/core/README.md, "Proofs"):
#                    a line per contract, `goals: N proved of M`; fails on any goal not proved
#                    or a negative control proved. Part of `make verify`.
#   make coverage-ha branch coverage of the HA core by the HA's host tests (gcov, -O0): metric
#                    lines per file, every untaken branch listed; fails below the floors below.
# Tools come from arduino_ha/apt-packages.txt through `make deps`.
HA_DIR := $(ROOT)/arduino_ha
HA_VERIFY_OUT := $(ROOT)/.build/arduino_ha_verify

VERIFY_TARGETS += verify-ha
BENCH_TARGETS += bench-ha

.PHONY: verify-ha verify-ha-m3 verify-ha-board bench-ha

verify-ha: verify-ha-eva verify-ha-fw-eva verify-ha-m3 verify-ha-board

# EVA over every .c of the core, driven by verify/eva_main.c in two input modes (finite full
# range; every bit pattern incl. NaN and inf), each over an unknown number of control periods;
# the negative control must be flagged and every core function reached. HA_CORE_DIR: try a
# patched copy of the core (verify/ALARMS.md).
HA_CORE_DIR ?= $(HA_DIR)/src/core
# The ground floor the core runs on (common/src): the geodesy and the HP command's CRC, checked
# with the core as part of the trusted code.
HA_FLOOR_DIR := $(ROOT)/common/src
HA_FLOOR_SRC := $(HA_FLOOR_DIR)/geo_wgs84.c $(HA_FLOOR_DIR)/hp_command.c
# The functions EVA takes by their contract instead of their body: each is proved by make
# prove-ha (WP_ha's --fct), so EVA rests on a proof, not on trust (src/core/README.md "Proofs").
HA_BY_CONTRACT := ha_clampf
# The period around the core on a Board (src/firmware): the drivers step the core through it, as
# the firmware does, so it is analysed, reached and measured with the core.
HA_APP_SRC := $(HA_DIR)/src/firmware/ha_app.c $(HA_DIR)/src/firmware/ha_retained.c
EVA_COMPONENTS += ha
EVA_ha_SOURCES = $(sort $(wildcard $(HA_CORE_DIR)/*.c)) $(HA_FLOOR_SRC) $(HA_APP_SRC) $(HA_DIR)/verify/eva_main.c
EVA_ha_ARGS = -I $(HA_CORE_DIR) -I $(HA_FLOOR_DIR) -I $(HA_DIR)/src/firmware --negative $(HA_DIR)/verify/eva_negative_control.c \
  --reach $(HA_CORE_DIR) $(addprefix --reach ,$(HA_FLOOR_SRC) $(HA_APP_SRC)) \
  --case finite-any-periods:main:1:non-finite:-DHA_EVA_STEPS=0 \
  --case any-bits-any-periods:main:1:none:-DHA_EVA_ANY_BITS,-DHA_EVA_STEPS=0 \
  --use-spec $(HA_BY_CONTRACT)
EVA_ha_DEPS = deps

# EVA over the firmware loop (src/firmware) with all it runs: the core, the link and its reports,
# the VN-200 feed and protocol core, on a board whose clock, readings, retained words and byte
# ports are anything (verify/eva_firmware_main.c); part of verify-ha, beside the core's own
# analyses (verify-ha-eva), not before them: make verify runs the two at once.
EVA_COMPONENTS += ha-fw
EVA_ha-fw_SOURCES = $(HA_DIR)/verify/eva_firmware_main.c $(HA_DIR)/src/firmware/ha_firmware.c \
  $(HA_DIR)/src/vn200/ha_vn200_feed.c $(addprefix $(ROOT)/common/vn200/,vn_framer.c vn_binary.c vn_checksum.c vn_ascii.c) \
  $(addprefix $(HA_DIR)/src/link/,ha_link.c ha_link_frame.c ha_link_report.c) $(LINK_GEN_DIR)/ha_msgs.c \
  $(sort $(wildcard $(HA_CORE_DIR)/*.c)) $(HA_FLOOR_SRC) $(HA_APP_SRC)
EVA_ha-fw_ARGS = -I $(HA_CORE_DIR) -I $(HA_FLOOR_DIR) -I $(ROOT)/common/link -I $(HA_DIR)/src/link -I $(HA_DIR)/src/firmware -I $(HA_DIR)/src/vn200 \
  -I $(ROOT)/common/vn200 -D 'HA_LINK_GENERATED_HEADER="$(LINK_GEN_DIR)/ha_msgs.h"' \
  --reach $(HA_DIR)/src/firmware --case any-board:main:1:none --use-spec $(HA_BY_CONTRACT)
EVA_ha-fw_DEPS = deps $(LINK_GEN_DIR)/ha_msgs.c
# The longest analysis of make verify (17 min on the slow CI machine): started first.
VERIFY_FIRST += verify-ha-fw-eva
VERIFY_PREP += $(LINK_GEN_DIR)/ha_msgs.c

verify-ha-m3: deps
	@bash $(HA_DIR)/verify/cross_size.sh $(HA_VERIFY_OUT)/m3

verify-ha-board: deps
	@bash $(HA_DIR)/verify/board_compile_check.sh $(HA_VERIFY_OUT)/board

bench-ha: deps
	@bash $(HA_DIR)/bench/run_bench.sh $(ROOT)/.build/arduino_ha_bench

# The sketch arduino-cli compiles and flashes, assembled under .build/sketch/arduino_ha: the
# sketch with the ground floor from common/: geodesy and the HP command's CRC in src/core/, the
# VN-200 protocol in src/vn200/ (arduino-cli compiles only inside the sketch folder; nothing is
# copied into the source tree). README.md, "Build and
# flash the Due".
HA_SKETCH_OUT := $(ROOT)/.build/sketch
.PHONY: sketch-ha
sketch-ha:
	@echo "sketch-ha: assembled $$(AIRCRAFT=$(AIRCRAFT) bash $(HA_DIR)/tools/assemble_sketch.sh $(HA_SKETCH_OUT))"

# The genuine Due image: platform.txt's recipes against the SAM core where arduino-cli installs it,
# else shared/vendor beside the repository (tools/build_due_image.sh). test/test_due_image.py
# checks the image it makes; README.md, "The Due image without arduino-cli". DUE_EXTRA_FLAGS=...
# as arduino-cli's --build-property compiler.cpp.extra_flags=... (e.g. -DDUE_HP_LINK_PORT=2).
VERIFY_TARGETS += due-image
.PHONY: due-image
due-image: deps
	@AIRCRAFT=$(AIRCRAFT) JOBS=$(JOBS) DUE_EXTRA_FLAGS='$(DUE_EXTRA_FLAGS)' bash $(HA_DIR)/tools/build_due_image.sh $(ROOT)/.build/due_image

# The Due's HIL build (src/board_due/due_hil_board.h: the pins' inputs from the simulator's step
# records on the native USB port, the outputs back in reply records) against the same real core:
# the same script with HA_DUE_HIL=1, into .build/due_hil_image. README.md, "The Due in the loop".
VERIFY_TARGETS += due-hil-image
.PHONY: due-hil-image
due-hil-image: deps
	@AIRCRAFT=$(AIRCRAFT) JOBS=$(JOBS) DUE_EXTRA_FLAGS='-DHA_DUE_HIL=1 $(DUE_EXTRA_FLAGS)' bash $(HA_DIR)/tools/build_due_image.sh $(ROOT)/.build/due_hil_image

# Processor in the loop: the firmware loop as Cortex-M3 machine code for QEMU's mps2-an385
# (pil/pil_main.c: the HP link, the VN-200 and the simulator's control records on three UARTs),
# which `hil/run_flight.py --ha qemu` flies (hil/ha_qemu.py). README.md, "Processor in the loop".
PIL_OUT := $(ROOT)/.build/pil
.PHONY: pil-image
pil-image: deps
	@AIRCRAFT=$(AIRCRAFT) bash $(HA_DIR)/pil/build_pil_image.sh $(PIL_OUT)

# The firmware's instructions per period in the loop, counted in QEMU (-icount), printed as
# metric: lines against the budget (hil/bench/bench_pil.py). Its VN-200 packets come from the
# build's libvn200_encode.so, found through the workspace's setup.bash.
BENCH_TARGETS += bench-pil
.PHONY: bench-pil
bench-pil: build
	@$(ROSENV) $(VENV)/bin/python $(ROOT)/hil/bench/bench_pil.py

# The floors (issue 25): every branch of the files that decide (the policy, the checks, the
# regions, the HP command's check, the surfaces) taken by a test; 95 % over the whole core. The
# untaken ones and why they cannot be taken: src/core/README.md, "Branch coverage".
.PHONY: coverage-ha
VERIFY_TARGETS += coverage-ha
HA_COVERAGE_FLOORS := ha_policy.c ha_checks.c ha_region.c hp_command.c ha_surfaces.c
coverage-ha: deps
	@$(HA_DIR)/tools/coverage_ha.sh $(ROOT) $(foreach f,$(HA_COVERAGE_FLOORS),--floor $(f)=100) --total-floor 95

# The contracts WP proves (HA_WP: EVA and the compilers never see them): the policy's rules,
# the restart history, the saturation into S_u. verify/wp_negative_control.c must stay unproved.
WP_COMPONENTS += ha
VERIFY_TARGETS += prove-ha
WP_ha_SOURCES = $(addprefix $(HA_CORE_DIR)/,ha_policy.c ha_surfaces.c ha_core.c ha_num.c)
# 60 s a goal: the saturation's take Z3 5 s on an idle core, and other work shares the cores.
WP_ha_ARGS = -I $(HA_CORE_DIR) -I $(HA_FLOOR_DIR) -D HA_WP --driver $(HA_DIR)/verify/ha_wp.driver --timeout 60 \
  --fct ha_policy_decide,ha_policy_restart,ha_surfaces_saturate,$(HA_BY_CONTRACT),prune_restarts,request_restart,ha_elapsed_us \
  --negative $(HA_DIR)/verify/wp_negative_control.c \
  --negative-fct clamp_lets_nan_through,keyed_clamp_forgetting_nan,handback_forgetting_state,record_forgetting
WP_ha_DEPS = deps order-key-check

# The axioms WP takes about ha_order_key, checked for all 2^32 floats (about 20 s).
.PHONY: order-key-check
order-key-check:
	@mkdir -p $(HA_VERIFY_OUT)
	@gcc -O2 -std=c99 -Wall -Wextra -Werror -I$(HA_CORE_DIR) -I$(HA_FLOOR_DIR) $(HA_DIR)/verify/order_key_check.c -lm \
	  -o $(HA_VERIFY_OUT)/order_key_check
	@$(HA_VERIFY_OUT)/order_key_check
