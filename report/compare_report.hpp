// Comparing the Pareto fronts of several design studies (`pkmopt compare`): e.g. the same
// 300 x 300 x 200 mm task solved for a hexapod, a hexaglide and a linear delta.
//
// Each run is a results folder of `pkmopt run` (DIR/pareto.json, format pkmopt-pareto-1, and
// optionally DIR/summary.json). The runs are compared on the objectives they all have
// ("shared objectives": same name, same sense and same unit in every run, in the order of the
// first run). Values are in the user's sign and units, as in pareto.json (a maximised metric is
// its positive value).
//
// Hypervolume in a common reference: every run is measured against the same reference point,
// built from the union U of the feasible designs of all runs with finite values of every shared
// objective. In minimisation form (f = -value for a maximised objective, f = value otherwise):
//   ideal_i     = min_{u in U} f_i(u),   nadir_i = max_{u in U} f_i(u)
//   reference_i = nadir_i + 0.1 (nadir_i - ideal_i)          (a range of 0 counts as 1)
//   HV(run)     = hypervolume of the run's feasible designs up to the reference
//                 (optimizer/indicators.hpp; units: the product of the shared objectives' units)
//   HV fraction = HV(run) / prod_i (reference_i - ideal_i)    (0..1, unitless)
// A larger hypervolume is better; only feasible designs count (infeasible ones are plotted).
// The reference and ideal points are reported in user sign.
//
//   std::vector<std::string> dirs{"results/hexapod", "results/hexaglide"};
//   const pkmopt::RunComparison comparison = pkmopt::load_run_comparison(dirs, "", "");
//   const std::string html = pkmopt::comparison_html(comparison);
//   const std::string png = pkmopt::comparison_plot_png(comparison);
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "report/pareto_report.hpp"

namespace pkmopt {

/// One results folder in a comparison.
struct ComparedRun {
  std::string dir;  ///< the results folder as given
  /// "study (model)" in the legend and tables; "study (model, DIR)" when two runs would
  /// otherwise have the same label (set by compare_runs).
  std::string label;
  ParetoFront front;                     ///< its pareto.json
  std::optional<std::string> algorithm;  ///< from summary.json, when present
  std::optional<double> evaluations;     ///< from summary.json, when present
  /// objective_index[k]: index in front.objectives of shared objective k.
  std::vector<std::size_t> objective_index;
  std::size_t feasible = 0;  ///< feasible designs
  std::size_t shown = 0;     ///< designs with finite values on both plotted axes
  std::size_t counted = 0;   ///< feasible designs with finite shared objectives (in the HV)
  double hypervolume = 0.0;  ///< see the header comment; NaN when no reference point
  double hypervolume_fraction = 0.0;  ///< HV / volume of [ideal, reference]; NaN likewise
};

/// Several runs compared on their shared objectives.
struct RunComparison {
  std::vector<ComparedRun> runs;
  std::vector<ParetoObjective> shared_objectives;  ///< in the order of the first run
  std::size_t x_objective = 0, y_objective = 1;    ///< indices into shared_objectives
  /// Common reference and ideal points (user sign, one per shared objective); empty when no
  /// run has a feasible design with finite shared objectives.
  std::vector<double> reference_point, ideal_point;
  /// Things a reader should know (tasks that differ, ...), one sentence each.
  std::vector<std::string> notes;

  /// Value of shared objective k of design d of run r (user sign and units).
  double value(std::size_t run, std::size_t design, std::size_t k) const;
};

/// Compares already-read fronts (`dirs[i]` is the folder of `fronts[i]`, for messages and
/// labels). `x_name`/`y_name` choose the plotted objectives by name ("" = the first shared
/// objectives not otherwise chosen). Throws InputError when there are fewer than two runs, a
/// shared name has a different sense or unit in two runs, fewer than two objectives are shared,
/// or `x_name`/`y_name` is not a shared objective or both are the same.
RunComparison compare_runs(std::vector<ComparedRun> runs, const std::string& x_name,
                           const std::string& y_name);

/// Reads DIR/pareto.json (and DIR/summary.json when present) of every folder and compares them.
/// Throws InputError naming the folder or file and key on any problem.
RunComparison load_run_comparison(const std::vector<std::string>& dirs, const std::string& x_name,
                                  const std::string& y_name);

/// One self-contained HTML page (inline SVG, CSS and JavaScript; no URL): the fronts of every
/// run in the same axes (one colour and marker per run, legend "study (model)", infeasible
/// designs open, knee designs enlarged with a black outline; hover shows a design, clicking a
/// legend entry hides or shows its run), a table per run (folder, model, designs, feasible
/// designs, hypervolume and its fraction, knee design and its objective values) and each run's
/// knee design table (parameters, objectives, constraints).
std::string comparison_html(const RunComparison& comparison);

/// The scatter alone: standalone SVG file and 8-bit RGB PNG.
std::string comparison_plot_svg(const RunComparison& comparison);
std::string comparison_plot_png(const RunComparison& comparison);

}  // namespace pkmopt
