# drone_ros/arduino_link targets (included by the root Makefile).
#   make bench-link   the HA-HP link over ptys (SIL HA + the real `arduino` node): command
#                     latency p50/p99, frames per second, bytes per 100 Hz period vs the baud budget
BENCH_TARGETS += bench-link

.PHONY: bench-link
bench-link: build
	@$(ROSENV) $(VENV)/bin/python $(ROOT)/drone_ros/arduino_link/bench/bench_link.py $(WS)
