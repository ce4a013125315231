# vn200_driver targets (included by the root Makefile).
#   make fuzz-vn200        libFuzzer (ASan+UBSan) on the framer, binary and ASCII decoders and
#                          command builders, VN200_FUZZ_S seconds each (default 120)
#   make fuzz-smoke-vn200  the same, 5 s each (~20 s)
#   make bench-vn200       parse throughput and CPU share at the sensor's maximum output
#   make verify-vn200      Frama-C EVA over vn200_driver/core (no alarms allowed), then the core
#                          cross-compiled for the Due's Cortex-M3 with -Werror (flash figures)
# Tools (clang-14, libclang-rt-14-dev, frama-c-base) come from vn200_driver/apt-packages.txt.
VN200_DIR := $(ROOT)/vn200_driver
VN200_OUT := $(ROOT)/.build/vn200
VN200_CORE_SRC := $(wildcard $(VN200_DIR)/core/*.c)
VN200_CORE_HDR := $(wildcard $(VN200_DIR)/core/*.h)
VN200_FUZZERS := framer binary ascii command
VN200_FUZZ_S ?= 120
VN200_CLANG ?= $(firstword $(shell command -v clang-14 clang 2>/dev/null))

FUZZ_TARGETS += fuzz-vn200
FUZZ_SMOKE_TARGETS += fuzz-smoke-vn200
BENCH_TARGETS += bench-vn200
VERIFY_TARGETS += verify-vn200

.PHONY: fuzz-vn200 fuzz-smoke-vn200 bench-vn200 verify-vn200 verify-vn200-eva verify-vn200-m3

$(VN200_OUT)/fuzz_%: $(VN200_DIR)/fuzz/fuzz_%.c $(VN200_CORE_SRC) $(VN200_CORE_HDR)
	@mkdir -p $(@D)
	@test -n "$(VN200_CLANG)" || { echo "clang not found: make deps"; exit 2; }
	@$(VN200_CLANG) -std=c99 -g -O1 -Wall -Wextra -Werror -fsanitize=fuzzer,address,undefined \
	  -fno-sanitize-recover=all -I$(VN200_DIR)/core $< $(VN200_CORE_SRC) -o $@

# Runs each harness for $(1) seconds on a working corpus seeded from fuzz/corpus/<name>
# (new inputs go to .build, the committed seeds stay as they are).
define vn200_run_fuzzers
	@for f in $(VN200_FUZZERS); do \
	  mkdir -p $(VN200_OUT)/corpus_$$f $(VN200_OUT)/artifacts_$$f; \
	  echo "fuzz-vn200: $$f for $(1) s"; \
	  $(VN200_OUT)/fuzz_$$f -max_total_time=$(1) -max_len=2048 -print_final_stats=1 \
	    -artifact_prefix=$(VN200_OUT)/artifacts_$$f/ \
	    $(VN200_OUT)/corpus_$$f $(VN200_DIR)/fuzz/corpus/$$f 2> $(VN200_OUT)/fuzz_$$f.log \
	    || { tail -n 40 $(VN200_OUT)/fuzz_$$f.log; echo "fuzz-vn200: $$f FAILED"; exit 1; }; \
	  grep -E "stat::number_of_executed_units|stat::average_exec_per_sec" $(VN200_OUT)/fuzz_$$f.log | sed "s/^/  /"; \
	done
endef

fuzz-vn200: $(addprefix $(VN200_OUT)/fuzz_,$(VN200_FUZZERS))
	$(call vn200_run_fuzzers,$(VN200_FUZZ_S))

fuzz-smoke-vn200: $(addprefix $(VN200_OUT)/fuzz_,$(VN200_FUZZERS))
	$(call vn200_run_fuzzers,5)

$(VN200_OUT)/vn200_bench: $(VN200_DIR)/bench/vn200_bench.cpp $(VN200_DIR)/src/output_config.cpp \
    $(VN200_DIR)/test/vn_packet_builder.h $(VN200_CORE_SRC) $(VN200_CORE_HDR)
	@mkdir -p $(@D)/bench_obj
	@cd $(@D)/bench_obj && gcc -std=c99 -O2 -Wall -Wextra -Werror -c $(VN200_CORE_SRC)
	@g++ -std=c++17 -O2 -Wall -Wextra -Werror -I$(VN200_DIR)/core -I$(VN200_DIR)/src \
	  -I$(VN200_DIR)/test $(VN200_DIR)/bench/vn200_bench.cpp $(VN200_DIR)/src/output_config.cpp \
	  $(@D)/bench_obj/*.o -o $@

bench-vn200: $(VN200_OUT)/vn200_bench
	@$(VN200_OUT)/vn200_bench

verify-vn200: verify-vn200-eva verify-vn200-m3

verify-vn200-eva:
	@$(VN200_DIR)/verify/run_eva.sh $(VN200_OUT)/eva

# The Due firmware links this core: it must build for the Cortex-M3 without a warning.
verify-vn200-m3:
	@mkdir -p $(VN200_OUT)/m3
	@cd $(VN200_OUT)/m3 && arm-none-eabi-gcc -mcpu=cortex-m3 -mthumb -std=c99 -Os -ffreestanding \
	  -Wall -Wextra -Werror -pedantic -Wconversion -Wshadow -c $(VN200_CORE_SRC)
	@arm-none-eabi-size -t $(VN200_OUT)/m3/*.o | tail -n 1 | \
	  awk '{ print "verify-vn200: Cortex-M3 core " $$1 " bytes flash, " $$2 + $$3 " bytes static RAM" }'
