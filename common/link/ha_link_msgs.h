/* The link's generated message code (common/link/gen/make_c99_msgs.py), always fresh from
 * msg/: CMake builds define HA_LINK_GENERATED_HEADER to the code generated in the build tree;
 * arduino-cli, which cannot run the generator, compiles the sketch `make sketch-ha` assembles,
 * with the same generator's output in generated/. */
#ifndef HA_LINK_MSGS_H
#define HA_LINK_MSGS_H

#ifdef HA_LINK_GENERATED_HEADER
#include HA_LINK_GENERATED_HEADER
#else
#include "generated/ha_msgs.h"
#endif

#endif /* HA_LINK_MSGS_H */
