# controller_DG808: `make bench-controller` prints the GNC step time on this host and the node's
# sensor-to-/servo_op latency at 20 and 100 Hz.
BENCH_TARGETS += bench-controller
.PHONY: bench-controller
bench-controller: build
	@$(ROSENV) $(WS)/devel/lib/drone_ros/bench_gnc
	@$(ROSENV) $(VENV)/bin/python $(ROOT)/drone_ros/controller/bench/bench_node_latency.py
	@echo "machine: $$(uname -srm), $$(nproc) cpu, $$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
