// Tests of io/output_file: an output file is written whole on commit or not at all (no file, no
// temporary left), an existing file is replaced only on commit, and a folder that does not exist
// is an InputError naming the file.
#include "io/output_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "io/input_error.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

std::size_t files_in(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.is_regular_file();
  return n;
}

TEST(OutputFile, CommitWritesTheWholeFile) {
  const scratch::ScratchDir dir;
  const std::string path = (dir / "out.csv").string();
  {
    AtomicOutputFile out(path);
    out.stream() << "x,y,z\n" << 1 << ',' << 2 << ',' << 3 << '\n';
    EXPECT_FALSE(fs::exists(path));  // only the temporary exists before the commit
    out.commit();
  }
  EXPECT_EQ(cli_runner::read_text(path), "x,y,z\n1,2,3\n");
  EXPECT_EQ(files_in(dir.path()), 1u);
  write_file_atomically(path, "replaced\n");
  EXPECT_EQ(cli_runner::read_text(path), "replaced\n");
  EXPECT_EQ(files_in(dir.path()), 1u);
}

TEST(OutputFile, WithoutCommitNothingIsWrittenOrReplaced) {
  const scratch::ScratchDir dir;
  const std::string path = (dir / "out.csv").string();
  try {
    AtomicOutputFile out(path);
    out.stream() << "half a file";
    throw std::runtime_error("a failure before the commit");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_EQ(files_in(dir.path()), 0u);  // the temporary is gone too
  write_file_atomically(path, "old\n");
  {
    AtomicOutputFile out(path);
    out.stream() << "new\n";
  }
  EXPECT_EQ(cli_runner::read_text(path), "old\n");
  EXPECT_EQ(files_in(dir.path()), 1u);
}

TEST(OutputFile, MissingFolderIsAnInputError) {
  const scratch::ScratchDir dir;
  const std::string path = (dir / "no" / "such" / "out.csv").string();
  try {
    write_file_atomically(path, "x\n");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": cannot write the output file (does its folder exist?)");
  }
  EXPECT_FALSE(fs::exists(dir / "no"));
}

}  // namespace
}  // namespace pkmopt
