#include "termios2_probe.h"

#include <asm/termbits.h>
#include <sys/ioctl.h>

long tty_output_baud(int fd) {
  struct termios2 tio {};
  if (ioctl(fd, TCGETS2, &tio) != 0) return -1;
  return static_cast<long>(tio.c_ospeed);
}
