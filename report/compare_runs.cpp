// Comparing runs: reading the results folders, the shared objectives, the plotted pair, the
// hypervolumes in a common reference point and the notes for the reader.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "io/format/input_error.hpp"
#include "optimizer/indicators.hpp"
#include "report/compare_detail.hpp"
#include "report/compare_report.hpp"

namespace pkmopt {
namespace {

using detail::run_label;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool maximized(const ParetoObjective& o) { return o.sense == "maximize"; }

// "a, b, c" of a front's objective names.
std::string objective_names(const ParetoFront& front) {
  std::string out;
  for (const auto& o : front.objectives) out += (out.empty() ? "'" : ", '") + o.name + "'";
  return out;
}

}  // namespace

double RunComparison::value(std::size_t run, std::size_t design, std::size_t k) const {
  return runs[run].front.designs[design].objectives[runs[run].objective_index[k]];
}

RunComparison compare_runs(std::vector<ComparedRun> runs, const std::string& x_name,
                           const std::string& y_name) {
  if (runs.size() < 2) {
    throw InputError(
        fmt::format("compare: expected at least two results folders, found {}", runs.size()));
  }
  RunComparison c;
  c.runs = std::move(runs);
  for (ComparedRun& run : c.runs) {
    run.label = fmt::format("{} ({})", run.front.study, run.front.model);
  }
  for (ComparedRun& run : c.runs) {
    const auto same = std::count_if(c.runs.begin(), c.runs.end(), [&](const ComparedRun& other) {
      return other.front.study == run.front.study && other.front.model == run.front.model;
    });
    if (same > 1) run.label = fmt::format("{} ({}, {})", run.front.study, run.front.model, run.dir);
  }
  const ParetoFront& first = c.runs.front().front;
  // Shared objectives: the first run's objectives that every run has, with equal sense and unit.
  for (const ParetoObjective& o : first.objectives) {
    bool everywhere = true;
    for (const ComparedRun& run : c.runs) {
      const auto& list = run.front.objectives;
      const auto it = std::find_if(list.begin(), list.end(),
                                   [&](const ParetoObjective& p) { return p.name == o.name; });
      if (it == list.end()) {
        everywhere = false;
        break;
      }
      const std::string where =
          fmt::format("objectives[{}]", static_cast<std::size_t>(it - list.begin()));
      if (it->sense != o.sense) {
        throw InputError(fmt::format("{}: {}.sense: expected '{}' as in {}, found '{}'",
                                     run.front.file, where, o.sense, first.file, it->sense));
      }
      if (it->unit != o.unit) {
        throw InputError(fmt::format("{}: {}.unit: expected '{}' as in {}, found '{}'",
                                     run.front.file, where, o.unit, first.file, it->unit));
      }
    }
    if (everywhere) c.shared_objectives.push_back(o);
  }
  if (c.shared_objectives.size() < 2) {
    std::string lists;
    for (const ComparedRun& run : c.runs) {
      lists += fmt::format("{}{}: {}", lists.empty() ? "" : "; ", run.front.file,
                           objective_names(run.front));
    }
    throw InputError(fmt::format(
        "objectives: expected at least two objectives shared by every run, found {} ({})",
        c.shared_objectives.size(), lists));
  }
  for (ComparedRun& run : c.runs) {
    run.objective_index.clear();
    for (const ParetoObjective& o : c.shared_objectives) {
      for (std::size_t j = 0; j < run.front.objectives.size(); ++j) {
        if (run.front.objectives[j].name == o.name) run.objective_index.push_back(j);
      }
    }
  }

  // Plotted objectives.
  std::string shared_list;
  for (const auto& o : c.shared_objectives)
    shared_list += (shared_list.empty() ? "" : ", ") + o.name;
  auto find_shared = [&](const std::string& option, const std::string& name) {
    for (std::size_t k = 0; k < c.shared_objectives.size(); ++k) {
      if (c.shared_objectives[k].name == name) return k;
    }
    throw InputError(fmt::format("{}: expected an objective of every run ({}), found {}", option,
                                 shared_list, quote_found(name)));
  };
  const std::optional<std::size_t> x =
      x_name.empty() ? std::nullopt : std::optional(find_shared("--x", x_name));
  const std::optional<std::size_t> y =
      y_name.empty() ? std::nullopt : std::optional(find_shared("--y", y_name));
  if (x && y && *x == *y) {
    throw InputError(fmt::format("--y: expected an objective other than --x ({}), found {}", x_name,
                                 quote_found(y_name)));
  }
  c.x_objective = x ? *x : (y && *y == 0 ? 1 : 0);
  if (y) {
    c.y_objective = *y;
  } else {
    c.y_objective = c.x_objective == 0 ? 1 : 0;
  }

  // Counts, then the hypervolume against the reference point of the union (minimisation form).
  const std::size_t m = c.shared_objectives.size();
  std::vector<ObjectiveSet> minimised(c.runs.size());
  ObjectiveSet all;
  for (std::size_t r = 0; r < c.runs.size(); ++r) {
    ComparedRun& run = c.runs[r];
    run.feasible = run.shown = run.counted = 0;
    for (std::size_t d = 0; d < run.front.designs.size(); ++d) {
      const ParetoDesign& design = run.front.designs[d];
      run.feasible += design.feasible ? 1 : 0;
      if (std::isfinite(c.value(r, d, c.x_objective)) &&
          std::isfinite(c.value(r, d, c.y_objective))) {
        ++run.shown;
      }
      if (!design.feasible) continue;
      std::vector<double> f(m);
      bool finite = true;
      for (std::size_t k = 0; k < m; ++k) {
        const double v = c.value(r, d, k);
        finite = finite && std::isfinite(v);
        f[k] = maximized(c.shared_objectives[k]) ? -v : v;
      }
      if (!finite) continue;
      minimised[r].push_back(f);
      all.push_back(f);
    }
    run.counted = minimised[r].size();
  }
  if (all.empty()) {
    for (ComparedRun& run : c.runs) run.hypervolume = run.hypervolume_fraction = kNaN;
    c.notes.push_back(
        "No run has a feasible design with finite values of every shared objective, so no "
        "hypervolume is given.");
  } else {
    const std::vector<double> reference = reference_point_from(all);
    const std::vector<double> ideal = ideal_point(all);
    double box = 1.0;
    for (std::size_t k = 0; k < m; ++k) box *= reference[k] - ideal[k];
    for (std::size_t r = 0; r < c.runs.size(); ++r) {
      ComparedRun& run = c.runs[r];
      run.hypervolume = minimised[r].empty() ? 0.0 : hypervolume(minimised[r], reference);
      run.hypervolume_fraction = run.hypervolume / box;
      if (minimised[r].empty()) {
        c.notes.push_back(fmt::format(
            "{} has no feasible design with finite values of every shared objective: its "
            "hypervolume is 0.",
            run_label(run)));
      }
    }
    for (std::size_t k = 0; k < m; ++k) {
      const double sign = maximized(c.shared_objectives[k]) ? -1.0 : 1.0;
      c.reference_point.push_back(sign * reference[k]);
      c.ideal_point.push_back(sign * ideal[k]);
    }
  }

  // What a reader should know.
  for (std::size_t r = 1; r < c.runs.size(); ++r) {
    const ParetoTask &a = first.task, &b = c.runs[r].front.task;
    if (a.wrench != b.wrench || a.tilt_deg != b.tilt_deg || a.yaw_deg != b.yaw_deg) {
      c.notes.push_back(fmt::format(
          "The task of {} (wrench, tilt or yaw) differs from that of {}: see the task table.",
          run_label(c.runs[r]), run_label(c.runs.front())));
    }
  }
  for (const ComparedRun& run : c.runs) {
    if (run.front.objectives.size() > m) {
      std::string left_out;
      for (const auto& o : run.front.objectives) {
        const bool shared = std::any_of(c.shared_objectives.begin(), c.shared_objectives.end(),
                                        [&](const ParetoObjective& s) { return s.name == o.name; });
        if (!shared) left_out += (left_out.empty() ? "" : ", ") + o.name;
      }
      c.notes.push_back(fmt::format(
          "{} also optimised {}, which not every run has; it is left out of this comparison "
          "(its knee design was chosen with it).",
          run_label(run), left_out));
    }
  }
  return c;
}

RunComparison load_run_comparison(const std::vector<std::string>& dirs, const std::string& x_name,
                                  const std::string& y_name) {
  namespace fs = std::filesystem;
  if (dirs.size() < 2) {
    throw InputError(
        fmt::format("compare: expected at least two results folders, found {}", dirs.size()));
  }
  std::vector<ComparedRun> runs;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    const fs::path dir(dirs[i]);
    if (!fs::is_directory(dir)) {
      throw InputError(fmt::format("{}: expected a results folder of `pkmopt run`, found {}",
                                   dirs[i], fs::exists(dir) ? "a file" : "no such folder"));
    }
    for (std::size_t j = 0; j < i; ++j) {
      std::error_code error;
      if (fs::equivalent(dir, fs::path(dirs[j]), error)) {
        throw InputError(
            fmt::format("{}: expected a results folder not already given, found the "
                        "same folder as {}",
                        dirs[i], dirs[j]));
      }
    }
    const fs::path pareto = dir / "pareto.json";
    if (!fs::exists(pareto)) {
      throw InputError(fmt::format(
          "{}: expected the Pareto front of a design study (`pkmopt run` writes it), found no "
          "such file",
          pareto.string()));
    }
    ComparedRun run;
    run.dir = dirs[i];
    run.front = read_pareto_json(pareto.string());
    const fs::path summary_path = dir / "summary.json";
    if (fs::exists(summary_path)) {
      const std::string text = read_input_file(summary_path.string());
      const nlohmann::json summary = nlohmann::json::parse(text, nullptr, false);
      if (summary.is_discarded() || !summary.is_object()) {
        throw InputError(fmt::format("{}: expected a JSON object (the run's summary), found {}",
                                     summary_path.string(),
                                     summary.is_discarded() ? "a syntax error" : "another value"));
      }
      if (summary.contains("algorithm") && summary["algorithm"].is_string()) {
        run.algorithm = summary["algorithm"].get<std::string>();
      }
      if (summary.contains("evaluations") && summary["evaluations"].is_number()) {
        run.evaluations = summary["evaluations"].get<double>();
      }
    }
    runs.push_back(std::move(run));
  }
  return compare_runs(std::move(runs), x_name, y_name);
}

}  // namespace pkmopt
