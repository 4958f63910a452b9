// pkmopt: the command line. See README.md for every command, file format and column.
//
// Exit status: 0 success, 2 bad input (files, options, values) or an output that could not be
// written, 3 a result written but probably wrong, 4 a distributed run stopped by a failed worker,
// 1 an internal fault. Every error is one line
// "pkmopt: error: ..." on stderr.

#include <CLI/CLI.hpp>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <string>

#include "app/commands.hpp"
#include "app/error_report.hpp"
#include "io/format/input_error.hpp"
#include "pkmopt/version.hpp"
#include "studies/distribute.hpp"

using pkmopt::cli::flush_stdout;
using pkmopt::cli::output_error;
using pkmopt::cli::report;

int main(int argc, char** argv) {
  // Under mpirun only rank 0 speaks; `run`, `workspace` and `analyze` share their work with the
  // other ranks (docs/distributed.md), every other command runs on rank 0 alone.
  if (pkmopt::mpi_launch_from_environment().rank > 0) {
    const std::string command = argc < 2 ? std::string() : std::string(argv[1]);
    if (command != "run" && command != "workspace" && command != "analyze") return 0;
    pkmopt::cli::silence_reports();
  }
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
  pkmopt::cli::add_choose_command(app);
  pkmopt::cli::add_compare_command(app);
  pkmopt::cli::add_trajectory_command(app);
  pkmopt::cli::add_task_poses_command(app);
  pkmopt::cli::add_draw_command(app);
  pkmopt::cli::check_real_options(app);
  try {
    for (int i = 1; i < argc; ++i) {
      try {
        pkmopt::require_utf8(argv[i], "");
      } catch (const pkmopt::InputError&) {
        throw pkmopt::InputError("command line: argument " + std::to_string(i) + " " +
                                 pkmopt::quote_found(argv[i]) + ": expected UTF-8 text");
      }
    }
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {  // --help, --version
      app.exit(e);
      return flush_stdout() ? 0 : output_error();
    }
    report("error", pkmopt::cli::parse_error_message(app, e, argc, argv));
    return pkmopt::kExitInputError;
  } catch (const pkmopt::ProbablyWrongResult& e) {
    if (!flush_stdout()) return output_error();
    report("warning", e.what());
    return pkmopt::kExitProbablyWrong;
  } catch (const pkmopt::InputError& e) {
    flush_stdout();
    report("error", e.what());
    return pkmopt::kExitInputError;
  } catch (const std::filesystem::filesystem_error& e) {
    // A path the user gave that the file system refuses (a symbolic link loop, a name too
    // long, no permission): bad input, with the path and the system's reason.
    flush_stdout();
    report("error",
           (e.path1().empty() ? std::string() : pkmopt::quote_found(e.path1().string()) + ": ") +
               e.code().message());
    return pkmopt::kExitInputError;
  } catch (const std::bad_alloc&) {
    flush_stdout();
    report("error",
           "out of memory: the sizes this input asks for (samples, grid nodes, population, "
           "points) do not fit in memory; make them smaller");
    return pkmopt::kExitInputError;
  } catch (const std::exception& e) {
    flush_stdout();
    report("internal error", e.what());
    return pkmopt::kExitInternalError;
  }
  return flush_stdout() ? 0 : output_error();
}
