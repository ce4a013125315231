# drone_ros/report targets, included by the root Makefile.
#   make bench-record   size per hour of a flight log (launch/record.launch's topics at their rates)
REPORT_DIR := $(ROOT)/drone_ros/report

.PHONY: bench-record
BENCH_TARGETS += bench-record

bench-record: build
	@$(ROSENV) $(VENV)/bin/python $(REPORT_DIR)/bench/bench_record.py
