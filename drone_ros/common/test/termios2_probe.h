// Reads back the speed a tty really runs at, through termios2, so a test can tell "the port
// opened" from "the port opened at the rate asked for". Its own file for the same reason as
// src/custom_baud.cpp: <asm/termbits.h> and <termios.h> cannot meet in one file.
#ifndef DRONE_ROS_COMMON_TERMIOS2_PROBE_H
#define DRONE_ROS_COMMON_TERMIOS2_PROBE_H

// Output speed of the tty behind fd in bit/s, or -1 if it cannot be read.
long tty_output_baud(int fd);

#endif
