/* The device's generated message code (arduino_ha/link/gen/make_c99_msgs.py). CMake builds
 * define HA_LINK_GENERATED_HEADER to the copy generated in the build tree, so a build always uses
 * code fresh from msg/; arduino-cli, which cannot run the generator, uses the copy that
 * `make due-sketch-msgs` writes into generated/ (a test keeps that copy identical). */
#ifndef HA_LINK_MSGS_H
#define HA_LINK_MSGS_H

#ifdef HA_LINK_GENERATED_HEADER
#include HA_LINK_GENERATED_HEADER
#else
#include "generated/ha_msgs.h"
#endif

#endif /* HA_LINK_MSGS_H */
