#include "signing_key.h"

#include <cctype>

namespace microhard_gs {
namespace {
int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}
}  // namespace

bool parse_signing_key(const std::string& text, SigningKey* key, std::string* error) {
  size_t begin = 0;
  size_t end = text.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(text[begin]))) ++begin;
  while (end > begin && std::isspace(static_cast<unsigned char>(text[end - 1]))) --end;
  if (end - begin != 2 * key->size()) {
    *error = "signing key must be 64 hex characters, found " + std::to_string(end - begin);
    return false;
  }
  SigningKey out{};
  for (size_t i = 0; i < out.size(); ++i) {
    const int hi = hex_value(text[begin + 2 * i]);
    const int lo = hex_value(text[begin + 2 * i + 1]);
    if (hi < 0 || lo < 0) {
      *error = "signing key has a non-hex character";
      return false;
    }
    out[i] = static_cast<uint8_t>(hi * 16 + lo);
  }
  bool all_zero = true;
  for (uint8_t b : out) all_zero = all_zero && b == 0;
  if (all_zero) {
    *error = "signing key is all zeros";
    return false;
  }
  *key = out;
  return true;
}

}  // namespace microhard_gs
