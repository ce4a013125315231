"""The stack's shared Python tools: the aircraft YAML checker and the generators that read it
(gen_limits_ranges, gen_aircraft_config, generated_file), airframe.yaml's body as the gain design
and the simulator both read it (airframe_body), the package's data folder (paths) and the
benchmarks' machine line (bench_machine). Imported by the HiL, the gain design and the tests; the
build runs the generators as `python3 -m stack_tools.<name>` through catkin's env.sh."""
