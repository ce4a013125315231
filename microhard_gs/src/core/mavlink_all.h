// The MAVLink 2 C library generated at build time by pymavlink's mavgen from the development.xml
// that pymavlink ships (common.xml plus the standard-modes messages AVAILABLE_MODES and
// CURRENT_MODE, which pymavlink 2.4.50 has only there; see ../../CMakeLists.txt). Included as a
// SYSTEM header.
#pragma once
#include <development/mavlink.h>
