// Tests of studies/run_lock: one writer per result folder, the holder's PID in the refusal, the
// lock released when its holder ends, and the temporaries of a killed run removed.
#include "studies/run_lock.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/format/input_error.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

class RunLockTest : public scratch::ScratchDirTest {};

TEST_F(RunLockTest, SecondHolderIsRefusedWithThePidOfTheFirst) {
  const std::string dir = dir_.string();
  {
    const RunLock first(dir);
    std::ifstream in(first.path());
    long pid = 0;
    in >> pid;
    EXPECT_EQ(pid, static_cast<long>(::getpid()));
    try {
      const RunLock second(dir);
      FAIL() << "a second lock was granted";
    } catch (const InputError& error) {
      EXPECT_EQ(std::string(error.what()),
                first.path() + ": another pkmopt run (PID " + std::to_string(::getpid()) +
                    ") is writing this folder; wait for it to finish or stop it, then run again "
                    "(with --resume to continue its journal)");
    }
  }
  // Released with its holder: the lock file stays, the next run takes it.
  EXPECT_TRUE(fs::exists(dir_ / "run.lock"));
  EXPECT_NO_THROW(RunLock again(dir));
}

// A holder that is killed (here: a child that exits without cleaning up) frees the folder.
TEST_F(RunLockTest, LockOfAKilledHolderIsFree) {
  const std::string dir = dir_.string();
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const RunLock held(dir);
    ::_exit(0);  // no destructor runs: the kernel releases the lock
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_NO_THROW(RunLock taken(dir));
}

TEST_F(RunLockTest, StaleTemporariesAreRemovedOthersKept) {
  fs::create_directories(dir_ / "designs");
  for (const char* name : {"pareto.csv.tmp.4242", "designs/d0001.yaml.tmp.17", "pareto.csv",
                           "notes.tmp.txt", "x.tmp.12a", "designs/d0001.yaml"})
    std::ofstream(dir_ / name) << "x";
  EXPECT_EQ(remove_stale_temporaries(dir_.string()), 2u);
  EXPECT_FALSE(fs::exists(dir_ / "pareto.csv.tmp.4242"));
  EXPECT_FALSE(fs::exists(dir_ / "designs/d0001.yaml.tmp.17"));
  for (const char* name : {"pareto.csv", "notes.tmp.txt", "x.tmp.12a", "designs/d0001.yaml"})
    EXPECT_TRUE(fs::exists(dir_ / name)) << name;
  EXPECT_EQ(remove_stale_temporaries((dir_ / "missing").string()), 0u);
}

TEST_F(RunLockTest, UncreatableLockIsAnInputError) {
  EXPECT_THROW(RunLock((dir_ / "no" / "such" / "folder").string()), InputError);
}

}  // namespace
}  // namespace pkmopt
