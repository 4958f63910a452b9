// Tests of report/pareto_choice: the NAME=VALUE requests and their refusals, the rules applied
// with maximised objectives negated, infeasible designs left out, and the terminal text.
#include "report/pareto_choice.hpp"

#include <gtest/gtest.h>

#include <string>

#include "io/format/input_error.hpp"

namespace pkmopt {
namespace {

// stiffness_min (N/m, maximised) against tcp_deflection_max (m, minimised). In minimisation
// sign and normalised: a (0, 1), b (0.25, 0.25), c (1, 0); d would be best in both but is
// infeasible.
ParetoFront hand_front() {
  ParetoFront front;
  front.file = "res/pareto.json";
  front.study = "hand";
  front.objectives = {{"stiffness_min", "maximize", "N/m"},
                      {"tcp_deflection_max", "minimize", "m"}};
  auto design = [](const std::string& id, double k, double u, bool feasible) {
    ParetoDesign d;
    d.id = id;
    d.objectives = {k, u};
    d.feasible = feasible;
    return d;
  };
  front.designs = {design("a", 5e6, 5e-4, true), design("b", 4e6, 2e-4, true),
                   design("c", 1e6, 1e-4, true), design("d", 9e6, 1e-5, false)};
  return front;
}

std::string message(const ParetoFront& front, ChoiceRule rule, const std::string& text) {
  try {
    parse_choice_request(front, rule, text, "--opt");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ParetoChoice, RulesSeeMaximisedObjectivesNegated) {
  const ParetoFront front = hand_front();
  EXPECT_EQ(front.designs[choose_design(front, {ChoiceRule::kKnee, {}}).design].id, "b");
  EXPECT_EQ(front.designs[choose_design(front, {ChoiceRule::kCompromise, {}}).design].id, "b");
  const ChoiceRequest stiff =
      parse_choice_request(front, ChoiceRule::kWeights, "stiffness_min=1", "--w");
  EXPECT_EQ(stiff.values, (std::vector<double>{1.0, 0.0}));
  EXPECT_EQ(front.designs[choose_design(front, stiff).design].id, "a");
  const ChoiceRequest small =
      parse_choice_request(front, ChoiceRule::kWeights, " tcp_deflection_max = 3 ", "--w");
  EXPECT_EQ(front.designs[choose_design(front, small).design].id, "c");
  // A reference at c's values chooses c; one stiffer than a with b's deflection: the ray
  // from z^ = (-0.25, 0.25) along (1, 1) meets b's level first (max term 0.5 for b, 1.25 for c,
  // 0.75 for a).
  EXPECT_EQ(
      front
          .designs[choose_design(front, parse_choice_request(
                                            front, ChoiceRule::kReference,
                                            "stiffness_min=1e6,tcp_deflection_max=1e-4", "--r"))
                       .design]
          .id,
      "c");
  const DesignChoice z = choose_design(
      front, parse_choice_request(front, ChoiceRule::kReference,
                                  "tcp_deflection_max=2e-4,stiffness_min=6e6", "--r"));
  EXPECT_EQ(front.designs[z.design].id, "b");
  EXPECT_EQ(z.candidates, 3u);  // d is infeasible
  EXPECT_NEAR(z.normalised[0], 0.25, 1e-12);
  EXPECT_NEAR(z.normalised[1], 0.25, 1e-12);
  EXPECT_NEAR(z.pseudo_weights[0], 0.5, 1e-12);
}

TEST(ParetoChoice, RequestsAreCheckedWithOneMessage) {
  const ParetoFront front = hand_front();
  EXPECT_EQ(message(front, ChoiceRule::kWeights, "stiffness=1"),
            "--opt: expected an objective of the front (stiffness_min, tcp_deflection_max), "
            "found 'stiffness'");
  EXPECT_EQ(message(front, ChoiceRule::kWeights, "stiffness_min"),
            "--opt: expected NAME=VALUE items separated by commas, NAME one of stiffness_min, "
            "tcp_deflection_max, found 'stiffness_min'");
  EXPECT_EQ(message(front, ChoiceRule::kWeights, "stiffness_min=-2"),
            "--opt: stiffness_min: expected a weight >= 0, found '-2'");
  EXPECT_EQ(message(front, ChoiceRule::kWeights, "stiffness_min=2x"),
            "--opt: stiffness_min: expected a weight >= 0, found '2x'");
  EXPECT_EQ(message(front, ChoiceRule::kWeights, "stiffness_min=0,tcp_deflection_max=0"),
            "--opt: expected a weight above 0 for at least one objective, found "
            "'stiffness_min=0,tcp_deflection_max=0'");
  EXPECT_EQ(message(front, ChoiceRule::kReference, "stiffness_min=1e6"),
            "--opt: expected an aspiration level for every objective, found none for "
            "tcp_deflection_max");
  EXPECT_EQ(message(front, ChoiceRule::kReference, "stiffness_min=1e6,stiffness_min=2e6"),
            "--opt: expected each objective once, found 'stiffness_min' twice");
  EXPECT_NE(message(front, ChoiceRule::kReference, "stiffness_min=1e400,tcp_deflection_max=1")
                .find("expected a finite number within +-1e15"),
            std::string::npos);
  ParetoFront none = front;
  for (ParetoDesign& d : none.designs) d.feasible = false;
  try {
    choose_design(none, {ChoiceRule::kKnee, {}});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "res/pareto.json: designs: expected at least one feasible design to choose from, "
              "found only infeasible designs");
  }
}

TEST(ParetoChoice, TheTextShowsEngineeringUnits) {
  const ParetoFront front = hand_front();
  const ChoiceRequest request = parse_choice_request(
      front, ChoiceRule::kReference, "tcp_deflection_max=2e-4,stiffness_min=6e6", "--r");
  const DesignChoice choice = choose_design(front, request);
  const std::string text = choice_text(front, request, choice);
  EXPECT_EQ(text.rfind("choose: b, one of 3 feasible designs, by the achievement scalarizing "
                       "function of the reference point (stiffness_min 6 N/µm, "
                       "tcp_deflection_max 200 µm)\n",
                       0),
            0u)
      << text;
  EXPECT_NE(text.find("4 N/µm"), std::string::npos) << text;
  EXPECT_NE(text.find("200 µm"), std::string::npos) << text;
  const std::string yaml = chosen_machine_file(front, request, choice, "model: hexapod\n");
  EXPECT_EQ(yaml.substr(yaml.find('\n') + 1), "model: hexapod\n");
  EXPECT_EQ(yaml.rfind("# Design b of the study hand (res/pareto.json), chosen by", 0), 0u);
}

}  // namespace
}  // namespace pkmopt
