# hil targets, included by the root Makefile.
#   make bench-fdm   the flight-dynamics model's speed as a multiple of real time (hil/fdm)
HIL_DIR := $(ROOT)/hil

.PHONY: bench-fdm
BENCH_TARGETS += bench-fdm

bench-fdm: deps
	@$(VENV)/bin/python $(HIL_DIR)/bench/bench_fdm.py

#   make bench-hil   the whole HiL stack in lockstep: x real time at 100 Hz and 20 Hz, per-phase step cost,
#                    then a seeded campaign of 150 fault flights on Dask (BENCH_HIL_FLIGHTS=N for another size);
#                    after the HA as Cortex-M3 machine code in the loop (make bench-pil, issue 23, first):
#                    the PIL loop's speed and the firmware's instructions per period against the 16,800 budget
.PHONY: bench-hil
BENCH_TARGETS += bench-hil

bench-hil: build bench-pil
	@$(ROSENV) $(VENV)/bin/python $(HIL_DIR)/bench/bench_hil.py --aircraft $(AIRCRAFT)

#   make campaign ARGS="--flights 200 --seed 7"   a seeded fault campaign on Dask (hil/campaign.py)
.PHONY: campaign
campaign: build
	@$(ROSENV) $(VENV)/bin/python $(HIL_DIR)/campaign.py --aircraft $(AIRCRAFT) $(ARGS)

#   make bench-flight-overhead   what one lockstep flight costs besides its steps, phase by phase
#                                (hil/bench/bench_flight_overhead.py; BENCH_FLIGHT_RUNS=N flights)
.PHONY: bench-flight-overhead
BENCH_TARGETS += bench-flight-overhead

bench-flight-overhead: build
	@$(ROSENV) $(VENV)/bin/python $(HIL_DIR)/bench/bench_flight_overhead.py

#   make test-pil   the thesis's case study (240 s, crash at 100 s) as the rostest hil/test/case_study.test,
#                   with the HA as Cortex-M3 machine code in QEMU (ha:=qemu, the lockstep image of make
#                   pil-image). Minutes of QEMU: not in make test, which flies 60 s of it
#                   (hil/test/test_pil_flight.py) and the whole case study with the SIL.
.PHONY: test-pil
test-pil: build pil-image
	@$(ROSENV) rostest drone_ros case_study.test ha:=qemu
