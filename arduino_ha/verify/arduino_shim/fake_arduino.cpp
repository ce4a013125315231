/* Host implementation of the shim's Arduino, Servo and Wire declarations: records what the board
 * layer does and lets board_host_test.cpp drive time, pins, the ADC and I2C replies. Test-only;
 * the Due build uses the real SAM core. */
#include <Arduino.h>
#include <Servo.h>
#include <Wire.h>
#include <string.h>

#include "fake_arduino.h"

namespace fake {
State state;
void reset() { state = State(); }
namespace {
int feed(uint8_t *ring, size_t cap, size_t *ring_len, size_t *pos, const uint8_t *bytes,
         size_t len) {
  const size_t unread = *ring_len - *pos;
  memmove(ring, ring + *pos, unread);
  *pos = 0u;
  *ring_len = unread;
  if (len > cap - unread) {
    return 0;
  }
  memcpy(ring + unread, bytes, len);
  *ring_len += len;
  return 1;
}
}  // namespace
int serial1_feed(const uint8_t *bytes, size_t len) {
  return feed(state.serial1_rx, sizeof state.serial1_rx, &state.serial1_len, &state.serial1_pos,
              bytes, len);
}
int usb_feed(const uint8_t *bytes, size_t len) {
  return feed(state.usb_rx, sizeof state.usb_rx, &state.usb_len, &state.usb_pos, bytes, len);
}
int serial0_feed(const uint8_t *bytes, size_t len) {
  return feed(state.serial0_rx, sizeof state.serial0_rx, &state.serial0_len, &state.serial0_pos,
              bytes, len);
}
size_t room(Port port) {
  switch (port) {
    case kSerial:
      return sizeof state.serial0_rx - (state.serial0_len - state.serial0_pos);
    case kSerial1:
      return sizeof state.serial1_rx - (state.serial1_len - state.serial1_pos);
    default:
      return sizeof state.usb_rx - (state.usb_len - state.usb_pos);
  }
}
void set_pin(uint32_t pin, int level) {
  state.pin_level[pin] = level;
  if (state.isr[pin] != nullptr) {
    state.isr[pin]();
  }
}
}  // namespace fake

extern "C" {
uint32_t millis(void) { return fake::state.now_us / 1000u; }
uint32_t micros(void) { return fake::state.now_us; }
void delay(uint32_t ms) { fake::state.now_us += ms * 1000u; }
void delayMicroseconds(uint32_t us) { fake::state.now_us += us; }
void pinMode(uint32_t pin, uint32_t mode) { fake::state.pin_mode[pin] = static_cast<int>(mode); }
void digitalWrite(uint32_t pin, uint32_t val) { fake::state.written[pin] = static_cast<int>(val); }
int digitalRead(uint32_t pin) { return fake::state.pin_level[pin]; }
void analogReadResolution(int res) { fake::state.adc_bits = res; }
uint32_t analogRead(uint32_t pin) {
  (void)pin;
  return fake::state.adc_counts;
}
void attachInterrupt(uint32_t pin, void (*callback)(void), uint32_t mode) {
  (void)mode;
  fake::state.isr[pin] = callback;
}
void detachInterrupt(uint32_t pin) { fake::state.isr[pin] = nullptr; }
void __enable_irq(void) { fake::state.irq_disabled = 0; }
void __disable_irq(void) { fake::state.irq_disabled = 1; }
}

void watchdogEnable(uint32_t timeout) { fake::state.watchdog_timeout_ms = timeout; }
void watchdogDisable(void) { fake::state.watchdog_timeout_ms = 0u; }
void watchdogReset(void) { fake::state.watchdog_kicks++; }

/* Not in fake::state: reset() is a power cycle of the fake board's pins, not of the backup
 * domain; tests clear it themselves for a power-up. */
Gpbr fake_gpbr = {};

/* Serial delivers what fake::serial0_feed() queued, Serial1 (the VN-200) what fake::serial1_feed()
 * queued, SerialUSB what fake::usb_feed() queued; Serial2 and Serial3 (port -1) see silence. */
namespace {
struct Ring {
  uint8_t *bytes;
  size_t *len;
  size_t *pos;
};
bool port_ring(int port, Ring *ring) {
  switch (port) {
    case fake::kSerial:
      *ring = Ring{fake::state.serial0_rx, &fake::state.serial0_len, &fake::state.serial0_pos};
      return true;
    case fake::kSerial1:
      *ring = Ring{fake::state.serial1_rx, &fake::state.serial1_len, &fake::state.serial1_pos};
      return true;
    case fake::kSerialUsb:
      *ring = Ring{fake::state.usb_rx, &fake::state.usb_len, &fake::state.usb_pos};
      return true;
    default:
      return false;
  }
}
/* What the sketch wrote to SerialUSB while the host had it open, kept for the test to read. */
size_t usb_keep(const uint8_t *buffer, size_t size) {
  if (!fake::state.usb_open || size > sizeof fake::state.usb_tx - fake::state.usb_tx_len) {
    return 0u;
  }
  memcpy(fake::state.usb_tx + fake::state.usb_tx_len, buffer, size);
  fake::state.usb_tx_len += size;
  return size;
}
}  // namespace
void FakeSerialPort::begin(unsigned long baud) { (void)baud; }
int FakeSerialPort::available(void) {
  Ring r;
  return port_ring(port_, &r) ? static_cast<int>(*r.len - *r.pos) : 0;
}
int FakeSerialPort::read(void) {
  Ring r;
  if (!port_ring(port_, &r) || *r.pos >= *r.len) {
    return -1;
  }
  return r.bytes[(*r.pos)++];
}
size_t FakeSerialPort::write(uint8_t c) { return write(&c, 1u); }
size_t FakeSerialPort::write(const uint8_t *buffer, size_t size) {
  const bool usb = port_ == fake::kSerialUsb;
  if (port_ < 0) {
    return size;
  }
  if (fake::state.tx_sink != nullptr) {
    return !usb || fake::state.usb_open
               ? fake::state.tx_sink(static_cast<fake::Port>(port_), buffer, size)
               : 0u;
  }
  return usb ? usb_keep(buffer, size) : size;
}
UARTClass Serial(fake::kSerial);
USARTClass Serial1(fake::kSerial1);
USARTClass Serial2(-1);
USARTClass Serial3(-1);
Serial_ SerialUSB(fake::kSerialUsb);

Servo::Servo() : servoIndex(255u), min(0), max(0) {}
uint8_t Servo::attach(int pin) { return attach(pin, MIN_PULSE_WIDTH, MAX_PULSE_WIDTH); }
uint8_t Servo::attach(int pin, int min_us, int max_us) {
  servoIndex = static_cast<uint8_t>(fake::state.servo_count++);
  fake::ServoRecord &r = fake::state.servos[servoIndex];
  r.pin = pin;
  r.min_us = min_us;
  r.max_us = max_us;
  r.pulse_us = DEFAULT_PULSE_WIDTH;
  return servoIndex;
}
void Servo::detach() {}
void Servo::write(int value) { writeMicroseconds(value); }
void Servo::writeMicroseconds(int value) {
  fake::ServoRecord &r = fake::state.servos[servoIndex];
  /* The real library clamps to the attach() range; so does the fake. */
  r.pulse_us = value < r.min_us ? r.min_us : (value > r.max_us ? r.max_us : value);
  r.writes++;
}
int Servo::read() { return 0; }
int Servo::readMicroseconds() { return fake::state.servos[servoIndex].pulse_us; }
bool Servo::attached() { return servoIndex != 255u; }

void TwoWire::begin() {}
void TwoWire::begin(uint8_t address) { (void)address; }
void TwoWire::setClock(uint32_t frequency) { fake::state.i2c_clock_hz = frequency; }
void TwoWire::beginTransmission(uint8_t address) { (void)address; }
uint8_t TwoWire::endTransmission(void) { return 0u; }
uint8_t TwoWire::requestFrom(uint8_t address, uint8_t quantity) {
  fake::state.i2c_last_address = address;
  fake::state.i2c_pos = 0u;
  return quantity < fake::state.i2c_reply_len ? quantity : fake::state.i2c_reply_len;
}
uint8_t TwoWire::requestFrom(int address, int quantity) {
  return requestFrom(static_cast<uint8_t>(address), static_cast<uint8_t>(quantity));
}
size_t TwoWire::write(uint8_t data) {
  (void)data;
  return 1u;
}
int TwoWire::available(void) { return fake::state.i2c_reply_len - fake::state.i2c_pos; }
int TwoWire::read(void) {
  return fake::state.i2c_pos < fake::state.i2c_reply_len
             ? fake::state.i2c_reply[fake::state.i2c_pos++]
             : -1;
}
TwoWire Wire;
TwoWire Wire1;
