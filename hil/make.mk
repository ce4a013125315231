# hil targets, included by the root Makefile.
#   make bench-fdm   the flight-dynamics model's speed as a multiple of real time (hil/fdm)
HIL_DIR := $(ROOT)/hil

.PHONY: bench-fdm
BENCH_TARGETS += bench-fdm

bench-fdm: deps
	@$(VENV)/bin/python $(HIL_DIR)/bench/bench_fdm.py
