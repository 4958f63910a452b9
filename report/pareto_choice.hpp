// Choosing one design of a study's front (pareto.json) by a rule of optimizer/decision.hpp: the
// knee, the compromise (nearest the ideal point), Deb's pseudo-weights nearest a preference, or
// the achievement scalarizing function of a reference point. Only feasible designs are
// candidates; maximised objectives are negated for the rules, so every rule sees minimisation.
//
// Preferences and reference points are written as NAME=VALUE items separated by commas, NAME an
// objective of the front and VALUE in the file's units (pareto.json: N/m, m, m^3, N, ...):
//   weights:   "stiffness_min=2,workspace_volume=1"   (objectives left out weigh 0)
//   reference: "stiffness_min=4e6,workspace_volume=0.05,singularity_margin=0.1,leg_force_max=2e4"
//              (every objective, the aspiration level of each)
//
// Example:
//   const ParetoFront front = read_pareto_json("results/hexapod-milling/pareto.json");
//   const ChoiceRequest request = parse_choice_request(front, ChoiceRule::kWeights,
//                                                      "stiffness_min=2,workspace_volume=1");
//   const DesignChoice choice = choose_design(front, request);   // front.designs[choice.design]
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "io/results/pareto_json.hpp"

namespace pkmopt {

enum class ChoiceRule { kKnee, kCompromise, kWeights, kReference };

struct ChoiceRequest {
  ChoiceRule rule = ChoiceRule::kKnee;
  /// kWeights: preference per objective (>= 0); kReference: aspiration level per objective in
  /// file units; in the order of ParetoFront::objectives.
  std::vector<double> values;
};

/// Parses `text` (see header comment) for `rule` (kWeights or kReference). Throws InputError
/// "OPTION: expected ..., found ..." naming the objectives the front has.
ChoiceRequest parse_choice_request(const ParetoFront& front, ChoiceRule rule,
                                   const std::string& text, const std::string& option);

struct DesignChoice {
  std::size_t design = 0;              ///< index into front.designs
  std::size_t candidates = 0;          ///< feasible designs the rule chose among
  std::vector<double> pseudo_weights;  ///< of the chosen design, per objective
  std::vector<double> normalised;      ///< its f^ (0 best, 1 worst of the front)
  std::string rule_text;               ///< e.g. "knee (smallest sum of normalised values)"
};

/// The design `request` chooses. Throws InputError when the front has no feasible design.
DesignChoice choose_design(const ParetoFront& front, const ChoiceRequest& request);

/// What the terminal shows of a choice: the design, the rule and the preference or reference,
/// then one row per objective (value and reference in engineering units, normalised value,
/// pseudo-weight), e.g.
///   choose: d0012, one of 58 feasible designs, by the compromise (nearest the ideal point ...)
///     objective                 value           normalised  pseudo-weight
///     stiffness_min (max)       4.213 N/µm      0.118       0.312
std::string choice_text(const ParetoFront& front, const ChoiceRequest& request,
                        const DesignChoice& choice);

/// The chosen design's machine file `machine_yaml` with comment lines in front naming the study,
/// the design and the rule (the machine it describes is unchanged).
std::string chosen_machine_file(const ParetoFront& front, const ChoiceRequest& request,
                                const DesignChoice& choice, const std::string& machine_yaml);

}  // namespace pkmopt
