/* Stand-in for the Arduino Servo library's public interface (arduino-libraries/Servo, the
 * version arduino-cli installs; its SAM backend drives a 20 ms = 50 Hz frame). Declarations
 * only, same signatures (fake_arduino.cpp implements them for the host run). */
#ifndef HA_ARDUINO_SHIM_SERVO_H
#define HA_ARDUINO_SHIM_SERVO_H

#include <stdint.h>

#define MIN_PULSE_WIDTH 544
#define MAX_PULSE_WIDTH 2400
#define DEFAULT_PULSE_WIDTH 1500
#define REFRESH_INTERVAL 20000

class Servo {
 public:
  Servo();
  uint8_t attach(int pin);
  uint8_t attach(int pin, int min, int max);
  void detach();
  void write(int value);
  void writeMicroseconds(int value);
  int read();
  int readMicroseconds();
  bool attached();

 private:
  uint8_t servoIndex;
  int8_t min;
  int8_t max;
};

#endif /* HA_ARDUINO_SHIM_SERVO_H */
