// Any baud rate through Linux's termios2 (BOTHER), for rates <termios.h> has no constant for.
// In its own file because <asm/termbits.h> and <termios.h> cannot be included together.
#ifndef DRONE_ROS_COMMON_CUSTOM_BAUD_H
#define DRONE_ROS_COMMON_CUSTOM_BAUD_H

namespace drone_ros_common {

// Sets input and output speed of the tty fd to baud; false (errno set) if the driver refuses.
bool set_custom_baud(int fd, int baud);

}  // namespace drone_ros_common

#endif
