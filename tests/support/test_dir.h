// A temporary folder of its own for the running test case, so that ctest may run cases (and build trees) in
// parallel without sharing files.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace lumis::test {

/// temp/<prefix>_<pid>_<test name>, created empty (anything left there by an earlier run is removed).
inline std::filesystem::path fresh_test_dir(const std::string& prefix) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()) + "_" + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// A fixture with a fresh folder of its own (`dir_`, removed afterwards), for tests that write files.
class FolderTest : public ::testing::Test {
 protected:
  explicit FolderTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override { dir_ = fresh_test_dir(prefix_); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  /// The path of `name` in the folder.
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  /// The names the folder holds: a temporary file left behind shows up here.
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    return names;
  }
  std::filesystem::path dir_;

 private:
  std::string prefix_;
};

}  // namespace lumis::test
