// The HA's configuration generator (tools/gen_aircraft_config.py) run from the tests as a user
// runs it: on a limits.yaml, or on the build's own with one key's value edited.
#ifndef ARDUINO_HA_TEST_LIMITS_GENERATOR_H
#define ARDUINO_HA_TEST_LIMITS_GENERATOR_H

#include <initializer_list>
#include <string>

std::string Slurp(const std::string& path);

// Runs the generator on limits_yaml and returns its exit status (0: the header was written); the
// header goes into *header and what it said on stderr (why it refused) into *message, for those
// given.
int RunGenerator(const std::string& limits_yaml, std::string* header = nullptr,
                 std::string* message = nullptr);

// The same on the build's limits.yaml with the first line setting key edited to `key: value`.
int GenerateWith(const std::string& key, const std::string& value, std::string* message = nullptr);

// The generator refuses the build's limits.yaml with key set to value, and its message says each
// of says (the key, the reason, the file to look in).
void ExpectRefused(const std::string& key, const std::string& value,
                   std::initializer_list<std::string> says);

#endif  // ARDUINO_HA_TEST_LIMITS_GENERATOR_H
