// Tests of io/format/output_file: an output file is written whole on commit or not at all (no file,
// no temporary left), an existing file is replaced only on commit, and a folder that does not exist
// is an InputError naming the file.
#include "io/format/output_file.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>

#include "io/format/input_error.hpp"
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

// --out replaced whatever it named: a device node or a symbolic link became a regular file (as
// root, `--out /dev/null` destroyed the system's /dev/null). Now a link is followed and its target
// replaced, a character device or FIFO is written into, a folder is refused.
TEST(OutputFile, OutReplacesWhatItNames) {
  const scratch::ScratchDir dir;
  // A symbolic link: the target is replaced atomically, the link stays a link.
  write_file_atomically((dir / "target.csv").string(), "old\n");
  fs::create_symlink("target.csv", dir / "link.csv");
  write_file_atomically((dir / "link.csv").string(), "new\n");
  EXPECT_TRUE(fs::is_symlink(dir / "link.csv"));
  EXPECT_EQ(cli_runner::read_text(dir / "target.csv"), "new\n");
  // A dangling link: its target is created.
  fs::create_symlink("later.csv", dir / "dangling.csv");
  write_file_atomically((dir / "dangling.csv").string(), "created\n");
  EXPECT_TRUE(fs::is_symlink(dir / "dangling.csv"));
  EXPECT_EQ(cli_runner::read_text(dir / "later.csv"), "created\n");
  // A FIFO with a reader: written into, still a FIFO; without a reader: an error, not a hang.
  const fs::path fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THROW(write_file_atomically(fifo.string(), "nobody reads\n"), InputError);
  std::string got;
  std::thread reader([&] { got = cli_runner::read_text(fifo); });
  for (int tries = 0;; ++tries) {  // until the reader has opened its end
    try {
      write_file_atomically(fifo.string(), "through the pipe\n");
      break;
    } catch (const InputError&) {
      ASSERT_LT(tries, 10000000) << "the reader never opened the FIFO";
    }
  }
  reader.join();
  EXPECT_EQ(got, "through the pipe\n");
  EXPECT_EQ(fs::status(fifo).type(), fs::file_type::fifo);
  // A character device (root may make one): written into, not replaced.
  const fs::path device = dir / "mynull";
  if (::mknod(device.c_str(), S_IFCHR | 0666, ::makedev(1, 3)) == 0) {
    write_file_atomically(device.string(), "discarded\n");
    EXPECT_EQ(fs::status(device).type(), fs::file_type::character);
  }
  // A folder is refused, by its type.
  fs::create_directories(dir / "folder");
  try {
    write_file_atomically((dir / "folder").string(), "x\n");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("found a folder"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_directory(dir / "folder"));
}

// Commands that write several files left the first ones behind when a later one failed
// (`compare ... --out c.html --svg /proc/version` kept c.html).
TEST(OutputFile, CommandsThatWriteSeveralFilesAreAllOrNothing) {
  const scratch::ScratchDir dir;
  const std::string first = (dir / "c.html").string();
  fs::create_directories(dir / "folder");
  for (const std::string& bad : {(dir / "no" / "such" / "x.svg").string(),
                                 (dir / "folder").string(), std::string("/proc/version")}) {
    EXPECT_THROW(write_files_together({{first, "<html>"}, {bad, "<svg/>"}}), InputError) << bad;
    EXPECT_FALSE(fs::exists(first)) << bad;
  }
  EXPECT_EQ(files_in(dir.path()), 0u);  // no temporary either
  write_files_together({{first, "<html>"}, {(dir / "c.svg").string(), "<svg/>"}});
  EXPECT_EQ(cli_runner::read_text(first), "<html>");
  EXPECT_EQ(cli_runner::read_text(dir / "c.svg"), "<svg/>");
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
