// Reports of a design study's results (`pkmopt export`): the Pareto front of DIR/pareto.json
// (read by io/results/pareto_json.hpp) as Pareto plots (SVG, PNG) and one self-contained HTML
// report.
//
// Units are those of pareto.json: parameters in file units (m, degrees for *_deg), objectives
// in the user's sign and units (N/m, m^3, N, ...), constraint values g in metric units with
// g <= 0 satisfied. A non-finite value (null in pareto.json) is NaN in memory, null in JSON, an
// empty cell in CSV, and is left out of the plots.
//
// The knee design's workspace slice: its machine file (designs/<id>.yaml, in the machine's base
// frame) is cut by the plane z = task.centre[2] + home_height (the task centre's height in that
// frame) at constant orientation R = I (rx = ry = rz = 0), coloured by singularity_margin, with
// the task wrench used for max_leg_force.
//
//   const pkmopt::ParetoFront front = pkmopt::read_pareto_json("results/pareto.json");
//   const std::string svg = pkmopt::pareto_plot_svg(front);
//   const auto slice = pkmopt::knee_workspace_slice(front, "results");
//   const std::string html = pkmopt::report_html(front, slice ? &*slice : nullptr);
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/results/pareto_json.hpp"
#include "models/workspace/workspace.hpp"

namespace pkmopt {

/// Scatter plot of objective `x_objective` against `y_objective` (feasible designs filled,
/// infeasible ones as rings, the knee red); axes named with unit and sense, with ticks.
/// Standalone SVG file (with its xmlns) and 8-bit RGB PNG.
std::string pareto_plot_svg(const ParetoFront& front, int x_objective = 0, int y_objective = 1);
std::string pareto_plot_png(const ParetoFront& front, int x_objective = 0, int y_objective = 1);

/// The knee design's workspace slice (see the header comment), or nullopt when there is no knee
/// or it has no machine file. Throws InputError if the machine file cannot be read.
/// `pixels` is the number of pixels along the longer side.
std::optional<WorkspaceSlice> knee_workspace_slice(const ParetoFront& front,
                                                   const std::string& results_dir,
                                                   int pixels = 160);

/// Every design with a machine file drawn at the task centre (R = I, lifted by its home_height),
/// all at one scale with its task box (report/machine_drawing.hpp): id -> inline SVG. Designs
/// whose file cannot be read or whose legs cannot assemble there are left out. Throws nothing
/// for a missing file: the report says which designs have no drawing.
std::map<std::string, std::string> design_drawings(const ParetoFront& front,
                                                   const std::string& results_dir);

/// The hypervolume of the run's non-dominated feasible designs against the evaluations made
/// (pareto.json "convergence"), as an inline SVG line plot; empty when the front has none.
std::string convergence_svg(const ParetoFront& front);

/// The knee in words for the report: what the knee of this front is (the design with the
/// smallest sum of objectives scaled 0..1 between the front's best and worst values, Das 1999)
/// and how pronounced it is (its distance below the plane through the scaled extremes).
std::string knee_text(const ParetoFront& front);

/// The self-contained HTML report: no external scripts, fonts, styles or URLs. In engineering
/// units (report/display_units.hpp), numbers to 5 significant digits: the Pareto scatter with the
/// pair of objectives chosen on the page, the parallel coordinates of three or more objectives,
/// click to pin 2-4 designs and compare them side by side (parameters with bounds flagged,
/// objectives, constraints, the machine drawn from `drawings`), the knee design with its
/// workspace slice (task box and colour bar) when `knee_slice` is given, the convergence plot,
/// the sortable and filterable table of every design, the study's settings.
std::string report_html(const ParetoFront& front, const WorkspaceSlice* knee_slice,
                        const std::map<std::string, std::string>& drawings = {});

/// Base64 (RFC 4648, with padding).
std::string base64(const std::string& bytes);

/// Helpers shared with other HTML/SVG writers (`pkmopt compare`): text with & < > " escaped for
/// HTML and XML; an objective's axis label "name [unit] (max|min)"; the HTML table of one
/// design's free and fixed parameters, objectives and constraints (as in the export report's
/// knee section).
std::string html_escape(std::string_view text);
std::string objective_axis_label(const ParetoObjective& objective);
std::string design_table_html(const ParetoFront& front, const ParetoDesign& design);

}  // namespace pkmopt
