// The result files of an architecture synthesis (docs/design-studies.md, "Which structure"):
//
//   DIR/pareto.csv, pareto.json   the merged front: the feasible non-dominated designs of every
//                                 structure's evaluations, with their `architecture`, objectives
//                                 (the user's sign and units), constraint values, parameters and
//                                 machine file (format pkmopt-synthesis-front-1)
//   DIR/designs/<id>.yaml         each merged-front design's machine file
//   DIR/candidates.csv, .json     every candidate: searched or dropped (and why), its budget, its
//                                 share of the merged front, its best value of each objective,
//                                 its binding constraints with their margins, the design-space
//                                 bounds its front presses on, why its designs failed (with
//                                 counts), and its folder
//   DIR/summary.json              the run's facts and the allocation rounds
//   DIR/candidates/NAME/          each searched structure's own result folder, as a design study
//                                 writes it (pareto.csv, pareto.json, summary.json, designs/,
//                                 journal.txt, evaluations.csv, study.resolved.yaml: that study
//                                 alone, with the seed and generations this run gave it)
// All of them are written together (io/format/output_file.hpp): all or none.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "io/format/output_file.hpp"
#include "studies/journal.hpp"
#include "studies/synthesis_run.hpp"
#include "studies/synthesis_study.hpp"

namespace pkmopt {

struct SynthesisFacts {
  int threads = 0;
  bool resumed = false;
  double wall_seconds = 0.0;
  /// One per searched candidate, in study.searched() order.
  std::vector<const JournaledProblem*> journals;
};

struct SynthesisOutputSummary {
  std::size_t designs = 0;    ///< on the merged front
  std::string status;         ///< ok, or no_feasible_design
  std::string infeasibility;  ///< for an empty merged front: each structure's main causes
  std::string table;          ///< the candidates table for the terminal
};

/// Writes the files above into `directory`, with the files `also` names (all or none). Sets each
/// searched candidate's optimizer generations to those it ran (its study.resolved.yaml).
SynthesisOutputSummary write_synthesis_outputs(const std::string& directory, SynthesisStudy& study,
                                               const SynthesisSearch& search,
                                               const SynthesisFacts& facts,
                                               const OutputFiles& also = {});

}  // namespace pkmopt
