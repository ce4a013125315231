/* Controls and records of fake_arduino.cpp, the host implementation of the shim headers used by
 * board_host_test.cpp to run the real board layer and sketch on the host. Test-only. */
#ifndef HA_FAKE_ARDUINO_H
#define HA_FAKE_ARDUINO_H

#include <stddef.h>
#include <stdint.h>

namespace fake {

const uint32_t kPins = 70u;

/* The sketch's serial ports, as tx_sink names them. */
enum Port { kSerial = 0, kSerial1 = 1, kSerialUsb = 2 };

struct ServoRecord {
  int pin = -1;
  int min_us = 0;
  int max_us = 0;
  int pulse_us = 0;
  uint32_t writes = 0u;
};

struct State {
  uint32_t now_us = 0u;
  int pin_level[kPins] = {};
  int pin_mode[kPins] = {};
  int written[kPins] = {};
  void (*isr[kPins])(void) = {};
  uint32_t watchdog_kicks = 0u;
  uint32_t watchdog_timeout_ms = 0u;
  int irq_disabled = 0;
  uint32_t adc_counts = 0u;
  int adc_bits = 10;
  ServoRecord servos[8];
  uint32_t servo_count = 0u;
  uint8_t i2c_reply[8] = {};
  uint8_t i2c_reply_len = 0u;
  uint8_t i2c_pos = 0u;
  uint8_t i2c_last_address = 0u;
  uint32_t i2c_clock_hz = 0u;
  /* Bytes waiting on Serial (the programming port: the HP link), read from serial0_pos on. */
  uint8_t serial0_rx[4096] = {};
  size_t serial0_len = 0u;
  size_t serial0_pos = 0u;
  /* Bytes waiting on Serial1 (the VN-200's port), read from serial1_pos on. */
  uint8_t serial1_rx[4096] = {};
  size_t serial1_len = 0u;
  size_t serial1_pos = 0u;
  /* The native USB port (SerialUSB): bytes the host sent, read from usb_pos on; what the sketch
   * wrote while the host had the port open (usb_open, the CDC line state), else dropped as the
   * SAM core's Serial_::write drops them. */
  uint8_t usb_rx[4096] = {};
  size_t usb_len = 0u;
  size_t usb_pos = 0u;
  int usb_open = 1;
  uint8_t usb_tx[65536] = {};
  size_t usb_tx_len = 0u;
  /* Set, it takes what the sketch writes on any port and returns how much it took (a program that
   * puts the ports on ptys: due_hil_on_ptys.cpp); unset, Serial's bytes vanish and SerialUSB's go
   * to usb_tx. */
  size_t (*tx_sink)(Port port, const uint8_t *bytes, size_t len) = nullptr;
};

extern State state;

void reset();
/* Drives an input pin and runs its interrupt handler (CHANGE), as the SAM core would. */
void set_pin(uint32_t pin, int level);
/* Queues bytes on Serial1's receive side, as the VN-200 sends them; returns 0 if they do not fit
 * (the unread bytes are kept at the front first). */
int serial1_feed(const uint8_t *bytes, size_t len);
/* The same for the native USB port, and for the programming port. */
int usb_feed(const uint8_t *bytes, size_t len);
int serial0_feed(const uint8_t *bytes, size_t len);
/* Free room on a port's receive side (no more is taken: the bytes wait at the host). */
size_t room(Port port);

}  // namespace fake

#endif
