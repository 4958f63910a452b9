// The keys of each algorithm in a study's `optimizer:` section, described once
// (io/format/field_list.hpp): the reader, the resolved-file writer and the tables of
// docs/optimizer.md all come from these lists. Besides its algorithm's keys every section has
// `algorithm` (required) and `seed` (integer >= 0, default 1).
//
// Example:
//   Nsga2Spec spec;
//   read_fields(section, spec);                      // strict, located errors
//   std::string table = fields_markdown(Nsga2Spec{});  // the docs table
#pragma once

#include <string_view>

#include "io/format/field_list.hpp"
#include "studies/optimizer_spec.hpp"

namespace pkmopt {

// Polynomial mutation keys of the evolutionary algorithms (NSGA-II, NSGA-III, MOEA/D).
template <class Fields, class Options>
void describe_mutation_fields(Fields& f, Options& o) {
  f.field("mutation_probability", o.mutation_probability,
          {.min = 0,
           .max = 1,
           .expected = "a probability in [0, 1]",
           .doc = "polynomial mutation probability per variable; 0 means 1/n for n variables"});
  f.field("mutation_eta", o.mutation_eta,
          {.min = 0, .min_exclusive = true, .doc = "polynomial mutation distribution index"});
}

// SBX and polynomial mutation keys of NSGA-II and NSGA-III.
template <class Fields, class Options>
void describe_variation_fields(Fields& f, Options& o, std::string_view eta_doc) {
  f.field("crossover_probability", o.crossover_probability,
          {.min = 0,
           .max = 1,
           .expected = "a probability in [0, 1]",
           .doc = "SBX crossover probability per pair"});
  f.field("crossover_eta", o.crossover_eta, {.min = 0, .min_exclusive = true, .doc = eta_doc});
  describe_mutation_fields(f, o);
}

template <class Fields>
void describe_fields(Fields& f, Nsga2Options& o) {
  f.field("population", o.population,
          {.min = 4, .max = 1e6, .even = true, .doc = "individuals per generation"});
  f.field("generations", o.generations,
          {.min = 0,
           .max = 1e7,
           .doc = "generations after the first; evaluations = population × (generations + 1)"});
  describe_variation_fields(f, o, "SBX distribution index (Deb et al. 2002)");
}

template <class Fields>
void describe_fields(Fields& f, Nsga3Spec& s) {
  Nsga3Options& o = s.options;
  f.field("population", o.population,
          {.min = 4,
           .max = 1e6,
           .even = true,
           .zero_is_unset = true,
           .default_text = "the directions rounded up to a multiple of 4",
           .doc = "individuals per generation"});
  f.field("generations", o.generations,
          {.min = 0,
           .max = 1e7,
           .doc = "generations after the first; evaluations = population × (generations + 1)"});
  f.field("divisions", o.divisions,
          {.min = 1,
           .max = 1000,
           .doc = "H of the Das–Dennis reference directions, C(H + M − 1, M − 1) of them for M "
                  "objectives (H1 of the boundary layer with inner_divisions)"});
  f.field("inner_divisions", o.inner_divisions,
          {.min = 0,
           .max = 1000,
           .doc = "H2 of an inside layer of directions (Deb & Jain 2014, for 8 and more "
                  "objectives); 0: one layer"});
  f.field("aspiration_divisions", o.aspiration_divisions,
          {.min = 1,
           .max = 100,
           .zero_is_unset = true,
           .default_text = "the largest giving at most 30 directions per point",
           .doc = "with `aspiration`: H of the Das–Dennis set around each aspiration point",
           .omit_when = [&s] { return s.aspiration.empty(); }});
  f.field("aspiration_spread", o.aspiration_spread,
          {.min = 0,
           .max = 1,
           .min_exclusive = true,
           .doc = "with `aspiration`: the size of the set around each point on the normalised "
                  "simplex (1: the whole simplex)",
           .omit_when = [&s] { return s.aspiration.empty(); }});
  describe_variation_fields(f, o, "SBX distribution index (Deb & Jain 2014: 30)");
}

template <class Fields>
void describe_fields(Fields& f, MoeadSpec& s) {
  MoeadOptions& o = s.options;
  f.field("generations", o.generations,
          {.min = 0,
           .max = 1e7,
           .doc = "generations after the first; evaluations = weights × (generations + 1)"});
  f.field("divisions", o.divisions,
          {.min = 1,
           .max = 1000,
           .doc = "H of the Das–Dennis weight vectors, one population member each (H1 of the "
                  "boundary layer with inner_divisions)"});
  f.field("inner_divisions", o.inner_divisions,
          {.min = 0, .max = 1000, .doc = "H2 of an inside layer of weight vectors; 0: one layer"});
  f.field("neighbours", o.neighbours,
          {.min = 2, .max = 1e6, .doc = "T, the nearest weight vectors a subproblem mates with"});
  f.field("neighbourhood_probability", o.neighbourhood_probability,
          {.min = 0,
           .max = 1,
           .expected = "a probability in [0, 1]",
           .doc = "δ, the probability that parents come from the neighbours (else from all)"});
  f.field("max_replacements", o.max_replacements,
          {.min = 1, .max = 1e6, .doc = "n_r, the most members one child replaces"});
  f.field("differential_weight", o.differential_weight,
          {.min = 0, .max = 2, .min_exclusive = true, .doc = "F of DE/rand/1"});
  f.field("crossover_rate", o.crossover_rate,
          {.min = 0,
           .max = 1,
           .expected = "a probability in [0, 1]",
           .doc = "CR of DE's binomial crossover"});
  describe_mutation_fields(f, o);
  f.field("normalize", o.normalize,
          {.doc = "Tchebycheff in objectives scaled by the ideal point and the population's "
                  "nadir (false: raw units)"});
}

template <class Fields>
void describe_fields(Fields& f, IpoptOptions& o) {
  f.field("max_iterations", o.max_iterations,
          {.min = 1, .max = 1e7, .doc = "Ipopt iterations per solve (max_iter)"});
  f.field("tolerance", o.tolerance,
          {.min = 0,
           .min_exclusive = true,
           .doc = "Ipopt convergence tolerance (tol, scaled NLP error)"});
}

template <class Fields>
void describe_start(Fields& f, std::vector<double>& start) {
  f.field("start", start,
          {.unit = "variable units",
           .default_text = "the bounds' centre",
           .doc = "start point, one value per variable within the bounds"});
}

template <class Fields>
void describe_fields(Fields& f, Nsga2Spec& s) {
  describe_fields(f, s.options);
}

template <class Fields>
void describe_fields(Fields& f, HybridSpec& s) {
  describe_fields(f, s.options.nsga2);
  f.field("polish_iterations", s.options.ipopt.max_iterations,
          {.min = 1, .max = 1e7, .doc = "Ipopt iterations per polished front design"});
}

template <class Fields>
void describe_fields(Fields& f, EpsilonConstraintSpec& s) {
  f.field("points", s.options.points,
          {.min = 2, .max = 1e5, .doc = "front points (epsilon levels)"});
  std::size_t primary = s.options.primary_objective + 1;
  f.field("primary_objective", primary,
          {.min = 1,
           .expected = "an objective number from 1 to the number of objectives",
           .doc = "the objective minimised; the others are bounded (1-based)"});
  s.options.primary_objective = primary - 1;
  describe_fields(f, s.options.ipopt);
  describe_start(f, s.options.start);
}

template <class Fields>
void describe_fields(Fields& f, NbiSpec& s) {
  f.field("points", s.options.points,
          {.min = 2, .max = 1e5, .doc = "front points (lattice points)"});
  f.field("equality_form", s.options.equality_form,
          {.doc = "the NBI line as an equality (Das & Dennis 1998) instead of ≤"});
  describe_fields(f, s.options.ipopt);
  describe_start(f, s.options.start);
}

template <class Fields>
void describe_fields(Fields& f, IpoptSpec& s) {
  describe_fields(f, s.options);
  describe_start(f, s.start);
}

template <class Fields>
void describe_fields(Fields& f, NloptSpec& s) {
  f.field("max_evaluations", s.options.max_evaluations,
          {.min = 1, .max = 1e10, .doc = "objective evaluations at most"});
  f.field("tolerance", s.options.relative_tolerance_x,
          {.min = 0,
           .min_exclusive = true,
           .zero_is_unset = true,
           .doc = "relative tolerance on x (xtol_rel)"});
  f.field("population", s.options.population,
          {.min = 1,
           .max = 1e6,
           .zero_is_unset = true,
           .doc = "population of the stochastic global algorithms (NLopt's default when unset)"});
  f.field("local_algorithm", s.options.local_algorithm,
          {.expected = "an NLopt algorithm name", .doc = "the local algorithm of MLSL and AUGLAG"});
  describe_start(f, s.start);
}

/// output.front_size of design and benchmark studies: one description for both readers, their
/// resolved writers and the docs tables.
template <class Fields>
void front_size_field(Fields& f, int& front_size) {
  f.field("front_size", front_size,
          {.min = 0,
           .max = kMaxFrontSize,
           .zero_is_unset = true,
           .expected = "an integer in [1, 100000]",
           .doc = "thin the front to this many designs (SPEA2 truncation, the extremes kept); "
                  "unset: every non-dominated feasible design of the run"});
}

}  // namespace pkmopt
