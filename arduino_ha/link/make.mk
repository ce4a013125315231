# arduino_ha/link targets (included by the root Makefile).
#   make due-sketch-msgs   write the core's DecisionStatus numbers and reasons and its
#                          OperatorCommand numbers into arduino_ha/src/generated/ (arduino-cli cannot run the generator; run this after any msg/ change,
#                          before compiling the sketch; CMake builds regenerate it on their own)
#   make fuzz-link         libFuzzer (clang, ASan + UBSan) on the device link, the host framer and
#                          the host's handling of announcements, logs and parameters,
#                          FUZZ_SECONDS each (tools/kit.mk)
#   make fuzz-smoke-link   the same, FUZZ_SMOKE_SECONDS each (CI)
#   make verify-link       the device link and its generated code: Frama-C EVA over any input
#                          bytes (verify/eva_link_main.c; fails on any alarm), and a cross-compile
#                          for the Due's Cortex-M3 (-Werror, -pedantic, -Wconversion) with flash,
#                          RAM and worst stack frame
LINK_DIR := $(ROOT)/arduino_ha/link
# The wire format both ends speak is the ground floor's: its generator and ha_link_msgs.h.
LINK_MSGS_DIR := $(ROOT)/common/link
LINK_GEN := $(PYTHON) $(LINK_MSGS_DIR)/gen/make_c99_msgs.py
LINK_SEARCH := drone_ros=$(ROOT)/msg std_msgs=/usr/share/std_msgs/msg \
  geometry_msgs=/usr/share/geometry_msgs/msg rosserial_msgs=$(LINK_MSGS_DIR)/gen/rosserial_msgs/msg
LINK_TYPES = $(shell cat $(LINK_MSGS_DIR)/gen/device_types.txt)
LINK_GEN_DIR := $(ROOT)/.build/link/generated

VERIFY_TARGETS += verify-link
.PHONY: due-sketch-msgs verify-link

due-sketch-msgs:
	@$(PYTHON) $(ROOT)/tools/gen_decision_status.py --c $(ROOT)/msg/DecisionStatus.msg \
	  $(ROOT)/arduino_ha/src/generated/ha_decision_status.h
	@$(PYTHON) $(ROOT)/tools/gen_decision_status.py --c-operator $(ROOT)/msg/OperatorCommand.msg \
	  $(ROOT)/arduino_ha/src/generated/ha_operator_command.h
	@echo "due-sketch-msgs: wrote arduino_ha/src/generated/ha_decision_status.h and ha_operator_command.h"

# The message code host builds use, generated into .build (CMake builds make their own).
$(LINK_GEN_DIR)/ha_msgs.c: $(LINK_MSGS_DIR)/gen/make_c99_msgs.py $(LINK_MSGS_DIR)/gen/device_types.txt $(wildcard $(ROOT)/msg/*.msg)
	@$(LINK_GEN) $(LINK_GEN_DIR) $(LINK_SEARCH) -- $(LINK_TYPES)
LINK_GEN_HEADER := -I$(LINK_MSGS_DIR) -DHA_LINK_GENERATED_HEADER=\"$(LINK_GEN_DIR)/ha_msgs.h\"

# Fuzzing (tools/kit.mk): the device link, the host framer and the host's handling of
# announcements, logs and parameters.
FUZZ_COMPONENTS += link
FUZZ_link_HARNESSES := device_link host_framer host_payloads
FUZZ_link_DEPS := $(LINK_GEN_DIR)/ha_msgs.c
FUZZ_link_device_link_SOURCES := $(LINK_DIR)/fuzz/fuzz_device_link.c $(ROOT)/arduino_ha/src/link/ha_link.c \
  $(ROOT)/arduino_ha/src/link/ha_link_frame.c $(LINK_GEN_DIR)/ha_msgs.c $(ROOT)/common/src/hp_command.c
FUZZ_link_device_link_FLAGS := -I$(ROOT)/arduino_ha/src/link -I$(ROOT)/common/src $(LINK_GEN_HEADER)
FUZZ_link_device_link_SEEDS := $(LINK_DIR)/fuzz/corpus_device_link
FUZZ_link_host_framer_SOURCES := $(ROOT)/drone_ros/arduino_link/fuzz/fuzz_host_framer.cpp \
  $(ROOT)/drone_ros/arduino_link/src/rosserial_framer.cpp
FUZZ_link_host_framer_FLAGS := -I$(ROOT)/drone_ros/arduino_link/src
FUZZ_link_host_framer_SEEDS := $(ROOT)/drone_ros/arduino_link/fuzz/corpus_host_framer
FUZZ_link_host_payloads_SOURCES := $(ROOT)/drone_ros/arduino_link/fuzz/fuzz_host_payloads.cpp \
  $(ROOT)/drone_ros/arduino_link/src/device_payloads.cpp $(LINK_GEN_DIR)/ha_msgs.c
FUZZ_link_host_payloads_FLAGS := -I$(ROOT)/drone_ros/arduino_link/src $(LINK_GEN_HEADER)
FUZZ_link_host_payloads_SEEDS := $(ROOT)/drone_ros/arduino_link/fuzz/corpus_host_payloads

verify-link: verify-link-m3 verify-link-eva

# EVA over any input bytes (verify/eva_link_main.c), tools/kit.mk.
EVA_COMPONENTS += link
EVA_link_SOURCES = $(LINK_DIR)/verify/eva_link_main.c $(ROOT)/arduino_ha/src/link/ha_link.c \
  $(ROOT)/arduino_ha/src/link/ha_link_frame.c $(ROOT)/arduino_ha/src/link/ha_link_report.c \
  $(LINK_GEN_DIR)/ha_msgs.c $(ROOT)/common/src/hp_command.c \
  $(ROOT)/arduino_ha/src/core/ha_surfaces.c $(ROOT)/arduino_ha/src/core/ha_num.c \
  $(ROOT)/arduino_ha/src/core/ha_aircraft.c
EVA_link_ARGS = -I $(ROOT)/arduino_ha/src/link -I $(ROOT)/arduino_ha/src/core -I $(ROOT)/common/src -I $(LINK_MSGS_DIR) \
  -D 'HA_LINK_GENERATED_HEADER="$(LINK_GEN_DIR)/ha_msgs.h"' --case any-bytes:main:1:none \
  --use-spec $(HA_BY_CONTRACT)
EVA_link_DEPS = $(LINK_GEN_DIR)/ha_msgs.c

LINK_M3_OUT ?= $(ROOT)/.build/link_m3
LINK_M3_SOURCES := $(ROOT)/arduino_ha/src/link/ha_link.c $(ROOT)/arduino_ha/src/link/ha_link_frame.c \
  $(ROOT)/arduino_ha/src/link/ha_link_report.c $(LINK_GEN_DIR)/ha_msgs.c
.PHONY: verify-link-m3
verify-link-m3: $(LINK_GEN_DIR)/ha_msgs.c
	@mkdir -p $(LINK_M3_OUT)
	@for f in $(LINK_M3_SOURCES); do \
	  arm-none-eabi-gcc -mcpu=cortex-m3 -mthumb -std=c99 -pedantic -Wall -Wextra -Werror -Wconversion \
	    -Os -fstack-usage -I$(ROOT)/arduino_ha/src/link -I$(ROOT)/common/src $(LINK_GEN_HEADER) \
	    -c $$f -o $(LINK_M3_OUT)/$$(basename $$f).o || exit 1; done
	@printf '#include "ha_link.h"\nunsigned long ha_link_ram = sizeof(HaLink);\n' > $(LINK_M3_OUT)/ram.c
	@arm-none-eabi-gcc -mcpu=cortex-m3 -mthumb -std=c99 -I$(ROOT)/arduino_ha/src/link -I$(ROOT)/common/src \
	  $(LINK_GEN_HEADER) -S $(LINK_M3_OUT)/ram.c -o $(LINK_M3_OUT)/ram.s
	@echo "link_flash: $$(arm-none-eabi-size -t $(LINK_M3_OUT)/*.c.o | tail -1 | awk '{print $$1}') bytes"
	@echo "link_ram_halink: $$(grep -A1 'ha_link_ram:' $(LINK_M3_OUT)/ram.s | grep -o '[0-9]\+$$') bytes"
	@echo "link_worst_stack_frame: $$(cat $(LINK_M3_OUT)/*.su | sort -t'	' -k2 -n | tail -1 | cut -f2) bytes"
	@echo "verify-link: cross-compiles for Cortex-M3 with no warning"
