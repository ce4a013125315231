#include "due_rc_capture.h"

#include <Arduino.h>

#include "due_config.h"

namespace {

struct RcChannelCapture {
  volatile uint32_t rise_us;
  volatile uint32_t width_us;
  volatile uint32_t fall_us;
  volatile uint8_t seen;
};

RcChannelCapture g_channels[HA_RC_CHANNELS];
volatile uint32_t g_glitches = 0u;

const uint32_t kRcPins[HA_RC_CHANNELS] = {DUE_PIN_RC_THROTTLE, DUE_PIN_RC_ELEVATOR,
                                          DUE_PIN_RC_AILERON, DUE_PIN_RC_RUDDER, DUE_PIN_RC_PIC};

/* Runs in interrupt context: a few loads and stores, no calls that could block. */
void on_edge(uint32_t channel) {
  const uint32_t now_us = micros();
  RcChannelCapture &c = g_channels[channel];
  if (digitalRead(kRcPins[channel]) != 0) {
    c.rise_us = now_us;
    return;
  }
  const uint32_t width_us = now_us - c.rise_us;
  if (width_us < DUE_RC_PULSE_MIN_PLAUSIBLE_US || width_us > DUE_RC_PULSE_MAX_PLAUSIBLE_US) {
    g_glitches = g_glitches + 1u;
    return;
  }
  c.width_us = width_us;
  c.fall_us = now_us;
  c.seen = 1u;
}

void on_throttle_edge() { on_edge(HA_RC_THROTTLE); }
void on_elevator_edge() { on_edge(HA_RC_ELEVATOR); }
void on_aileron_edge() { on_edge(HA_RC_AILERON); }
void on_rudder_edge() { on_edge(HA_RC_RUDDER); }
void on_pic_edge() { on_edge(HA_RC_PIC); }

void (*const kHandlers[HA_RC_CHANNELS])(void) = {on_throttle_edge, on_elevator_edge,
                                                 on_aileron_edge, on_rudder_edge, on_pic_edge};

}  // namespace

void due_rc_begin(void) {
  for (uint32_t ch = 0u; ch < static_cast<uint32_t>(HA_RC_CHANNELS); ++ch) {
    pinMode(kRcPins[ch], INPUT);
    attachInterrupt(digitalPinToInterrupt(kRcPins[ch]), kHandlers[ch], CHANGE);
  }
}

void due_rc_read(HaRcInputs *rc) {
  uint8_t all_fresh = 1u;
  noInterrupts();
  /* Sampled with interrupts off, so no edge can land between this time and the copies below
   * (an edge newer than now_us would make the age wrap and the channel look lost). */
  const uint32_t now_us = micros();
  for (uint32_t ch = 0u; ch < static_cast<uint32_t>(HA_RC_CHANNELS); ++ch) {
    const RcChannelCapture &c = g_channels[ch];
    rc->pulse_us[ch] = static_cast<uint16_t>(c.width_us);
    if (c.seen == 0u || now_us - c.fall_us > DUE_RC_TIMEOUT_US) {
      all_fresh = 0u;
    }
  }
  interrupts();
  rc->valid = all_fresh;
}

uint32_t due_rc_glitches(void) { return g_glitches; }
