#include "limits_generator.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include <unistd.h>

namespace {

std::string TempFile(const char* stem) {
  std::string name = std::string("/tmp/") + stem + "_XXXXXX";
  const int fd = mkstemp(&name[0]);
  EXPECT_GE(fd, 0) << name;
  if (fd >= 0) close(fd);
  return name;
}

}  // namespace

std::string Slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

int RunGenerator(const std::string& limits_yaml, std::string* header, std::string* message) {
  const std::string out = TempFile("ha_config");
  const std::string err = TempFile("ha_config_err");
  const std::string cmd = std::string(HA_PYTHON) + " " + HA_CONFIG_GENERATOR + " " + limits_yaml +
                          " " + out + " > /dev/null 2> " + err;
  const int status = std::system(cmd.c_str());
  if (header != nullptr) *header = Slurp(out);
  if (message != nullptr) *message = Slurp(err);
  std::remove(out.c_str());
  std::remove(err.c_str());
  return status;
}

int GenerateWith(const std::string& key, const std::string& value, std::string* message) {
  const std::string yaml = Slurp(HA_LIMITS_YAML);
  const std::regex line("(^|\n)([ ]*" + key + ":) [^\n]*");
  EXPECT_TRUE(std::regex_search(yaml, line)) << key << " is not in " << HA_LIMITS_YAML;
  const std::string edited =
      std::regex_replace(yaml, line, "$1$2 " + value, std::regex_constants::format_first_only);
  const std::string name = TempFile("ha_limits");
  std::ofstream(name) << edited;
  const int status = RunGenerator(name, nullptr, message);
  std::remove(name.c_str());
  return status;
}

void ExpectRefused(const std::string& key, const std::string& value,
                   std::initializer_list<std::string> says) {
  std::string message;
  EXPECT_NE(GenerateWith(key, value, &message), 0) << key << ": " << value << " was accepted";
  for (const std::string& said : says) {
    EXPECT_NE(message.find(said), std::string::npos)
        << "the refusal of " << key << ": " << value << " does not say \"" << said << "\":\n"
        << message;
  }
}
