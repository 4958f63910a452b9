// pkmopt describe MACHINE.yaml
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "io/machine/machine_description.hpp"

namespace pkmopt::cli {

void add_describe_command(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "describe",
      "Print a machine's degrees of freedom, drives and structure class (P<serial>З<parallel>)");
  cmd->add_option("machine", *file, "Machine file (YAML): a parallel model, serial or hybrid")
      ->required();
  cmd->callback([file] { std::cout << format_description(describe_machine_file(*file)); });
}

}  // namespace pkmopt::cli
