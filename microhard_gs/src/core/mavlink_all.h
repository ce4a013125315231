// The MAVLink 2 C library generated at build time by pymavlink's mavgen from the common.xml
// that pymavlink ships (see ../../CMakeLists.txt). Included as a SYSTEM header.
#pragma once
#include <common/mavlink.h>
