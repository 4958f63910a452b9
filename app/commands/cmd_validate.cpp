// pkmopt validate STUDY.yaml: checks a design or benchmark study file without running it.
//
// Prints a short summary (free parameters, objectives, constraints, task poses, optimizer) and
// exits 0, or prints the exact error (file:line:col: key: expected X, found Y) and exits 2.
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "studies/benchmark_study.hpp"
#include "studies/design_study.hpp"
#include "studies/synthesis_run.hpp"
#include "studies/synthesis_study.hpp"

namespace pkmopt::cli {
namespace {

std::string optimizer_text(const OptimizerSpec& spec) {
  if (const Nsga2Options* nsga2 = spec.nsga2())
    return fmt::format("{} (population {}, generations {}, seed {}: {} evaluations)", spec.name(),
                       nsga2->population, nsga2->generations, spec.seed,
                       nsga2->population * (nsga2->generations + 1));
  if (const Nsga3Options* nsga3 = spec.nsga3()) {
    const std::string directions =
        nsga3->aspiration_points.empty()
            ? fmt::format("reference directions H = {}{}", nsga3->divisions,
                          nsga3->inner_divisions > 0
                              ? fmt::format(" and inner H = {}", nsga3->inner_divisions)
                              : "")
            : fmt::format("{} directions about {} aspiration point{} (spread {})",
                          nsga3_directions(*nsga3, nsga3->aspiration_points.front().size()).size(),
                          nsga3->aspiration_points.size(),
                          nsga3->aspiration_points.size() > 1 ? "s" : "", nsga3->aspiration_spread);
    return fmt::format("{} (population {}, generations {}, {}, seed {}: {} evaluations)",
                       spec.name(), nsga3->population, nsga3->generations, directions, spec.seed,
                       nsga3->population * (nsga3->generations + 1));
  }
  if (const MoeadOptions* moead = spec.moead())
    return fmt::format(
        "{} (weight vectors H = {}{}, {} neighbours, generations {}, seed {}: {} evaluations)",
        spec.name(), moead->divisions,
        moead->inner_divisions > 0 ? fmt::format(" and inner H = {}", moead->inner_divisions) : "",
        moead->neighbours, moead->generations, spec.seed, spec.expected_requests());
  return fmt::format("{} (seed {})", spec.name(), spec.seed);
}

std::string design_space_text(const DesignStudy& study) {
  std::string free, fixed;
  std::size_t n_free = 0;
  for (const StudyParameter& p : study.parameters) {
    if (p.free()) {
      ++n_free;
      free += fmt::format("\n    {:<30} {:>10.6g} .. {:<10.6g} {}", p.name, p.min, p.max, p.unit);
    } else {
      fixed += fmt::format("{}{} {:.6g} {}", fixed.empty() ? "" : ", ", p.name, p.min, p.unit);
    }
  }
  std::string text = fmt::format("  design space: {} free of {} parameters{}", n_free,
                                 study.parameters.size(), free);
  if (!fixed.empty()) text += "\n    fixed: " + fixed;
  return text + "\n";
}

std::string objectives_text(const DesignStudy& study) {
  std::string text = fmt::format("  objectives ({}):", study.objectives().size());
  for (const DesignObjective& o : study.objectives()) {
    const std::string_view unit = design_metric_unit(o.metric);
    text += fmt::format("\n    {} {} ({})", o.sense == Sense::maximize ? "maximize" : "minimize",
                        design_metric_name(o.metric), unit.empty() ? "dimensionless" : unit);
  }
  text += fmt::format("\n  constraints ({}):",
                      study.constraints().size() + (study.require_reachable() ? 1 : 0));
  if (study.require_reachable())
    text += "\n    task_reachable (every task pose within the strokes and joint limits)";
  for (const DesignConstraint& c : study.constraints()) {
    const std::string_view unit = design_metric_unit(c.metric);
    text += fmt::format("\n    {} {} {:.6g}{}{}", design_metric_name(c.metric),
                        c.relation == Relation::less_equal ? "<=" : ">=", c.bound,
                        unit.empty() ? "" : " ", unit);
  }
  if (const ActuatorCatalog* chosen = study.problem->actuator_catalog();
      chosen != nullptr && study.problem->prices_each_drive()) {
    text += fmt::format(
        "\n  drives: every drive priced from catalog '{}' ({} linear, {} rotary entries, by "
        "cost): the cheapest entry of its kind that carries it; alike drives (a parallel "
        "machine's legs) one entry",
        chosen->name, chosen->entries.size(), chosen->rotary_entries.size());
  } else if (const ActuatorCatalog* chosen = study.problem->actuator_catalog()) {
    const ActuatorCatalog& catalog = *chosen;
    text += fmt::format(
        "\n  actuators: each design's cheapest entry of catalog '{}' ({} entries, {}) that "
        "carries its legs",
        catalog.name, catalog.entries.size(),
        catalog.entries.front().cost ? "by cost" : "by force rating");
  }
  return text + "\n";
}

// The task as it will be computed: poses (count, extent of positions and angles, in the base
// frame before each design's home_height lift) and the wrench with its origin.
std::string task_text(const DesignStudy& study) {
  const DesignTask& task = study.task();
  const std::size_t poses = task.poses.size();
  std::string text = fmt::format(
      "  task: {} region centred at ({:.6g}, {:.6g}, {:.6g}) m; {} poses = {} positions x {} "
      "orientations (tilt <= {:.6g} deg, yaw +-{:.6g} deg)\n",
      study.task_region, study.task_centre[0], study.task_centre[1], study.task_centre[2], poses,
      study.task_positions, poses / std::max<std::size_t>(1, study.task_positions),
      study.task_tilt_deg, study.task_yaw_deg);
  if (poses > 0) {
    Eigen::Vector3d lo = task.poses[0].position, hi = lo;
    Eigen::Vector3d alo = rad_to_deg(task.poses[0].angles), ahi = alo;
    for (const Pose& p : task.poses) {
      lo = lo.cwiseMin(p.position);
      hi = hi.cwiseMax(p.position);
      alo = alo.cwiseMin(rad_to_deg(p.angles));
      ahi = ahi.cwiseMax(rad_to_deg(p.angles));
    }
    text += fmt::format(
        "    positions (base frame, before the home_height lift): x {:.6g} .. {:.6g}, y {:.6g} .. "
        "{:.6g}, z {:.6g} .. {:.6g} m\n    angles: rx {:.4g} .. {:.4g}, ry {:.4g} .. {:.4g}, rz "
        "{:.4g} .. {:.4g} deg\n",
        lo.x(), hi.x(), lo.y(), hi.y(), lo.z(), hi.z(), alo.x(), ahi.x(), alo.y(), ahi.y(), alo.z(),
        ahi.z());
  }
  const Wrench& w = task.wrench;
  text += study.task_wrench_origin.empty()
              ? std::string("    wrench: none (zero)\n")
              : fmt::format(
                    "    wrench at the TCP (base axes): force [{:.6g}, {:.6g}, {:.6g}] N, moment "
                    "[{:.6g}, {:.6g}, {:.6g}] N*m; {}\n",
                    w(0), w(1), w(2), w(3), w(4), w(5), study.task_wrench_origin);
  if (task.acceleration_max > 0.0)
    text += fmt::format("    a_max: {:.6g} m/s^2 (drives sized for it)\n", task.acceleration_max);
  return text;
}

// A synthesis: the task's motions, the candidates searched (with their design spaces) and those
// dropped (with why), and the budget's rounds.
std::string synthesis_text(const std::string& path, const SynthesisStudy& study) {
  const std::vector<std::size_t> searched = study.searched();
  std::string text = fmt::format(
      "{}: synthesis study '{}' is valid\n  task motion: {} ({})\n  candidates: {} searched, {} "
      "dropped\n",
      path, study.name, study.motion.type(), study.motion.words(), searched.size(),
      study.candidates.size() - searched.size());
  for (const SynthesisCandidate& c : study.candidates) {
    if (!c.searched) {
      text += fmt::format("    dropped  {} ({}): {}\n", c.name, c.structure, c.dropped);
      continue;
    }
    std::size_t free = 0;
    for (const StudyParameter& p : c.study->parameters) free += p.free() ? 1 : 0;
    text += fmt::format(
        "    search   {} ({}; {}): {} free parameters, task centre [{:.6g}, {:.6g}, {:.6g}] m; "
        "mobility: {}\n",
        c.name, c.structure, c.origin, free, c.task_centre[0], c.task_centre[1], c.task_centre[2],
        c.mobility);
  }
  const DesignStudy& first = *study.candidates[searched.front()].study;
  std::string task = task_text(first);
  if (task.starts_with("  task: "))
    task = fmt::format("  task (in the frame of {}): ", study.candidates[searched.front()].name) +
           task.substr(8);
  text += objectives_text(first) + task;
  const AllocationPlan plan = plan_allocation(searched.size(), study.nsga2.population,
                                              study.nsga2.generations, study.allocation);
  text += fmt::format(
      "  optimizer: nsga2 per structure, population {}, seed {}; budget {} evaluations ({} "
      "structures x {} x ({} + 1))\n  allocation: {}",
      study.nsga2.population, study.nsga2.seed, plan.budget, searched.size(),
      study.nsga2.population, study.nsga2.generations, study.allocation.rule);
  for (std::size_t r = 0; r < plan.structures.size(); ++r)
    text += fmt::format("{} round {}: {} structure(s) x {} generations", r == 0 ? ";" : ",", r + 1,
                        plan.structures[r], plan.generations[r]);
  return text + "\n";
}

void validate_study(const std::string& path) {
  if (const YamlValue root = YamlValue::load_file(path); is_synthesis_study(root)) {
    std::cout << synthesis_text(path, load_synthesis_study(root));
    return;
  }
  if (is_design_study_file(path)) {
    const DesignStudy study = load_design_study(path);
    std::string text =
        fmt::format("{}: design study '{}' (model {}) is valid\n", path, study.name, study.model);
    text += design_space_text(study) + objectives_text(study) + task_text(study);
    text += fmt::format("  optimizer: {}, {} formulation\n", optimizer_text(study.optimizer),
                        study.aggregate() ? "aggregate" : "smooth");
    if (study.front_size > 0)
      text += fmt::format("  front: thinned to {} designs\n", study.front_size);
    std::cout << text;
    return;
  }
  const BenchmarkStudy study = load_benchmark_study(path);
  std::cout << fmt::format(
      "{}: benchmark study '{}' is valid\n  problem: {} ({} variables, {} objectives, {} "
      "constraints)\n  optimizer: {}\n",
      path, study.name, study.problem->name(), study.problem->num_variables(),
      study.problem->num_objectives(), study.problem->num_constraints(),
      optimizer_text(study.optimizer));
}

}  // namespace

void add_validate_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd =
      app.add_subcommand("validate", "Check a study file (design or benchmark) without running it");
  cmd->add_option("study", *path, "Study file (YAML)")->required();
  cmd->callback([path] { validate_study(*path); });
}

}  // namespace pkmopt::cli
