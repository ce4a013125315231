// The MAVLink 2 signing key file: 64 hexadecimal characters (the 32-byte secret), surrounding
// whitespace allowed, nothing else. One place so the node and the tests read it the same way.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace microhard_gs {

using SigningKey = std::array<uint8_t, 32>;

// True and `key` filled when `text` is a valid key; otherwise false and `error` says why.
bool parse_signing_key(const std::string& text, SigningKey* key, std::string* error);

}  // namespace microhard_gs
