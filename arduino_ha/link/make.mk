# arduino_ha/link targets (included by the root Makefile).
#   make due-sketch-msgs   write the Due's generated message code into arduino_ha/src/link/generated/
#                          and the core's DecisionStatus numbers into arduino_ha/src/core/ (arduino-cli cannot run the generator; run this after any msg/ change,
#                          before compiling the sketch; CMake builds regenerate it on their own)
#   make fuzz-link         libFuzzer (clang, ASan + UBSan) on the device link, the host framer and
#                          the host's handling of announcements, logs and parameters,
#                          FUZZ_LINK_SECONDS each (default 120)
#   make fuzz-link-smoke   the same, 10 s each (CI)
#   make verify-link       the device link and its generated code: Frama-C EVA over any input
#                          bytes (verify/eva_link_main.c; fails on any alarm), and a cross-compile
#                          for the Due's Cortex-M3 (-Werror, -pedantic, -Wconversion) with flash,
#                          RAM and worst stack frame
LINK_DIR := $(ROOT)/arduino_ha/link
LINK_GEN := /usr/bin/python3 $(LINK_DIR)/gen/make_c99_msgs.py
LINK_SEARCH := drone_ros=$(ROOT)/msg std_msgs=/usr/share/std_msgs/msg \
  geometry_msgs=/usr/share/geometry_msgs/msg rosserial_msgs=$(LINK_DIR)/gen/rosserial_msgs/msg
LINK_TYPES = $(shell cat $(LINK_DIR)/gen/device_types.txt)
LINK_FUZZ_OUT ?= $(ROOT)/.build/link_fuzz
LINK_CLANG ?= clang-14
LINK_CLANGXX ?= clang++-14
LINK_FUZZ_FLAGS := -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
FUZZ_LINK_SECONDS ?= 120

VERIFY_TARGETS += verify-link
FUZZ_TARGETS += fuzz-link
FUZZ_SMOKE_TARGETS += fuzz-link-smoke

.PHONY: due-sketch-msgs fuzz-link fuzz-link-smoke fuzz-link-build verify-link

due-sketch-msgs:
	@$(LINK_GEN) $(ROOT)/arduino_ha/src/link/generated $(LINK_SEARCH) -- $(LINK_TYPES)
	@/usr/bin/python3 $(ROOT)/tools/gen_decision_status.py --c $(ROOT)/msg/DecisionStatus.msg \
	  $(ROOT)/arduino_ha/src/core/ha_decision_status.h
	@echo "due-sketch-msgs: wrote arduino_ha/src/link/generated/ and arduino_ha/src/core/ha_decision_status.h"

fuzz-link-build:
	@mkdir -p $(LINK_FUZZ_OUT)
	@$(LINK_GEN) $(LINK_FUZZ_OUT)/gen/generated $(LINK_SEARCH) -- $(LINK_TYPES)
	@$(LINK_CLANG) -std=c99 $(LINK_FUZZ_FLAGS) -I$(ROOT)/arduino_ha/src/link \
	  -DHA_LINK_GENERATED_HEADER=\"$(LINK_FUZZ_OUT)/gen/generated/ha_msgs.h\" \
	  $(LINK_DIR)/fuzz/fuzz_device_link.c $(ROOT)/arduino_ha/src/link/ha_link.c \
	  $(ROOT)/arduino_ha/src/link/ha_link_frame.c $(LINK_FUZZ_OUT)/gen/generated/ha_msgs.c \
	  $(ROOT)/arduino_ha/src/core/hp_command.c -o $(LINK_FUZZ_OUT)/fuzz_device_link
	@$(LINK_CLANGXX) -std=c++17 $(LINK_FUZZ_FLAGS) -I$(ROOT)/drone_ros/arduino_link/src \
	  $(ROOT)/drone_ros/arduino_link/fuzz/fuzz_host_framer.cpp \
	  $(ROOT)/drone_ros/arduino_link/src/rosserial_framer.cpp -o $(LINK_FUZZ_OUT)/fuzz_host_framer
	@$(LINK_CLANG) -std=c99 $(LINK_FUZZ_FLAGS) -I$(ROOT)/arduino_ha/src/link \
	  -DHA_LINK_GENERATED_HEADER=\"$(LINK_FUZZ_OUT)/gen/generated/ha_msgs.h\" \
	  -c $(LINK_FUZZ_OUT)/gen/generated/ha_msgs.c -o $(LINK_FUZZ_OUT)/ha_msgs_host.o
	@$(LINK_CLANGXX) -std=c++17 $(LINK_FUZZ_FLAGS) -I$(ROOT)/drone_ros/arduino_link/src \
	  -I$(ROOT)/arduino_ha/src/link -DHA_LINK_GENERATED_HEADER=\"$(LINK_FUZZ_OUT)/gen/generated/ha_msgs.h\" \
	  $(ROOT)/drone_ros/arduino_link/fuzz/fuzz_host_payloads.cpp \
	  $(ROOT)/drone_ros/arduino_link/src/device_payloads.cpp $(LINK_FUZZ_OUT)/ha_msgs_host.o \
	  -o $(LINK_FUZZ_OUT)/fuzz_host_payloads

# The seed corpus in the repo is copied, so findings land in .build and the repo stays clean.
define link_fuzz_run
	@rm -rf $(LINK_FUZZ_OUT)/corpus_$(1) && mkdir -p $(LINK_FUZZ_OUT)/corpus_$(1)
	@cp $(2)/*.bin $(LINK_FUZZ_OUT)/corpus_$(1)/
	@cd $(LINK_FUZZ_OUT) && ./fuzz_$(1) -max_total_time=$(3) -print_final_stats=1 \
	  corpus_$(1) 2>&1 | grep -E "stat::number_of_executed_units|ERROR|SUMMARY|Done" ; \
	  test $${PIPESTATUS[0]} -eq 0 && echo "fuzz_$(1): no crash in $(3) s"
endef

fuzz-link: fuzz-link-build
	$(call link_fuzz_run,device_link,$(LINK_DIR)/fuzz/corpus_device_link,$(FUZZ_LINK_SECONDS))
	$(call link_fuzz_run,host_framer,$(ROOT)/drone_ros/arduino_link/fuzz/corpus_host_framer,$(FUZZ_LINK_SECONDS))
	$(call link_fuzz_run,host_payloads,$(ROOT)/drone_ros/arduino_link/fuzz/corpus_host_payloads,$(FUZZ_LINK_SECONDS))

fuzz-link-smoke: fuzz-link-build
	$(call link_fuzz_run,device_link,$(LINK_DIR)/fuzz/corpus_device_link,10)
	$(call link_fuzz_run,host_framer,$(ROOT)/drone_ros/arduino_link/fuzz/corpus_host_framer,10)
	$(call link_fuzz_run,host_payloads,$(ROOT)/drone_ros/arduino_link/fuzz/corpus_host_payloads,10)

LINK_M3_OUT ?= $(ROOT)/.build/link_m3
LINK_M3_SOURCES := $(ROOT)/arduino_ha/src/link/ha_link.c $(ROOT)/arduino_ha/src/link/ha_link_frame.c \
  $(LINK_M3_OUT)/gen/generated/ha_msgs.c
verify-link:
	@mkdir -p $(LINK_M3_OUT)
	@$(LINK_GEN) $(LINK_M3_OUT)/gen/generated $(LINK_SEARCH) -- $(LINK_TYPES)
	@for f in $(LINK_M3_SOURCES); do \
	  arm-none-eabi-gcc -mcpu=cortex-m3 -mthumb -std=c99 -pedantic -Wall -Wextra -Werror -Wconversion \
	    -Os -fstack-usage -I$(ROOT)/arduino_ha/src/link \
	    -DHA_LINK_GENERATED_HEADER=\"$(LINK_M3_OUT)/gen/generated/ha_msgs.h\" \
	    -c $$f -o $(LINK_M3_OUT)/$$(basename $$f).o || exit 1; done
	@printf '#include "ha_link.h"\nunsigned long ha_link_ram = sizeof(HaLink);\n' > $(LINK_M3_OUT)/ram.c
	@arm-none-eabi-gcc -mcpu=cortex-m3 -mthumb -std=c99 -I$(ROOT)/arduino_ha/src/link \
	  -DHA_LINK_GENERATED_HEADER=\"$(LINK_M3_OUT)/gen/generated/ha_msgs.h\" -S $(LINK_M3_OUT)/ram.c -o $(LINK_M3_OUT)/ram.s
	@echo "link_flash: $$(arm-none-eabi-size -t $(LINK_M3_OUT)/*.c.o | tail -1 | awk '{print $$1}') bytes"
	@echo "link_ram_halink: $$(grep -A1 'ha_link_ram:' $(LINK_M3_OUT)/ram.s | grep -o '[0-9]\+$$') bytes"
	@echo "link_worst_stack_frame: $$(cat $(LINK_M3_OUT)/*.su | sort -t'	' -k2 -n | tail -1 | cut -f2) bytes"
	@echo "verify-link: cross-compiles for Cortex-M3 with no warning"
	@frama-c -machdep gcc_x86_32 -c11 -eva -eva-precision 1 -eva-no-show-progress -eva-print-callstacks \
	  -warn-special-float none -cpp-extra-args="-I$(ROOT)/arduino_ha/src/link -I$(ROOT)/arduino_ha/src/core \
	  -DHA_LINK_GENERATED_HEADER=\\\"$(LINK_M3_OUT)/gen/generated/ha_msgs.h\\\"" \
	  $(LINK_DIR)/verify/eva_link_main.c $(ROOT)/arduino_ha/src/link/ha_link.c \
	  $(ROOT)/arduino_ha/src/link/ha_link_frame.c $(LINK_M3_OUT)/gen/generated/ha_msgs.c \
	  $(ROOT)/arduino_ha/src/core/hp_command.c > $(LINK_M3_OUT)/eva.log 2>&1 \
	  || { tail -n 30 $(LINK_M3_OUT)/eva.log; exit 1; }
	@if grep -q "0 alarms generated" $(LINK_M3_OUT)/eva.log && ! grep -q "eva:alarm" $(LINK_M3_OUT)/eva.log; then \
	  echo "verify-link: EVA, 0 alarms (log: $(LINK_M3_OUT)/eva.log)"; \
	else grep -A8 "eva:alarm" $(LINK_M3_OUT)/eva.log | head -n 40; echo "verify-link: EVA alarms"; exit 1; fi
