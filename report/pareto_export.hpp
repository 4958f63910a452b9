// The files of `pkmopt export` (docs/export.md): a design study's Pareto front (DIR/pareto.json
// of `pkmopt run`, read by io/results/pareto_json.hpp) rendered as one output file and, optionally,
// plots.
//
//   csv    pareto_csv (io/results/pareto_json.hpp), default name pareto_export.csv
//   json   pareto_json, the front normalised, default name pareto_export.json
//   html   report_html (report/pareto_report.hpp) with the knee design's workspace slice,
//          default name report.html; always comes with the plots
//   plots  pareto.svg and pareto.png (the first two objectives) and, when the knee design has a
//          machine file, knee_slice.svg and knee_slice.png (coloured by singularity_margin; the
//          slice is described in report/pareto_report.hpp)
// Units are those of pareto.json. Everything is rendered in memory; the caller writes the files
// (io/format/output_file.hpp) once the last one is rendered, so an error writes nothing.
//
// Example:
//   const ParetoFront front = read_pareto_json("results/pareto.json");
//   for (const auto& [path, bytes] : pareto_export_files(front, "results", ExportFormat::kHtml,
//                                                        "results/report.html", "results", true))
//     write_file_atomically(path.string(), bytes);
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/results/pareto_json.hpp"

namespace pkmopt {

enum class ExportFormat { kCsv, kJson, kHtml };

/// "csv", "json" or "html"; nullopt otherwise.
std::optional<ExportFormat> parse_export_format(std::string_view name);

/// The output file's name when none is given: pareto_export.csv, pareto_export.json, report.html.
std::string default_export_name(ExportFormat format);

/// How `--format csv --units` labels the columns: not at all (the file's SI units, headers
/// unit-free as docs/conventions.md has them), a second row of units, or the unit in each
/// header (`base_radius [mm]`); labelled columns hold engineering units
/// (report/display_units.hpp: mm, µm, N/µm, l, kN, deg).
enum class CsvUnits { kNone, kRow, kSuffix };

/// "row" or "suffix"; nullopt otherwise.
std::optional<CsvUnits> parse_csv_units(std::string_view name);

/// pareto_csv (io/results/pareto_json.hpp) in engineering units with the units as `units` says
/// (kNone: pareto_csv itself).
std::string pareto_csv_with_units(const ParetoFront& front, CsvUnits units);

/// The files of an export of `front` (read from the results folder `results_dir`, where the
/// knee design's machine file is) as (path, bytes): first `out_file` in `format`, then, when
/// `plots` or the format is html, the plot files in `plot_dir`. Throws InputError when the knee
/// design's machine file cannot be read.
std::vector<std::pair<std::filesystem::path, std::string>> pareto_export_files(
    const ParetoFront& front, const std::string& results_dir, ExportFormat format,
    const std::filesystem::path& out_file, const std::filesystem::path& plot_dir, bool plots,
    CsvUnits csv_units = CsvUnits::kNone);

}  // namespace pkmopt
