// libFuzzer harness over everything microhard_gs parses from the link: arbitrary bytes, in
// arbitrary chunks, with signing on or off, interleaved with clock ticks (mission timeouts,
// telemetry). Beyond the sanitizers it checks one property: every frame the vehicle sends back
// is a well-formed MAVLink frame.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "gs_core.h"
#include "gs_test_config.h"

using namespace microhard_gs;

namespace {

void check_frames_parse(const std::vector<std::vector<uint8_t>>& frames) {
  for (const auto& f : frames) {
    mavlink_status_t status{};
    mavlink_message_t buffer{};
    int ok = 0;
    for (uint8_t b : f) {
      mavlink_message_t msg;
      mavlink_status_t s;
      if (mavlink_frame_char_buffer(&buffer, &status, b, &msg, &s) == MAVLINK_FRAMING_OK) ++ok;
    }
    if (ok != 1) abort();  // the vehicle sent something a ground station cannot parse
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  const uint8_t mode = data[0];
  uint32_t lcg = data[1] * 2654435761u + 1u;
  data += 2;
  size -= 2;

  GsConfig c = test::gs_config(50.0);
  c.mission.item_timeout_ms = 50;
  c.mission.max_retries = 2;
  c.signing = (mode & 1) != 0;
  for (size_t i = 0; i < c.signing_key.size(); ++i) c.signing_key[i] = static_cast<uint8_t>(i + 1);
  ParamTable params;
  for (const ParamSpec& s : controller_param_specs()) params.add(s, 1.0);

  GsCore core(c, params);
  Clock now{1000, 1795000000ULL * 1000000ULL};
  core.tick(now);
  if (mode & 2) {
    core.set_home(GeoPoint{40.11, -88.22, 220.0});  // the HA's /home has come
  }
  if (mode & 4) {
    Telemetry t;
    t.lat_deg = 40.11;
    t.lon_deg = -88.22;
    t.alt_m = 260.0;
    t.ins_link_up = true;
    core.set_telemetry(t, now);
  }
  size_t off = 0;
  while (off < size) {
    lcg = lcg * 1664525u + 1013904223u;
    const size_t chunk = 1 + (lcg >> 24) % 300;
    const size_t n = chunk < size - off ? chunk : size - off;
    core.handle_bytes(data + off, n, now);
    off += n;
    now.mono_ms += (lcg >> 8) % 40;
    now.unix_us += ((lcg >> 8) % 40) * 1000;
    core.tick(now);
    if (mode & 8) {
      DecisionInfo d;
      d.controller = static_cast<uint8_t>((lcg >> 4) % 6);
      d.reasons_at_switch = lcg;
      d.altitude_agl_ft = (lcg >> 16) % 500;
      core.set_decision(d);
    }
    check_frames_parse(core.take_frames());
    core.take_way_plans();
    core.take_operator_requests();
    // The controller's answers: accepted, refused, or none at all (the timeout), sometimes
    // after the timeout already answered for it.
    for (const ParamSetRequest& r : core.take_param_set_requests()) {
      lcg = lcg * 1664525u + 1013904223u;
      if ((lcg >> 28) % 4 == 3) continue;
      ParamSetAnswer a;
      a.accepted = (lcg >> 28) % 4 == 0;
      a.value_in_force = r.value;
      a.reason = std::string((lcg >> 8) % 120, 'x');
      core.param_set_answered(r, a);
    }
    if ((lcg >> 20) % 8 == 0) {
      ParamSetRequest late;
      late.id = lcg;
      late.ros_name = controller_param_specs()[lcg % controller_param_specs().size()].ros_name;
      late.value = static_cast<double>(lcg % 1000);
      ParamSetAnswer a;
      a.accepted = true;
      a.value_in_force = late.value;
      core.param_set_answered(late, a);
    }
  }
  return 0;
}
