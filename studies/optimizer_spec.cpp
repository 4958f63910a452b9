#include "studies/optimizer_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "optimizer/anchors.hpp"
#include "studies/optimizer_fields.hpp"

namespace pkmopt {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

std::size_t read_count(const YamlValue& value, long long minimum) {
  const long long n = value.as_int();
  if (n < minimum) value.fail(fmt::format("an integer >= {}", minimum), value.describe());
  return static_cast<std::size_t>(n);
}

std::vector<double> read_start(const YamlValue& section, const Problem& problem) {
  auto v = section.optional("start");
  if (!v) return {};
  std::vector<double> start = v->as_doubles(static_cast<int>(problem.num_variables()));
  const Bounds bounds = problem.bounds();
  for (std::size_t j = 0; j < start.size(); ++j)
    if (start[j] < bounds.lower[j] || start[j] > bounds.upper[j])
      v->fail(fmt::format("start values within the bounds (variable {} in [{}, {}])", j + 1,
                          bounds.lower[j], bounds.upper[j]),
              format_number(start[j]));
  return start;
}

// Reads an algorithm's keys (its field list, studies/optimizer_fields.hpp); the keys checked
// against the list, `algorithm` and `seed` beforehand.
template <class Spec>
Spec read_spec(const YamlValue& section) {
  Spec spec;
  FieldReader reader(section);
  describe_fields(reader, spec);
  return spec;
}

// Ipopt's acceptable tolerance is never tighter than the tolerance asked for.
void keep_acceptable_tolerance(IpoptOptions& options) {
  options.acceptable_tolerance = std::max(options.acceptable_tolerance, options.tolerance);
}

// nsga3's `aspiration`: a list of points, each a list of M numbers in objective order or a map
// naming every objective; returned in the objectives' own sense.
std::vector<std::vector<double>> read_aspiration(const YamlValue& value, std::size_t m,
                                                 const ObjectiveNaming& objectives) {
  std::vector<std::vector<double>> points;
  const std::string names = [&] {
    std::string text;
    for (const std::string& n : objectives.names) text += (text.empty() ? "" : ", ") + n;
    return text;
  }();
  const std::string expected =
      objectives.names.empty()
          ? fmt::format("a list of {} numbers (one per objective)", m)
          : fmt::format(
                "a map of every objective ({}) to its aspiration level, or a list of {} "
                "numbers in that order",
                names, m);
  if (!value.is_sequence() || value.elements().empty())
    value.fail("a list of aspiration points, each " + expected, value.describe());
  for (const YamlValue& point : value.elements()) {
    if (point.is_sequence()) {
      points.push_back(point.as_doubles(static_cast<int>(m)));
      continue;
    }
    if (!point.is_map() || objectives.names.empty()) point.fail(expected, point.describe());
    std::vector<std::string> allowed(objectives.names.begin(), objectives.names.end());
    point.check_keys(allowed);
    std::vector<double> z;
    for (const std::string& name : objectives.names) z.push_back(point.required(name).as_double());
    points.push_back(std::move(z));
  }
  return points;
}

AlgorithmSpec read_algorithm(const std::string& name, const YamlValue& s, const Problem& problem,
                             std::uint64_t seed, std::optional<std::string>& unsupported,
                             const ObjectiveNaming& objectives) {
  if (name == "nsga2") {
    unsupported = nsga2_explain_unsupported(problem);
    Nsga2Spec spec = read_spec<Nsga2Spec>(s);
    spec.options.seed = seed;
    return spec;
  }
  if (name == "nsga3") {
    unsupported = nsga2_explain_unsupported(problem);
    Nsga3Spec spec = read_spec<Nsga3Spec>(s);
    spec.options.seed = seed;
    if (auto v = s.optional("aspiration")) {
      const std::size_t m = problem.num_objectives();
      spec.aspiration = read_aspiration(*v, m, objectives);
      spec.options.aspiration_points = spec.aspiration;
      for (auto& z : spec.options.aspiration_points)
        for (std::size_t i = 0; i < m && i < objectives.maximize.size(); ++i)
          if (objectives.maximize[i]) z[i] = -z[i];
    } else {
      for (const char* key : {"aspiration_divisions", "aspiration_spread"})
        if (auto v = s.optional(key))
          v->fail("`aspiration` points beside it (it shapes the directions around them)",
                  "no aspiration");
    }
    if (spec.options.population == 0) {  // the directions' count rounded up to a multiple of 4
      std::size_t directions = 0;
      try {
        directions = nsga3_directions(spec.options, problem.num_objectives()).size();
      } catch (const std::invalid_argument& e) {
        s.required("divisions").fail("fewer reference directions", e.what());
      }
      spec.options.population = (directions + 3) / 4 * 4;
    }
    return spec;
  }
  if (name == "moead") {
    unsupported = nsga2_explain_unsupported(problem);
    MoeadSpec spec = read_spec<MoeadSpec>(s);
    spec.options.seed = seed;
    try {
      spec.population = moead_weights(spec.options, problem.num_objectives()).size();
    } catch (const std::invalid_argument& e) {
      s.required("divisions").fail("fewer weight vectors", e.what());
    }
    if (spec.population < 3) {
      const auto key = s.optional("divisions");
      (key ? *key : s)
          .fail("at least 3 weight vectors (one member each)",
                fmt::format("{} for this number of objectives", spec.population));
    }
    return spec;
  }
  if (name == "hybrid") {
    unsupported = nsga2_explain_unsupported(problem);
    if (!unsupported && problem.num_objectives() < 2)
      unsupported = fmt::format("hybrid builds fronts, but '{}' has one objective (use ipopt)",
                                problem.name());
    HybridSpec spec = read_spec<HybridSpec>(s);
    spec.options.nsga2.seed = seed;
    return spec;
  }
  if (name == "epsilon_constraint") {
    EpsilonConstraintSpec spec = read_spec<EpsilonConstraintSpec>(s);
    if (auto v = s.optional("primary_objective");
        v && spec.options.primary_objective >= problem.num_objectives())
      v->fail(fmt::format("an objective number from 1 to {}", problem.num_objectives()),
              v->describe());
    keep_acceptable_tolerance(spec.options.ipopt);
    spec.options.start = read_start(s, problem);
    unsupported = epsilon_constraint_explain_unsupported(problem, spec.options);
    return spec;
  }
  if (name == "nbi") {
    NbiSpec spec = read_spec<NbiSpec>(s);
    keep_acceptable_tolerance(spec.options.ipopt);
    spec.options.start = read_start(s, problem);
    unsupported = nbi_explain_unsupported(problem, spec.options);
    return spec;
  }
  if (name == "ipopt") {
    unsupported = ipopt_explain_unsupported(problem);
    IpoptSpec spec = read_spec<IpoptSpec>(s);
    keep_acceptable_tolerance(spec.options);
    spec.start = read_start(s, problem);
    return spec;
  }
  NloptSpec spec = read_spec<NloptSpec>(s);
  spec.options.algorithm = name.substr(6);
  spec.options.seed = seed;
  spec.start = read_start(s, problem);
  unsupported = nlopt_explain_unsupported(problem, spec.options);
  return spec;
}

// The keys of an algorithm's field list.
template <class Spec>
std::vector<std::string> spec_keys() {
  FieldKeys keys;
  Spec spec;
  describe_fields(keys, spec);
  return keys.keys;
}

}  // namespace

std::string OptimizerSpec::name() const {
  return std::visit(
      Overloaded{[](const Nsga2Spec&) { return std::string("nsga2"); },
                 [](const Nsga3Spec&) { return std::string("nsga3"); },
                 [](const MoeadSpec&) { return std::string("moead"); },
                 [](const HybridSpec&) { return std::string("hybrid"); },
                 [](const EpsilonConstraintSpec&) { return std::string("epsilon_constraint"); },
                 [](const NbiSpec&) { return std::string("nbi"); },
                 [](const IpoptSpec&) { return std::string("ipopt"); },
                 [](const NloptSpec& s) { return "nlopt:" + s.options.algorithm; }},
      algorithm);
}

const Nsga2Options* OptimizerSpec::nsga2() const {
  if (const auto* s = std::get_if<Nsga2Spec>(&algorithm)) return &s->options;
  if (const auto* s = std::get_if<HybridSpec>(&algorithm)) return &s->options.nsga2;
  return nullptr;
}

const Nsga3Options* OptimizerSpec::nsga3() const {
  if (const auto* s = std::get_if<Nsga3Spec>(&algorithm)) return &s->options;
  return nullptr;
}

const MoeadOptions* OptimizerSpec::moead() const {
  if (const auto* s = std::get_if<MoeadSpec>(&algorithm)) return &s->options;
  return nullptr;
}

long long OptimizerSpec::expected_requests() const {
  if (const auto* s = std::get_if<Nsga2Spec>(&algorithm))
    return static_cast<long long>(s->options.population * (s->options.generations + 1));
  if (const auto* s = std::get_if<Nsga3Spec>(&algorithm))
    return static_cast<long long>(s->options.population * (s->options.generations + 1));
  if (const auto* s = std::get_if<MoeadSpec>(&algorithm))
    return static_cast<long long>(s->population * (s->options.generations + 1));
  return 0;
}

OptimizerSpec read_optimizer_section(const YamlValue& section, const Problem& problem,
                                     const ObjectiveNaming& objectives) {
  section.expect_map();
  OptimizerSpec spec;
  const YamlValue algorithm = section.required("algorithm");
  const std::string name = algorithm.as_string();
  std::vector<std::string> allowed;
  if (name == "nsga2") {
    allowed = spec_keys<Nsga2Spec>();
  } else if (name == "nsga3") {
    allowed = spec_keys<Nsga3Spec>();
    allowed.push_back("aspiration");
  } else if (name == "moead") {
    allowed = spec_keys<MoeadSpec>();
  } else if (name == "hybrid") {
    allowed = spec_keys<HybridSpec>();
  } else if (name == "epsilon_constraint") {
    allowed = spec_keys<EpsilonConstraintSpec>();
  } else if (name == "nbi") {
    allowed = spec_keys<NbiSpec>();
  } else if (name == "ipopt") {
    allowed = spec_keys<IpoptSpec>();
  } else if (name.starts_with("nlopt:")) {
    allowed = spec_keys<NloptSpec>();
  } else {
    algorithm.fail(
        "one of nsga2, nsga3, moead, epsilon_constraint, nbi, hybrid, ipopt, nlopt:<ALGORITHM>",
        quote_found(name));
  }
  allowed.insert(allowed.begin(), {"algorithm", "seed"});
  section.check_keys(allowed);
  if (auto v = section.optional("seed")) spec.seed = static_cast<std::uint64_t>(read_count(*v, 0));
  std::optional<std::string> unsupported;
  spec.algorithm = read_algorithm(name, section, problem, spec.seed, unsupported, objectives);
  if (unsupported) algorithm.fail(*unsupported);
  return spec;
}

std::string optimizer_section_yaml(const OptimizerSpec& spec) {
  const std::string name = spec.name();
  FieldWriter writer;
  std::visit([&](auto algorithm_spec) { describe_fields(writer, algorithm_spec); }, spec.algorithm);
  std::string text = "algorithm: " + (name.starts_with("nlopt:") ? "\"" + name + "\"" : name) +
                     fmt::format(", seed: {}", spec.seed);
  for (const std::string& item : writer.items()) text += ", " + item;
  if (const auto* s = std::get_if<Nsga3Spec>(&spec.algorithm); s && !s->aspiration.empty()) {
    std::string points;
    for (const std::vector<double>& z : s->aspiration) {
      std::string values;
      for (double v : z) values += (values.empty() ? "" : ", ") + format_number(v);
      points += (points.empty() ? "[" : ", [") + values + "]";
    }
    text += ", aspiration: [" + points + "]";
  }
  return "{" + text + "}";
}

std::string optimizer_fields_markdown(std::string_view algorithm) {
  FieldDocs docs;
  if (algorithm == "nsga2") {
    Nsga2Spec spec;
    describe_fields(docs, spec);
  } else if (algorithm == "nsga3") {
    Nsga3Spec spec;
    describe_fields(docs, spec);
  } else if (algorithm == "moead") {
    MoeadSpec spec;
    describe_fields(docs, spec);
  } else if (algorithm == "hybrid") {
    HybridSpec spec;
    describe_fields(docs, spec);
  } else if (algorithm == "epsilon_constraint") {
    EpsilonConstraintSpec spec;
    describe_fields(docs, spec);
  } else if (algorithm == "nbi") {
    NbiSpec spec;
    describe_fields(docs, spec);
  } else if (algorithm == "ipopt") {
    IpoptSpec spec;
    describe_fields(docs, spec);
  } else if (algorithm == "nlopt") {
    NloptSpec spec;
    describe_fields(docs, spec);
  } else {
    throw std::invalid_argument("optimizer_fields_markdown: unknown algorithm '" +
                                std::string(algorithm) + "'");
  }
  return docs.markdown();
}

namespace {

RunOutcome single_objective_outcome(const Problem& problem, const std::string& name,
                                    SolveResult result) {
  RunOutcome outcome;
  outcome.front.algorithm = name;
  outcome.front.num_objectives = problem.num_objectives();
  if (!result.fitness.empty()) {
    outcome.front.x.push_back(result.x);
    outcome.front.fitness.push_back(result.fitness);
  }
  outcome.front.fitness_evaluations = result.fitness_evaluations;
  outcome.front.gradient_evaluations = result.gradient_evaluations;
  outcome.front.seconds = result.seconds;
  outcome.front.message = result.message;
  outcome.status = std::string(to_string(result.status));
  outcome.single = std::move(result);
  return outcome;
}

RunOutcome front_outcome(FrontResult front) {
  RunOutcome outcome;
  outcome.front = std::move(front);
  outcome.status = outcome.front.x.empty() ? "no_feasible_design" : "ok";
  return outcome;
}

}  // namespace

RunOutcome run_optimizer(const Problem& problem, const OptimizerSpec& spec, int threads) {
  auto start_of = [&](const std::vector<double>& start) {
    return start.empty() ? default_start(problem) : start;
  };
  return std::visit(
      Overloaded{
          [&](const Nsga2Spec& s) {
            Nsga2Options options = s.options;
            options.threads = threads;
            return front_outcome(run_nsga2(problem, options));
          },
          [&](const Nsga3Spec& s) {
            Nsga3Options options = s.options;
            options.threads = threads;
            return front_outcome(run_nsga3(problem, options));
          },
          [&](const MoeadSpec& s) {
            MoeadOptions options = s.options;
            options.threads = threads;
            return front_outcome(run_moead(problem, options));
          },
          [&](const HybridSpec& s) {
            HybridOptions options = s.options;
            options.nsga2.threads = threads;
            return front_outcome(run_hybrid(problem, options));
          },
          [&](const EpsilonConstraintSpec& s) {
            return front_outcome(run_epsilon_constraint(problem, s.options));
          },
          [&](const NbiSpec& s) { return front_outcome(run_nbi(problem, s.options)); },
          [&](const IpoptSpec& s) {
            return single_objective_outcome(
                problem, spec.name(), solve_with_ipopt(problem, start_of(s.start), s.options));
          },
          [&](const NloptSpec& s) {
            return single_objective_outcome(
                problem, spec.name(), solve_with_nlopt(problem, start_of(s.start), s.options));
          }},
      spec.algorithm);
}

std::string front_rule_text(std::size_t front_size, std::size_t num_objectives) {
  if (num_objectives < 2) return "the single-objective solver's answer";
  std::string rule =
      "the non-dominated set of every feasible design the run evaluated (its archive)";
  if (front_size > 0)
    rule += fmt::format(
        ", thinned to at most {} designs by SPEA2 truncation (the designs nearest to another in "
        "range-scaled objectives removed first, the best design of each objective kept)",
        front_size);
  return rule;
}

}  // namespace pkmopt
