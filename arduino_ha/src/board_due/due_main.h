/* The firmware's setup and loop, kept out of the .ino so the host compile check covers them. */
#ifndef DUE_MAIN_H
#define DUE_MAIN_H

#include "../firmware/ha_firmware.h"

void due_main_setup(void);
void due_main_loop(void);

/* The firmware's state, for the sketch-on-host checks (verify/board_host_test.cpp). */
const HaFirmware *due_main_firmware(void);

#endif /* DUE_MAIN_H */
