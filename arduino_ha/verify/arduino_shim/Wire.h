/* Stand-in for the SAM core's Wire library (libraries/Wire/src/Wire.h): the TwoWire members the
 * board layer uses, same signatures. Declarations only (fake_arduino.cpp implements them for
 * the host run). */
#ifndef HA_ARDUINO_SHIM_WIRE_H
#define HA_ARDUINO_SHIM_WIRE_H

#include <stddef.h>
#include <stdint.h>

class TwoWire {
 public:
  void begin();
  void begin(uint8_t address);
  void setClock(uint32_t frequency);
  void beginTransmission(uint8_t address);
  uint8_t endTransmission(void);
  uint8_t requestFrom(uint8_t address, uint8_t quantity);
  uint8_t requestFrom(int address, int quantity);
  size_t write(uint8_t data);
  int available(void);
  int read(void);
};

extern TwoWire Wire;
extern TwoWire Wire1;

#endif /* HA_ARDUINO_SHIM_WIRE_H */
