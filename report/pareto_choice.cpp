#include "report/pareto_choice.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string_view>

#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"
#include "optimizer/decision.hpp"
#include "report/display_units.hpp"
#include "report/pareto_report_detail.hpp"

namespace pkmopt {
namespace {

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::string objective_names(const ParetoFront& front) {
  std::string names;
  for (const ParetoObjective& o : front.objectives) names += (names.empty() ? "" : ", ") + o.name;
  return names;
}

double sense_sign(const ParetoObjective& o) { return o.sense == "maximize" ? -1.0 : 1.0; }

}  // namespace

ChoiceRequest parse_choice_request(const ParetoFront& front, ChoiceRule rule,
                                   const std::string& text, const std::string& option) {
  const bool weights = rule == ChoiceRule::kWeights;
  const std::string item_text =
      fmt::format("NAME=VALUE items separated by commas, NAME one of {}", objective_names(front));
  ChoiceRequest request{rule, std::vector<double>(front.objectives.size(), NAN)};
  std::string_view rest = text;
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = trimmed(rest.substr(0, comma));
    const std::size_t equals = item.find('=');
    if (equals == std::string_view::npos)
      throw InputError(fmt::format("{}: expected {}, found {}", option, item_text,
                                   quote_found(std::string(item))));
    const std::string name(trimmed(item.substr(0, equals)));
    const std::string value_text(trimmed(item.substr(equals + 1)));
    std::size_t k = 0;
    while (k < front.objectives.size() && front.objectives[k].name != name) ++k;
    if (k == front.objectives.size())
      throw InputError(fmt::format("{}: expected an objective of the front ({}), found {}", option,
                                   objective_names(front), quote_found(name)));
    if (!std::isnan(request.values[k]))
      throw InputError(fmt::format("{}: expected each objective once, found {} twice", option,
                                   quote_found(name)));
    char* end = nullptr;
    const double value = read_input_number(value_text.c_str(), &end);
    const bool number = !value_text.empty() && end == value_text.c_str() + value_text.size();
    if (!number || !sane_input_number(value) || (weights && value < 0.0))
      throw InputError(fmt::format("{}: {}: expected {}, found {}", option, name,
                                   weights ? "a weight >= 0" : std::string(kSaneNumberText),
                                   quote_found(value_text)));
    request.values[k] = value;
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  std::string missing;
  for (std::size_t k = 0; k < front.objectives.size(); ++k) {
    if (!std::isnan(request.values[k])) continue;
    if (weights) {
      request.values[k] = 0.0;
    } else {
      missing += (missing.empty() ? "" : ", ") + front.objectives[k].name;
    }
  }
  if (!missing.empty())
    throw InputError(
        fmt::format("{}: expected an aspiration level for every objective, found none for {}",
                    option, missing));
  if (weights) {
    double total = 0.0;
    for (double w : request.values) total += w;
    if (!(total > 0.0))
      throw InputError(
          fmt::format("{}: expected a weight above 0 for at least one objective, "
                      "found {}",
                      option, quote_found(text)));
  }
  return request;
}

DesignChoice choose_design(const ParetoFront& front, const ChoiceRequest& request) {
  const std::size_t m = front.objectives.size();
  std::vector<std::size_t> candidates;
  ObjectiveSet objectives;
  for (std::size_t d = 0; d < front.designs.size(); ++d) {
    const ParetoDesign& design = front.designs[d];
    bool finite = design.feasible && design.objectives.size() == m;
    for (std::size_t k = 0; finite && k < m; ++k) finite = std::isfinite(design.objectives[k]);
    if (!finite) continue;
    candidates.push_back(d);
    std::vector<double> f(m);
    for (std::size_t k = 0; k < m; ++k)
      f[k] = sense_sign(front.objectives[k]) * design.objectives[k];
    objectives.push_back(std::move(f));
  }
  if (candidates.empty())
    throw InputError(
        fmt::format("{}: designs: expected at least one feasible design to choose "
                    "from, found {}",
                    front.file, front.designs.empty() ? "none" : "only infeasible designs"));
  DesignChoice choice;
  choice.candidates = candidates.size();
  std::size_t k = 0;
  switch (request.rule) {
    case ChoiceRule::kKnee:
      k = knee_point(objectives);
      choice.rule_text = "the knee (smallest sum of normalised objective values)";
      break;
    case ChoiceRule::kCompromise:
      k = compromise_point(objectives);
      choice.rule_text = "the compromise (nearest the ideal point in normalised units)";
      break;
    case ChoiceRule::kWeights:
      k = choose_by_weights(objectives, request.values);
      choice.rule_text = "pseudo-weights nearest the preference";
      break;
    case ChoiceRule::kReference: {
      std::vector<double> reference(m);
      for (std::size_t i = 0; i < m; ++i)
        reference[i] = sense_sign(front.objectives[i]) * request.values[i];
      k = choose_by_reference(objectives, reference);
      choice.rule_text = "the achievement scalarizing function of the reference point";
      break;
    }
  }
  choice.design = candidates[k];
  choice.pseudo_weights = pseudo_weights(objectives)[k];
  choice.normalised = front_scale(objectives).normalised(objectives[k]);
  return choice;
}

namespace {

// "stiffness_min 0.67, workspace_volume 0.33" or "stiffness_min 4 N/µm, ..." (display units).
std::string request_text(const ParetoFront& front, const ChoiceRequest& request) {
  std::string text;
  if (request.rule == ChoiceRule::kWeights) {
    double total = 0.0;
    for (double w : request.values) total += w;
    for (std::size_t k = 0; k < front.objectives.size(); ++k)
      text += fmt::format("{}{} {}", text.empty() ? "" : ", ", front.objectives[k].name,
                          report_detail::short_number(request.values[k] / total));
  } else if (request.rule == ChoiceRule::kReference) {
    for (std::size_t k = 0; k < front.objectives.size(); ++k) {
      const ParetoObjective& o = front.objectives[k];
      const EngineeringUnit e = engineering_unit(o.name, o.unit);
      text += fmt::format("{}{} {}{}", text.empty() ? "" : ", ", o.name,
                          report_detail::short_number(e.scale * request.values[k]),
                          e.unit.empty() ? "" : " " + e.unit);
    }
  }
  return text;
}

}  // namespace

std::string choice_text(const ParetoFront& front, const ChoiceRequest& request,
                        const DesignChoice& choice) {
  const ParetoDesign& d = front.designs[choice.design];
  const std::string preference = request_text(front, request);
  std::string out =
      fmt::format("choose: {}, one of {} feasible designs, by {}{}\n", d.id, choice.candidates,
                  choice.rule_text, preference.empty() ? "" : " (" + preference + ")");
  out += fmt::format("  {:<30} {:>16}  {:>10}  {:>13}\n", "objective", "value", "normalised",
                     "pseudo-weight");
  for (std::size_t k = 0; k < front.objectives.size(); ++k) {
    const ParetoObjective& o = front.objectives[k];
    const EngineeringUnit e = engineering_unit(o.name, o.unit);
    const std::string value = report_detail::short_number(e.scale * d.objectives[k]) +
                              (e.unit.empty() ? "" : " " + e.unit);
    out += fmt::format("  {:<30} {:>16}  {:>10.3f}  {:>13.3f}\n",
                       o.name + (o.sense == "maximize" ? " (max)" : " (min)"), value,
                       choice.normalised[k], choice.pseudo_weights[k]);
  }
  return out;
}

std::string chosen_machine_file(const ParetoFront& front, const ChoiceRequest& request,
                                const DesignChoice& choice, const std::string& machine_yaml) {
  const std::string preference = request_text(front, request);
  return fmt::format(
      "# Design {} of the study {} ({}), chosen by {}{} among {} feasible designs "
      "(pkmopt choose).\n{}",
      front.designs[choice.design].id, front.study, front.file, choice.rule_text,
      preference.empty() ? "" : " (" + preference + ")", choice.candidates, machine_yaml);
}

}  // namespace pkmopt
