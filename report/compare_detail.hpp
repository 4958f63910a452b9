// Internal helpers shared by the comparison sources (report/compare_*.cpp). Not part of the
// public API.
#pragma once

#include <string>

#include "report/compare_report.hpp"

namespace pkmopt::detail {

inline const std::string& run_label(const ComparedRun& run) { return run.label; }

}  // namespace pkmopt::detail
