// The page of an architecture synthesis (`pkmopt export DIR --format html` on a folder of a
// synthesis study, studies/synthesis_outputs.hpp): every structure's own front in one scatter,
// one colour and marker per structure with its knee design (the compare page of
// report/compare_report.hpp over DIR/candidates/NAME), then the candidates table (searched and
// dropped with why, generations, designs on the merged front and share, best value of each
// objective, binding constraints and bounds, or the failures of a structure without a feasible
// design), then a drawing of each structure's knee design (report/machine_drawing.hpp, at the
// model's drawing pose).
//
// Example:
//   const std::string html = pkmopt::synthesis_report_html("results/milling-synthesis");
#pragma once

#include <string>

namespace pkmopt {

/// True when DIR holds a synthesis run (DIR/candidates.json).
bool is_synthesis_folder(const std::string& dir);

/// The page (one self-contained HTML file). Throws InputError for a folder whose files cannot be
/// read.
std::string synthesis_report_html(const std::string& dir);

}  // namespace pkmopt
