/* The Due board: pin map and the constants of the avionics hardware around the SAM3X8E. These
 * describe the board and its sensors, not the aircraft (aircraft limits, servo calibration and
 * the control rate come from aircraft/<name>/ through the core's HaAircraftConfig). The pin map
 * is repeated in arduino_ha/README.md; change both together. */
#ifndef DUE_CONFIG_H
#define DUE_CONFIG_H

#include <stdint.h>

/* Servo/ESC outputs (Servo library: 50 Hz frame, any digital pin). */
#define DUE_PIN_SERVO_ELEVATOR 7u
#define DUE_PIN_SERVO_AILERON 8u
#define DUE_PIN_SERVO_RUDDER 9u
#define DUE_PIN_SERVO_THROTTLE 6u

/* RC receiver PWM channels, captured on pin-change interrupts (every Due pin can interrupt).
 * Order matches HA_RC_* in core/ha_types.h. */
#define DUE_PIN_RC_THROTTLE 22u
#define DUE_PIN_RC_ELEVATOR 23u
#define DUE_PIN_RC_AILERON 24u
#define DUE_PIN_RC_RUDDER 25u
#define DUE_PIN_RC_PIC 26u
/* A channel whose last pulse ended longer ago than this is lost (receivers frame at 50 Hz; five
 * missed frames = lost). */
#define DUE_RC_TIMEOUT_US 100000u
/* Widths outside this window are glitches, not servo pulses (counted and dropped). */
#define DUE_RC_PULSE_MIN_PLAUSIBLE_US 700u
#define DUE_RC_PULSE_MAX_PLAUSIBLE_US 2300u

/* AMS 5812 airspeed sensor on the Due's first I2C bus (SDA 20, SCL 21). */
#define DUE_AMS5812_I2C_ADDRESS 0x78u
#define DUE_I2C_CLOCK_HZ 400000u
/* Full scale of the fitted part, AMS 5812-0003-D (differential, 0 ... 0.3 psi = 0 ... 2068 Pa):
 * reads up to about 190 ft/s indicated, well above the glider's speeds, with 0.08 Pa per count.
 * Fitting another range means changing these two values. */
#define DUE_AMS5812_P_MIN_PA 0.0f
#define DUE_AMS5812_P_MAX_PA 2068.43f

/* Battery: analog pin A0 (Due pin 54) behind a resistor divider; the ADC reads 0 ... 3.3 V over
 * 12 bits. The divider (47k over 10k) maps up to 18.8 V onto 3.3 V. */
#define DUE_PIN_BATTERY 54u
#define DUE_ADC_BITS 12
#define DUE_ADC_FULL_SCALE_COUNTS 4095.0f
#define DUE_ADC_REFERENCE_V 3.3f
#define DUE_BATTERY_DIVIDER_RATIO 5.7f

/* HP computer reset: drives the gate of the transistor on the HP's reset/power-enable line.
 * HIGH holds the HP in reset. */
#define DUE_PIN_HP_RESET 30u

/* Status LEDs (HA_LED_* bits). */
#define DUE_PIN_LED_HP 31u
#define DUE_PIN_LED_HA 13u /* the on-board "L" LED */
#define DUE_PIN_LED_MANUAL 32u
#define DUE_PIN_LED_FAULT 33u

/* VN-200 port 1 on the Due's Serial1 (RX1 = pin 19, TX1 = pin 18), configured on the sensor for
 * this rate and for the binary output the HA decodes. */
#define DUE_VN200_BAUD 115200u

/* HP link (rosserial): which of the Due's two USB connectors carries it, chosen at compile time
 * (e.g. arduino-cli --build-property "compiler.cpp.extra_flags=-DDUE_HP_LINK_PORT=2"):
 *  - DUE_HP_LINK_PORT_PROGRAMMING (default): `Serial`, the SAM3X's UART0 behind the ATmega16U2
 *    USB-serial bridge, at DUE_HP_LINK_BAUD. The link budget (drone_ros/arduino_link/README.md)
 *    and the flight launch (arduino_baud 250000) assume this port. 250000 is exact on both chips
 *    (84 MHz / (16 x 21), 16 MHz / (8 x 8)); 115200 cannot carry the HA's two status messages at
 *    100 Hz.
 *  - DUE_HP_LINK_PORT_NATIVE: `SerialUSB`, the SAM3X's own USB (CDC; libsam's UDD_Init leaves
 *    it high-speed capable); no UART in between, so the baud rate is ignored on both ends. */
#define DUE_HP_LINK_PORT_PROGRAMMING 1
#define DUE_HP_LINK_PORT_NATIVE 2
#ifndef DUE_HP_LINK_PORT
#define DUE_HP_LINK_PORT DUE_HP_LINK_PORT_PROGRAMMING
#endif
#define DUE_HP_LINK_BAUD 250000u

/* The build: 0 flies the aircraft (due_board.cpp: the pins); 1 is the HIL build
 * (due_hil_board.cpp): the pins' inputs come from the simulator's step records on the native USB
 * port and the outputs go back in reply records, the HP link and the VN-200 stay where they are.
 * arduino-cli: --build-property "compiler.cpp.extra_flags=-DHA_DUE_HIL=1"
 * "compiler.c.extra_flags=-DHA_DUE_HIL=1"; make due-hil-image. */
#ifndef HA_DUE_HIL
#define HA_DUE_HIL 0
#endif

/* Hardware watchdog: reset if the loop has not completed a period for this long. The SAM3X
 * watchdog mode register can be written once per reset, so it is set in watchdogSetup(). */
#define DUE_WATCHDOG_TIMEOUT_MS 100u

#endif /* DUE_CONFIG_H */
