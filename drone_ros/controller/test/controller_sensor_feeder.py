#!/usr/bin/env python3
"""The controller rostests' sensor node (stack_testing/sensor_feeder.py, which the latency
benchmark also drives in-process). Private parameters: rate_hz (default 50), stop_after_s."""
from stack_testing.sensor_feeder import main

if __name__ == "__main__":
    main()
