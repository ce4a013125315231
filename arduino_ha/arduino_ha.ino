// drone_ros high-assurance (HA) firmware for the Arduino Due.
// Everything lives under src/: the portable C99 core (src/core), the rosserial link
// (src/link) and the Due board layer (src/board_due); the VN-200 protocol core joins them in
// src/vn200 when the sketch is assembled (make sketch-ha). Build and flash: see README.md.
#include "src/board_due/due_main.h"

void setup() { due_main_setup(); }

void loop() { due_main_loop(); }
