// pkmopt choose DIR (--weights W | --reference R | --knee | --compromise) [--out FILE]
// Reads DIR/pareto.json (written by `pkmopt run`), chooses one feasible design by the rule
// given (report/pareto_choice.hpp), prints it and writes its machine file (default
// DIR/chosen.yaml). See docs/export.md, "Choosing a design".
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "io/results/pareto_json.hpp"
#include "report/pareto_choice.hpp"

namespace pkmopt::cli {
namespace {

struct ChooseCommandOptions {
  std::string results_dir;
  std::string weights;
  std::string reference;
  bool knee = false;
  bool compromise = false;
  std::string out;
};

ChoiceRequest request_of(const ParetoFront& front, const ChooseCommandOptions& opt) {
  const int rules = (opt.weights.empty() ? 0 : 1) + (opt.reference.empty() ? 0 : 1) +
                    (opt.knee ? 1 : 0) + (opt.compromise ? 1 : 0);
  if (rules != 1)
    throw InputError(
        fmt::format("choose: expected one of --weights, --reference, --knee and "
                    "--compromise, found {}",
                    rules == 0 ? "none" : fmt::format("{} of them", rules)));
  if (!opt.weights.empty())
    return parse_choice_request(front, ChoiceRule::kWeights, opt.weights, "--weights");
  if (!opt.reference.empty())
    return parse_choice_request(front, ChoiceRule::kReference, opt.reference, "--reference");
  return ChoiceRequest{opt.knee ? ChoiceRule::kKnee : ChoiceRule::kCompromise, {}};
}

void run_choose(const ChooseCommandOptions& opt) {
  namespace fs = std::filesystem;
  const fs::path dir(opt.results_dir);
  require_results_folder(opt.results_dir);
  require_not_a_folder("--out", opt.out);
  const ParetoFront front = read_pareto_json((dir / "pareto.json").string());
  const ChoiceRequest request = request_of(front, opt);
  const DesignChoice choice = choose_design(front, request);
  const ParetoDesign& design = front.designs[choice.design];
  if (!design.machine_file) {
    throw InputError(
        fmt::format("{}: {}: expected a machine_file (the study writes them unless `write_designs: "
                    "false`), found none",
                    (dir / "pareto.json").string(), design.id));
  }
  const fs::path machine = dir / *design.machine_file;
  const std::string yaml = read_input_file(machine.string());
  const fs::path out = opt.out.empty() ? dir / "chosen.yaml" : fs::path(opt.out);
  write_file_atomically(out.string(), chosen_machine_file(front, request, choice, yaml));
  fmt::print("{}machine file: {} -> {}\n", choice_text(front, request, choice), machine.string(),
             out.string());
  std::fflush(stdout);
}

}  // namespace

void add_choose_command(CLI::App& app) {
  auto opt = std::make_shared<ChooseCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "choose",
      "Choose one feasible design of a study's Pareto front (DIR/pareto.json of `pkmopt run`) "
      "by a preference, a reference point, the knee or the compromise; print it and write its "
      "machine file");
  cmd->add_option("dir", opt->results_dir, "Results folder of `pkmopt run`")->required();
  cmd->add_option("--weights", opt->weights,
                  "Preference NAME=W,... over the objectives (W >= 0, scaled to sum 1; objectives "
                  "left out weigh 0): the design whose pseudo-weights are nearest");
  cmd->add_option("--reference", opt->reference,
                  "Aspiration level NAME=VALUE,... of every objective, in the units of "
                  "pareto.json (N/m, m, m^3, N): the design the achievement scalarizing function "
                  "chooses");
  cmd->add_flag("--knee", opt->knee, "The knee design (smallest sum of normalised objectives)");
  cmd->add_flag("--compromise", opt->compromise,
                "The design nearest the ideal point in normalised objectives");
  cmd->add_option("--out", opt->out, "The chosen design's machine file (default DIR/chosen.yaml)");
  cmd->callback([opt] { run_choose(*opt); });
}

}  // namespace pkmopt::cli
