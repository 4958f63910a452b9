// Shared by report/pareto_report.cpp (the plots) and report/pareto_report_html.cpp (the HTML
// report). Not part of the public interface: report/pareto_report.hpp is.
#pragma once

#include <string>
#include <string_view>

#include "io/results/pareto_json.hpp"

namespace pkmopt::report_detail {

/// {:.4g}.
std::string short_number(double v);
/// & < > " escaped.
std::string xml_escape(std::string_view text);
/// "name [unit] (max|min)".
std::string objective_label(const ParetoObjective& o);
/// The scatter of two objectives (inline SVG when not `standalone`), one element per design
/// with data-id.
std::string scatter_svg(const ParetoFront& front, int x_axis, int y_axis, bool standalone);
/// Parallel coordinates of every objective, best at the top, one polyline per design (data-id).
std::string parallel_svg(const ParetoFront& front);
/// The table of one design (parameters, objectives, constraints, actuator) in file units.
std::string knee_table(const ParetoFront& front, const ParetoDesign& d);

}  // namespace pkmopt::report_detail
