// The LQR gains are generated, not typed: rerunning the design script on the checked-in airframe
// data must reproduce the aircraft's checked-in gains.yaml byte for byte.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include <unistd.h>

namespace {

std::string read_all(const std::string &path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

TEST(DesignGains, RerunningTheDesignReproducesTheAircraftsCheckedInGains) {
  char dir_template[] = "/tmp/design_gains_XXXXXX";
  const char *dir = mkdtemp(dir_template);
  ASSERT_NE(dir, nullptr);
  const std::string out = std::string(dir) + "/gains.yaml";
  const std::string cmd = std::string(DESIGN_PYTHON) + " " + DESIGN_SCRIPT + " " + AIRCRAFT_DIR +
                          " --out " + out + " > " + dir + "/log.txt 2>&1";
  const int rc = std::system(cmd.c_str());
  const std::string log = read_all(std::string(dir) + "/log.txt");
  ASSERT_EQ(rc, 0) << log;
  const std::string generated = read_all(out);
  const std::string checked_in = read_all(std::string(AIRCRAFT_DIR) + "/gains.yaml");
  std::remove(out.c_str());
  std::remove((std::string(dir) + "/log.txt").c_str());
  rmdir(dir);
  ASSERT_FALSE(generated.empty());
  EXPECT_EQ(generated, checked_in)
      << "aircraft data or design script changed: rerun design_gains.py " AIRCRAFT_DIR
         " and check in its gains.yaml";
}

}  // namespace

int main(int argc, char **argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
