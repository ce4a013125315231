/* Minimal stand-in for the Arduino SAM core's Arduino.h (ArduinoCore-sam 1.6.x, the Due): only
 * the declarations the HA board layer uses, with the SAM core's signatures, so the board layer
 * can be compiled on a machine where the SAM core cannot be installed. Declarations only; the
 * host run (board_host_test.cpp) links fake_arduino.cpp, which implements them. Keep the
 * signatures identical to the SAM core's headers (wiring_digital.h, wiring_analog.h, wiring.h,
 * WInterrupts.h, watchdog.h, variant.h, UARTClass.h/USARTClass.h, USB/USBAPI.h). */
#ifndef HA_ARDUINO_SHIM_ARDUINO_H
#define HA_ARDUINO_SHIM_ARDUINO_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* wiring_constants.h */
#define HIGH 0x1
#define LOW 0x0
#define INPUT 0x0
#define OUTPUT 0x1
#define INPUT_PULLUP 0x2
#define CHANGE 2
#define FALLING 3
#define RISING 4

/* wiring.h */
extern uint32_t millis(void);
extern uint32_t micros(void);
extern void delay(uint32_t dwMs);
extern void delayMicroseconds(uint32_t dwUs);

/* wiring_digital.h */
extern void pinMode(uint32_t dwPin, uint32_t dwMode);
extern void digitalWrite(uint32_t dwPin, uint32_t dwVal);
extern int digitalRead(uint32_t ulPin);

/* wiring_analog.h */
extern void analogReadResolution(int res);
extern uint32_t analogRead(uint32_t ulPin);

/* WInterrupts.h */
void attachInterrupt(uint32_t pin, void (*callback)(void), uint32_t mode);
void detachInterrupt(uint32_t pin);

/* CMSIS (core_cm3.h), used by interrupts()/noInterrupts() */
void __enable_irq(void);
void __disable_irq(void);

/* CMSIS for the SAM3X8E (component/component_gpbr.h, sam3x8e.h): the eight general-purpose backup
 * registers, kept across a reset. The fake puts them in host memory. */
typedef volatile uint32_t RwReg;
typedef struct {
  RwReg SYS_GPBR[8];
} Gpbr;
extern Gpbr fake_gpbr;
#define GPBR (&fake_gpbr)

#ifdef __cplusplus
}
#endif

#define interrupts() __enable_irq()
#define noInterrupts() __disable_irq()

/* variant.h (arduino_due_x) */
#define NUM_DIGITAL_PINS 66u
#define digitalPinToInterrupt(p) ((p) < NUM_DIGITAL_PINS ? (p) : -1)
#define LED_BUILTIN 13
static const uint8_t A0 = 54;

/* watchdog.h: C++ linkage in the SAM core (included outside its extern "C" block). */
#ifdef __cplusplus
void watchdogEnable(uint32_t timeout);
void watchdogDisable(void);
void watchdogReset(void);
void watchdogSetup(void);

/* Stream/HardwareSerial subset of UARTClass (Serial), USARTClass (Serial1..3) and Serial_
 * (SerialUSB). */
class HardwareSerial {
 public:
  virtual ~HardwareSerial() {}
  virtual void begin(unsigned long baud) = 0;
  virtual int available(void) = 0;
  virtual int read(void) = 0;
  virtual size_t write(uint8_t c) = 0;
  virtual size_t write(const uint8_t *buffer, size_t size) = 0;
};

/* The fake board's ports share one implementation (fake_arduino.cpp), told apart by the port
 * each object is; the Due's class names stay, as the sketch declares them. */
class FakeSerialPort : public HardwareSerial {
 public:
  explicit FakeSerialPort(int port) : port_(port) {}
  void begin(unsigned long baud) override;
  int available(void) override;
  int read(void) override;
  size_t write(uint8_t c) override;
  size_t write(const uint8_t *buffer, size_t size) override;

 private:
  int port_;
};

class UARTClass : public FakeSerialPort {
 public:
  using FakeSerialPort::FakeSerialPort;
};

class USARTClass : public UARTClass {
 public:
  using UARTClass::UARTClass;
};

class Serial_ : public FakeSerialPort {
 public:
  using FakeSerialPort::FakeSerialPort;
};

extern UARTClass Serial;
extern USARTClass Serial1;
extern USARTClass Serial2;
extern USARTClass Serial3;
extern Serial_ SerialUSB;
#endif /* __cplusplus */

#endif /* HA_ARDUINO_SHIM_ARDUINO_H */
