// The pkmopt subcommands. Each `add_*_command` adds one subcommand (with its options and its
// callback) to the CLI11 app; callbacks throw InputError for bad input (exit status 2).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>

namespace pkmopt::cli {

void add_analyze_command(CLI::App& app);
void add_fk_command(CLI::App& app);
void add_describe_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_validate_command(CLI::App& app);
void add_calibrate_command(CLI::App& app);
void add_simulate_measurements_command(CLI::App& app);
void add_calibration_poses_command(CLI::App& app);
void add_workspace_command(CLI::App& app);
void add_export_command(CLI::App& app);
void add_choose_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_trajectory_command(CLI::App& app);
void add_task_poses_command(CLI::App& app);
void add_draw_command(CLI::App& app);

/// The check of a number option: `accept(value)` or "expected EXPECTED, found TEXT" (a value
/// that is not a number is left to CLI11's own message).
CLI::Validator number_check(bool (*accept)(double), std::string_view expected,
                            const std::string& name);

/// The check of an option that is a length in metres: within +-1000 m
/// (io/format/number_policy.hpp), "expected a length within +-1000 m, found 1e15".
CLI::Validator length_in_metres();

}  // namespace pkmopt::cli
