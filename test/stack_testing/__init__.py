"""Test helpers more than one folder's tests or benchmarks use: the wire tap between two ptys
(wire_tap), the ground station harness and MAVProxy as a client (gs_harness, mavproxy_gcs), the
fault tests' flights (fault_flight), the HA in the loop over QEMU (ha_in_loop), the
controller's sensor feeder (sensor_feeder), the Due's host programs built (due_host), messages
kept from a subscription (kept_messages), a process ended (processes), a private rosmaster
(ros_master), a rostest's wait (story_wait) and a tlog read back (tlog_file). A package of
setup.py like the code they test, so a test imports them by name from any folder; they read the
source tree (stack_tools.paths.ROOT)."""
