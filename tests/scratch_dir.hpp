// The one scratch folder of the tests: a new, empty, uniquely named folder under the system's
// temporary folder, removed with everything in it at the end of the test. Every test that writes
// files (machine files, studies, result folders, the CLI's captured output) writes them here.
//
// A fixture gives each test its own folder `dir_` (and `write`, `path`, `run_cli` into it):
//   class AnalyzeCli : public scratch::ScratchDirTest {};
//   TEST_F(AnalyzeCli, Works) {
//     const cli_runner::CliRun r = run_cli("analyze " + write("m.yaml", text) + " --poses ...");
//   }
// A test without a fixture (or a suite sharing one folder) holds a ScratchDir itself:
//   TEST(Journal, Resume) { const scratch::ScratchDir dir; std::ofstream(dir / "a.txt") << "x"; }
//
// The folder is <temp>/pkmopt_<Suite>_<Test>_XXXXXX (mkdtemp), so tests that run at the same
// time never share a folder. Set PKMOPT_KEEP_SCRATCH=1 to keep the folders for a look after a
// failure.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include "tests/cli_runner.hpp"

namespace scratch {

/// A new, empty, uniquely named folder, removed (recursively) by the destructor.
class ScratchDir {
 public:
  /// Named after the running test (suite and test name), or "pkmopt" outside a test.
  ScratchDir() : ScratchDir(current_test_tag()) {}
  /// Named <temp>/pkmopt_<tag>_XXXXXX.
  explicit ScratchDir(const std::string& tag) {
    std::string name = "pkmopt_";
    for (char c : tag) name += (std::isalnum(static_cast<unsigned char>(c)) || c == '_') ? c : '_';
    std::string pattern = (std::filesystem::temp_directory_path() / (name + "_XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr)
      throw std::runtime_error("cannot create a scratch folder from " + pattern);
    path_ = pattern;
  }
  ~ScratchDir() {
    const char* keep = std::getenv("PKMOPT_KEEP_SCRATCH");
    if (keep != nullptr && std::string(keep) == "1") return;
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::filesystem::path& name) const { return path_ / name; }

  /// Writes `text` (bytes as given) to <folder>/<name>, creating the folders on the way, and
  /// returns the file's path.
  std::string write(const std::filesystem::path& name, const std::string& text) const {
    const std::filesystem::path file = path_ / name;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << text;
    return file.string();
  }

  /// "Suite_Test" of the running test ("pkmopt" outside a test).
  static std::string current_test_tag() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    if (info == nullptr) return "pkmopt";
    return std::string(info->test_suite_name()) + "_" + info->name();
  }

 private:
  std::filesystem::path path_;
};

/// A fixture giving every test its own ScratchDir, `dir_`.
class ScratchDirTest : public ::testing::Test {
 protected:
  /// The path of <dir_>/<name> as a string.
  std::string path(const std::filesystem::path& name) const { return (dir_ / name).string(); }
  /// Writes <dir_>/<name> and returns its path.
  std::string write(const std::filesystem::path& name, const std::string& text) const {
    return scratch_dir_.write(name, text);
  }
  /// `pkmopt <args>` with its captured output in dir_ (tests/cli_runner.hpp).
  cli_runner::CliRun run_cli(const std::string& args) const {
    return cli_runner::run_cli(dir_, args);
  }

  const ScratchDir scratch_dir_;
  const std::filesystem::path dir_ = scratch_dir_.path();
};

}  // namespace scratch
