// Any baud rate through Linux's termios2 (BOTHER), for rates <termios.h> has no constant for,
// such as 250000: exact on both the Due's 16U2 (16 MHz / 64) and its SAM3X UART (84 MHz / 336).
// Kept in its own file because <asm/termbits.h> and <termios.h> cannot be included together.
#ifndef ARDUINO_LINK_CUSTOM_BAUD_H
#define ARDUINO_LINK_CUSTOM_BAUD_H

namespace arduino_link {

// Sets input and output speed of fd to baud; false if the driver refuses.
bool set_custom_baud(int fd, int baud);

}  // namespace arduino_link

#endif
