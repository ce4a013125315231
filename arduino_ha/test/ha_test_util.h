// Scripted timelines for the HA core: a fake board with a simulated clock, an HP that sends
// commands on demand, and a tiny point-mass aircraft for closed-loop tests.
#ifndef ARDUINO_HA_TEST_HA_TEST_UTIL_H
#define ARDUINO_HA_TEST_HA_TEST_UTIL_H

#include <cstdint>

#include "fake_board.h"
#include "ha_aircraft.h"
#include "ha_app.h"
#include "ha_core.h"

// A valid HP command (CRC filled in) for the given surfaces.
HaHpCommand MakeCommand(uint32_t seq, float throttle, float elevator_deg, float aileron_deg,
                        float rudder_deg);
void SealCommand(HaHpCommand* cmd);  // recomputes the CRC after a field was changed

bool SurfacesFinite(const HaSurfaces& s);
// Inside the configured actuator box (which is what S_u describes).
bool SurfacesInside(const HaAircraftConfig& cfg, const HaSurfaces& s);

// Level flight at this altitude and airspeed, on the safety circle's edge, a fresh INS state at
// now_us: what the INS adapter would have written.
void WriteCruiseState(const HaAircraftConfig& cfg, HaInputs* in, uint32_t now_us,
                      float altitude_agl_ft, float airspeed_ftps);

class Timeline {
 public:
  explicit Timeline(const HaAircraftConfig& cfg = ha_aircraft_config);
  Timeline(const Timeline&) = delete;
  Timeline& operator=(const Timeline&) = delete;

  // Level flight at this altitude and airspeed, on the circle's edge, fresh INS state.
  void Cruise(float altitude_agl_ft = 200.0f, float airspeed_ftps = 60.0f);
  // Parked: on the ground, no airspeed.
  void Parked();

  // One period: the command (if any) arrives mid-period, then the HA runs at the period's end.
  const HaOutputs& Step();
  const HaOutputs& StepWith(const HaHpCommand& cmd);
  // A fresh, valid command with the next sequence number and these surfaces.
  const HaOutputs& StepWithGood(float aileron_deg = 2.0f, float elevator_deg = -1.0f,
                                float rudder_deg = 0.5f, float throttle = 0.45f);
  // Valid commands until the HP is in control and the handover slew is over; returns the number
  // of periods until the HP was in control.
  int ReachHp(int max_periods = 1000);
  void Operator(uint8_t command);

  const HaOutputs& out() const { return app.outputs; }
  uint8_t controller() const { return app.outputs.controller; }
  HaSurfaces servos() const { return board.servo_writes.back(); }
  uint32_t NextSeq() { return ++seq; }

  HaAircraftConfig cfg;
  FakeBoard board;
  HaApp app;
  uint32_t seq = 1000;
  uint32_t operator_id = 0;
  bool refresh_state = true;  // false: the INS state stops arriving
};

// Point mass with first-order rate responses: enough to show the safety controller flies a
// circle, holds speed above stall and altitude below the ceiling.
struct PointMassAircraft {
  float north_ft = 0, east_ft = 0, heading_deg = 0;
  float roll_deg = 0, pitch_deg = 0, p_deg_s = 0, q_deg_s = 0, r_deg_s = 0;
  float airspeed_ftps = 60, altitude_ft = 200;
  float wind_north_ftps = 0, wind_east_ftps = 0;  // the air's velocity over the ground
  void Step(const HaSurfaces& u, float dt_s);
  void WriteTo(HaInputs* in, uint32_t now_us) const;
  float DistanceFt() const;
};

// The HA's core alone flying the point mass, period by period, on a simulated clock: the
// aircraft's state into the inputs, the core's surfaces back into the aircraft.
struct HaAloneFlight {
  explicit HaAloneFlight(uint32_t start_us = 555000u,
                         const HaAircraftConfig& config = ha_aircraft_config);
  // One period with the pitot reading the aircraft's airspeed ...
  const HaOutputs& Step();
  // ... or this (what ha_app hands over: -1 for a failed read).
  const HaOutputs& StepWithPitot(float airspeed_ftps);
  float PeriodS() const { return cfg.period_us * 1e-6f; }
  // On the HA's circle, heading east (its tangent at the north point), level.
  void StartOnTheCircle(float altitude_ft, float airspeed_ftps);

  const HaAircraftConfig& cfg;
  HaCore core;
  HaInputs in{};
  HaOutputs out{};
  PointMassAircraft ac;
  uint32_t now_us;
};

#endif  // ARDUINO_HA_TEST_HA_TEST_UTIL_H
