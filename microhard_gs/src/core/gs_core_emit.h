// GsCore::emit, shared by the units that make GsCore (one per MAVLink microservice): encodes one
// message with the vehicle's ids and signing state and queues its frame, through the Emitter
// every service shares.
#pragma once

#include "gs_core.h"

namespace microhard_gs {

template <typename Encode>
void GsCore::emit(Encode encode) {
  out_.emit(encode);
}

}  // namespace microhard_gs
