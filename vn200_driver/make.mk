# vn200_driver targets (included by the root Makefile).
#   make fuzz-vn200        libFuzzer (ASan+UBSan) on the framer, binary and ASCII decoders and
#                          command builders, FUZZ_SECONDS each (tools/kit.mk)
#   make fuzz-smoke-vn200  the same, FUZZ_SMOKE_SECONDS each (CI)
#   make bench-vn200       parse throughput and CPU share at the sensor's maximum output
#   make verify-vn200      Frama-C EVA over common/vn200 (no alarms allowed), then the core
#                          cross-compiled for the Due's Cortex-M3 with -Werror (flash figures)
# Tools (clang-14, libclang-rt-14-dev, frama-c-base) come from vn200_driver/apt-packages.txt.
VN200_DIR := $(ROOT)/vn200_driver
VN200_OUT := $(ROOT)/.build/vn200
# The protocol core is the ground floor's (common/vn200); its checks stay with the driver.
VN200_CORE_DIR := $(ROOT)/common/vn200
VN200_CORE_SRC := $(wildcard $(VN200_CORE_DIR)/*.c)
VN200_CORE_HDR := $(wildcard $(VN200_CORE_DIR)/*.h)
VN200_FUZZERS := framer binary ascii command

BENCH_TARGETS += bench-vn200
VERIFY_TARGETS += verify-vn200

.PHONY: bench-vn200 verify-vn200 verify-vn200-m3

# Fuzzing: one harness per parser and the command builders (tools/kit.mk).
FUZZ_COMPONENTS += vn200
FUZZ_vn200_HARNESSES := $(VN200_FUZZERS)
$(foreach f,$(VN200_FUZZERS),$(eval FUZZ_vn200_$(f)_SOURCES := $(VN200_DIR)/fuzz/fuzz_$(f).c $(VN200_CORE_SRC)))
$(foreach f,$(VN200_FUZZERS),$(eval FUZZ_vn200_$(f)_FLAGS := -I$(VN200_CORE_DIR)))
$(foreach f,$(VN200_FUZZERS),$(eval FUZZ_vn200_$(f)_SEEDS := $(VN200_DIR)/fuzz/corpus/$(f)))
$(foreach f,$(VN200_FUZZERS),$(eval FUZZ_vn200_$(f)_RUN_FLAGS := -max_len=2048))
FUZZ_vn200_DEPS := $(VN200_CORE_HDR)

$(VN200_OUT)/vn200_bench: $(VN200_DIR)/bench/vn200_bench.cpp $(VN200_DIR)/src/output_config.cpp \
    $(VN200_DIR)/test/vn_packet_builder.h $(VN200_CORE_SRC) $(VN200_CORE_HDR)
	@mkdir -p $(@D)/bench_obj
	@cd $(@D)/bench_obj && gcc -std=c99 -O2 -Wall -Wextra -Werror -c $(VN200_CORE_SRC)
	@g++ -std=c++17 -O2 -Wall -Wextra -Werror -I$(VN200_CORE_DIR) -I$(VN200_DIR)/src \
	  -I$(VN200_DIR)/test $(VN200_DIR)/bench/vn200_bench.cpp $(VN200_DIR)/src/output_config.cpp \
	  $(@D)/bench_obj/*.o -o $@

bench-vn200: $(VN200_OUT)/vn200_bench
	@$(VN200_OUT)/vn200_bench

verify-vn200: verify-vn200-eva verify-vn200-m3

# One analysis per part: the command builders, the binary decoder, the ASCII decoder (unknown
# bytes, lengths and arguments), the framer (10 reads of up to 16 unknown bytes reach every
# state while keeping the analysis to minutes). The binary decoder runs with
# -warn-special-float none: it does no float arithmetic and rejects NaN/inf on the bit pattern
# before any float exists (unit-tested), but EVA cannot see through the memcpy from bits to float.
EVA_COMPONENTS += vn200
EVA_vn200_SOURCES = $(VN200_DIR)/verify/eva_main.c $(sort $(VN200_CORE_SRC))
EVA_vn200_ARGS = -I $(VN200_CORE_DIR) \
  --case main_commands:main_commands:3:non-finite \
  --case main_binary:main_binary:3:none \
  --case main_ascii:main_ascii:3:non-finite \
  --case main_framer:main_framer:2:non-finite:-DREAD_MAX=16u,-DREADS=10

# The Due firmware links this core: it must build for the Cortex-M3 without a warning.
verify-vn200-m3:
	@mkdir -p $(VN200_OUT)/m3
	@cd $(VN200_OUT)/m3 && arm-none-eabi-gcc -mcpu=cortex-m3 -mthumb -std=c99 -Os -ffreestanding \
	  -Wall -Wextra -Werror -pedantic -Wconversion -Wshadow -c $(VN200_CORE_SRC)
	@arm-none-eabi-size -t $(VN200_OUT)/m3/*.o | tail -n 1 | \
	  awk '{ print "verify-vn200: Cortex-M3 core " $$1 " bytes flash, " $$2 + $$3 " bytes static RAM" }'
