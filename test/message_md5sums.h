// The message md5sums pinned in test/message_md5sums.txt ("name md5" per line, # comments): the
// wire contract both the stack's ROS messages and the HA's generated copies are held to.
#ifndef DRONE_ROS_TEST_MESSAGE_MD5SUMS_H
#define DRONE_ROS_TEST_MESSAGE_MD5SUMS_H

#include <fstream>
#include <map>
#include <sstream>
#include <string>

inline std::map<std::string, std::string> pinned_md5sums(const char *path) {
  std::map<std::string, std::string> sums;
  std::ifstream file(path);
  std::string line;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string name, md5;
    fields >> name >> md5;
    sums[name] = md5;
  }
  return sums;
}

#endif  // DRONE_ROS_TEST_MESSAGE_MD5SUMS_H
