#include "fake_board.h"

namespace {

FakeBoard* self(void* ctx) { return static_cast<FakeBoard*>(ctx); }

uint32_t micros(void* ctx) { return self(ctx)->now_us; }

void write_servos(void* ctx, const HaSurfaces* s) { self(ctx)->servo_writes.push_back(*s); }

void read_rc(void* ctx, HaRcInputs* rc) { *rc = self(ctx)->rc; }

int read_airspeed(void* ctx, float* v) {
  FakeBoard* b = self(ctx);
  // A live AMS5812's noise moves its last bits every read (the HA calls a reading repeated to
  // the bit for pitot_stuck_s a stuck sensor): a tiny deterministic dither, unless a story
  // freezes the sensor.
  b->airspeed_reads++;
  *v = b->airspeed_ftps + (b->pitot_noise && b->airspeed_ftps > 0.0f
                               ? 0.001f * static_cast<float>(b->airspeed_reads % 3u)
                               : 0.0f);
  return self(ctx)->airspeed_ok ? 1 : 0;
}

int read_battery(void* ctx, float* v) {
  *v = self(ctx)->battery_v;
  return self(ctx)->battery_ok ? 1 : 0;
}

void set_hp_reset(void* ctx, int asserted) {
  FakeBoard* b = self(ctx);
  if (asserted != 0 && !b->hp_reset) {
    b->hp_reset_assertions++;
  }
  b->hp_reset = asserted != 0;
}

void set_leds(void* ctx, uint8_t leds) { self(ctx)->leds = leds; }

void kick_watchdog(void* ctx) { self(ctx)->watchdog_kicks++; }

int read_retained(void* ctx, uint32_t words[HA_RETAINED_WORDS]) {
  for (uint32_t i = 0; i < HA_RETAINED_WORDS; ++i) words[i] = self(ctx)->retained[i];
  return 1;
}

void write_retained(void* ctx, const uint32_t words[HA_RETAINED_WORDS]) {
  for (uint32_t i = 0; i < HA_RETAINED_WORDS; ++i) self(ctx)->retained[i] = words[i];
  self(ctx)->retained_writes++;
}

size_t take(std::deque<uint8_t>* rx, uint32_t* reads, uint8_t* bytes, size_t max_len) {
  size_t n = 0;
  ++*reads;
  while (n < max_len && !rx->empty()) {
    bytes[n++] = rx->front();
    rx->pop_front();
  }
  return n;
}

size_t hp_read(void* ctx, uint8_t* bytes, size_t max_len) {
  return take(&self(ctx)->hp_rx, &self(ctx)->port_reads, bytes, max_len);
}

void hp_write(void* ctx, const uint8_t* bytes, size_t len) {
  self(ctx)->hp_tx.insert(self(ctx)->hp_tx.end(), bytes, bytes + len);
}

size_t ins_read(void* ctx, uint8_t* bytes, size_t max_len) {
  return take(&self(ctx)->ins_rx, &self(ctx)->port_reads, bytes, max_len);
}

}  // namespace

FakeBoard::FakeBoard() {
  iface.ctx = this;
  iface.micros = micros;
  iface.write_servos = write_servos;
  iface.read_rc = read_rc;
  iface.read_airspeed_ftps = read_airspeed;
  iface.read_battery_v = read_battery;
  iface.set_hp_reset = set_hp_reset;
  iface.set_leds = set_leds;
  iface.kick_watchdog = kick_watchdog;
  iface.read_retained = read_retained;
  iface.write_retained = write_retained;
  iface.hp_link.read = hp_read;
  iface.hp_link.write = hp_write;
  iface.ins.read = ins_read;
  iface.ins.write = nullptr;  // the HA never writes to its VN-200
  CenterSticks();
}

void FakeBoard::CenterSticks() {
  rc.pulse_us[HA_RC_THROTTLE] = 1000;
  rc.pulse_us[HA_RC_ELEVATOR] = 1500;
  rc.pulse_us[HA_RC_AILERON] = 1500;
  rc.pulse_us[HA_RC_RUDDER] = 1500;
  rc.pulse_us[HA_RC_PIC] = 1000;
  rc.valid = 1;
}

void FakeBoard::SetPilotInCommand(bool pilot) { rc.pulse_us[HA_RC_PIC] = pilot ? 2000 : 1000; }
