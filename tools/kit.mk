# The verify and fuzz kit (included by the root Makefile after every <folder>/make.mk): each
# component only declares its inputs, and gets targets of one pattern.
#
# Frama-C EVA (tools/eva.sh), target verify-<c>-eva (list it among verify-<c>'s prerequisites):
#   EVA_COMPONENTS += <c>
#   EVA_<c>_SOURCES  the analysed sources (the driver with main() included)
#   EVA_<c>_ARGS     eva.sh options: -I, -D, --case, --negative, --reach
#   EVA_<c>_DEPS     files to make first (generated headers)
#
# Frama-C WP (tools/wp.sh), target prove-<c> (list it in VERIFY_TARGETS):
#   WP_COMPONENTS += <c>
#   WP_<c>_SOURCES   the sources whose contracts are proved
#   WP_<c>_ARGS      wp.sh options: -I, -D, --fct, --driver, --negative, --negative-fct, --timeout
#   WP_<c>_DEPS      files to make first
#
# libFuzzer (tools/fuzz.sh), targets fuzz-<c> (FUZZ_SECONDS per harness, default 120) and
# fuzz-smoke-<c> (FUZZ_SMOKE_SECONDS per harness, default 10; CI), binaries in .build/fuzz/<c>/:
#   FUZZ_COMPONENTS += <c>
#   FUZZ_<c>_HARNESSES       harness names <h>
#   FUZZ_<c>_<h>_SOURCES     its sources (.c as C99, the rest C++17)
#   FUZZ_<c>_<h>_FLAGS       compile flags (-I, -D, -isystem)
#   FUZZ_<c>_<h>_SEEDS       the committed seed corpus folder
#   FUZZ_<c>_<h>_RUN_FLAGS   extra libFuzzer flags (-max_len=...)
#   FUZZ_<c>_DEPS            files to make first (generated headers)
FUZZ_SECONDS ?= 120
FUZZ_SMOKE_SECONDS ?= 10
FUZZ_OUT := $(ROOT)/.build/fuzz
EVA_OUT := $(ROOT)/.build/eva

define eva_component
.PHONY: verify-$(1)-eva
verify-$(1)-eva: $(EVA_$(1)_DEPS)
	@$(ROOT)/tools/eva.sh $(1) $(EVA_OUT)/$(1) $(EVA_$(1)_ARGS) -- $(EVA_$(1)_SOURCES)
endef

WP_OUT := $(ROOT)/.build/wp

define wp_component
.PHONY: prove-$(1)
prove-$(1): $(WP_$(1)_DEPS)
	@$(ROOT)/tools/wp.sh $(1) $(WP_OUT)/$(1) $(WP_$(1)_ARGS) -- $(WP_$(1)_SOURCES)
endef

define fuzz_harness
$(FUZZ_OUT)/$(1)/fuzz_$(2): $(FUZZ_$(1)_$(2)_SOURCES) $(FUZZ_$(1)_DEPS) $(ROOT)/tools/fuzz.sh
	@mkdir -p $(FUZZ_OUT)/$(1)
	@$(ROOT)/tools/fuzz.sh build $$@ $(FUZZ_$(1)_$(2)_FLAGS) -- $(FUZZ_$(1)_$(2)_SOURCES)
endef

define fuzz_component
$(foreach h,$(FUZZ_$(1)_HARNESSES),$(eval $(call fuzz_harness,$(1),$(h))))
.PHONY: fuzz-$(1) fuzz-smoke-$(1)
FUZZ_TARGETS += fuzz-$(1)
FUZZ_SMOKE_TARGETS += fuzz-smoke-$(1)
fuzz-$(1): $(addprefix $(FUZZ_OUT)/$(1)/fuzz_,$(FUZZ_$(1)_HARNESSES))
	@$(foreach h,$(FUZZ_$(1)_HARNESSES),$(ROOT)/tools/fuzz.sh run $(1) $(FUZZ_OUT)/$(1)/fuzz_$(h) $(FUZZ_SECONDS) $(FUZZ_$(1)_$(h)_SEEDS) $(FUZZ_$(1)_$(h)_RUN_FLAGS) &&) true
fuzz-smoke-$(1): $(addprefix $(FUZZ_OUT)/$(1)/fuzz_,$(FUZZ_$(1)_HARNESSES))
	@$(foreach h,$(FUZZ_$(1)_HARNESSES),$(ROOT)/tools/fuzz.sh run $(1) $(FUZZ_OUT)/$(1)/fuzz_$(h) $(FUZZ_SMOKE_SECONDS) $(FUZZ_$(1)_$(h)_SEEDS) $(FUZZ_$(1)_$(h)_RUN_FLAGS) &&) true
endef

$(foreach c,$(EVA_COMPONENTS),$(eval $(call eva_component,$(c))))
$(foreach c,$(WP_COMPONENTS),$(eval $(call wp_component,$(c))))
$(foreach c,$(FUZZ_COMPONENTS),$(eval $(call fuzz_component,$(c))))
