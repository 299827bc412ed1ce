// Test helpers shared by every suite: data locations and scratch files.
#pragma once

#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace mpcal::testing {

/// Radians in a degree.
inline constexpr double kDeg = std::numbers::pi / 180.0;
/// A relative tolerance for results that differ by a few double roundings.
inline constexpr double kArithmetic = 1e-12;

/// A file among the project's own small test logs (tests/data/).
inline std::string TestDataPath(const std::string& name) {
  return std::string(MPCAL_TEST_DATA_DIR) + "/" + name;
}

/// A file among the real recordings from other projects (tests/data/real/,
/// each folder with its source and licence).
inline std::string RealDataPath(const std::string& name) {
  return std::string(MPCAL_REAL_DATA_DIR) + "/" + name;
}

/// A fresh scratch directory for one test, removed with the object.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            (std::string("mpcal_") + (info ? info->name() : "test") + "_" +
             std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  /// Path of `name` inside the directory.
  std::string Path(const std::string& name) const { return (path_ / name).string(); }
  /// Writes `content` to `name` and returns its path.
  std::string Write(const std::string& name, const std::string& content) const {
    std::ofstream(Path(name), std::ios::binary) << content;
    return Path(name);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace mpcal::testing
