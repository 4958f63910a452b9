// pkmopt: the command line. See README.md for every command, file format and column.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "app/commands.hpp"
#include "io/input_error.hpp"
#include "pkmopt/version.hpp"

namespace {

// "pkmopt: <kind>: <message>" on stderr. C stdio, which reports a failed write (stderr a full
// disk, a closed descriptor) by its return value instead of an exception: the exit status is
// then still the one the message belongs to.
void report(const char* kind, const char* message) noexcept {
  std::fprintf(stderr, "pkmopt: %s: %s\n", kind, message);
  std::fflush(stderr);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pkmopt: multi-objective design optimisation of parallel kinematic machine tools"};
  app.set_version_flag("--version", std::string("pkmopt ") + pkmopt::kVersion);
  app.require_subcommand(1);
  pkmopt::cli::add_analyze_command(app);
  pkmopt::cli::add_fk_command(app);
  pkmopt::cli::add_describe_command(app);
  pkmopt::cli::add_run_command(app);
  pkmopt::cli::add_validate_command(app);
  pkmopt::cli::add_calibrate_command(app);
  pkmopt::cli::add_simulate_measurements_command(app);
  pkmopt::cli::add_calibration_poses_command(app);
  pkmopt::cli::add_workspace_command(app);
  pkmopt::cli::add_export_command(app);
  pkmopt::cli::add_compare_command(app);
  pkmopt::cli::add_trajectory_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : pkmopt::kExitInputError;
  } catch (const pkmopt::ProbablyWrongResult& e) {
    std::fflush(stdout);
    report("warning", e.what());
    return pkmopt::kExitProbablyWrong;
  } catch (const pkmopt::InputError& e) {
    std::fflush(stdout);
    report("error", e.what());
    return pkmopt::kExitInputError;
  } catch (const std::exception& e) {
    std::fflush(stdout);
    report("internal error", e.what());
    return pkmopt::kExitInternalError;
  }
  return 0;
}
