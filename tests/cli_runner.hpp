// Running the pkmopt binary from tests: exit status, standard output and standard error.
//
// The only ways tests start pkmopt (PKMOPT_CLI):
//   run_cli(scratch, "analyze m.yaml --poses p.csv")   one command, output captured;
//   run_script(scratch, "studies/library/x/run.sh", "OUT 0.04 61")
//                                                        a study's run.sh with PKMOPT set;
//   spawn_cli({"run", "s.yaml", "--out", "o"})         a background process (to kill it).
// `scratch` is the test's scratch folder (tests/scratch_dir.hpp); the captured output files
// live there while the command runs.
#pragma once

#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace cli_runner {

struct CliRun {
  int status = -1;  ///< exit status, -1 if the process did not exit normally
  std::string out;
  std::string err;
};

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs the shell command `command` with no standard input, its standard output and error
/// captured through files in `scratch`.
inline CliRun run_command(const std::filesystem::path& scratch, const std::string& command) {
  const std::filesystem::path out = scratch / "stdout.txt", err = scratch / "stderr.txt";
  const std::string cmd = command + " >" + out.string() + " 2>" + err.string() + " </dev/null";
  const int raw = std::system(cmd.c_str());
  CliRun r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = read_text(out);
  r.err = read_text(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

/// Runs `pkmopt <args>` (PKMOPT_CLI) with no standard input; `scratch` holds the captured output
/// files while it runs.
inline CliRun run_cli(const std::filesystem::path& scratch, const std::string& args) {
  return run_command(scratch, std::string(PKMOPT_CLI) + " " + args);
}

/// Runs `bash <script> <args>` with PKMOPT=PKMOPT_CLI (how a study's run.sh finds pkmopt);
/// `script` is relative to the source tree.
inline CliRun run_script(const std::filesystem::path& scratch, const std::string& script,
                         const std::string& args) {
  return run_command(scratch, "PKMOPT=" + std::string(PKMOPT_CLI) + " bash " +
                                  (std::filesystem::path(PKMOPT_SOURCE_DIR) / script).string() +
                                  " " + args);
}

/// Starts `pkmopt <args...>` in the background (output discarded) and returns its process id,
/// for tests that stop a run part way (kill, then waitpid).
inline pid_t spawn_cli(const std::vector<std::string>& args) {
  const pid_t child = fork();
  if (child != 0) return child;  // the parent (or -1 when fork failed)
  if (std::freopen("/dev/null", "w", stdout) == nullptr ||
      std::freopen("/dev/null", "w", stderr) == nullptr)
    _exit(126);
  std::vector<char*> argv;
  std::string program = "pkmopt";
  argv.push_back(program.data());
  std::vector<std::string> copies = args;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(PKMOPT_CLI, argv.data());
  _exit(127);
}

}  // namespace cli_runner
