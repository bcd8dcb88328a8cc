#include "surface_nbv/util/safe_file_name.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

using namespace surface_nbv;
namespace fs = std::filesystem;

class SafeFileName : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (fs::temp_directory_path() / "surface_nbv_safe_name_test").string();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ + "/real.map") << "x";
    std::ofstream("/tmp/surface_nbv_outside.map") << "secret";
    ASSERT_EQ(symlink("/tmp/surface_nbv_outside.map", (dir_ + "/link.map").c_str()), 0);
    fs::create_directories(dir_ + "/sub");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string dir_;
};

TEST_F(SafeFileName, AcceptsPlainNames) {
  std::string path;
  ASSERT_TRUE(resolveFileName(dir_, "new.map", false, &path).ok());
  EXPECT_EQ(path, dir_ + "/new.map");
  ASSERT_TRUE(resolveFileName(dir_, "real.map", true, &path).ok());
  EXPECT_EQ(path, dir_ + "/real.map");
}

TEST_F(SafeFileName, RefusesPathsTraversalAndSymlinks) {
  std::string path = "untouched";
  for (const std::string& bad : {std::string(""), std::string(".."), std::string("."), std::string("../x.map"),
                                 std::string("/etc/passwd"), std::string("a/b.map"), std::string("a\\b"),
                                 std::string(".hidden"), std::string("link.map"), std::string("sub"),
                                 std::string("new\nline"), std::string(200, 'a')}) {
    const Status s = resolveFileName(dir_, bad, false, &path);
    EXPECT_FALSE(s.ok()) << "accepted '" << bad << "'";
    EXPECT_FALSE(s.message().empty());
  }
  EXPECT_EQ(path, "untouched");
  EXPECT_FALSE(resolveFileName(dir_, "missing.map", true, &path).ok());
  EXPECT_FALSE(resolveFileName("", "x.map", false, &path).ok());
}
