// NSGA-II's variation operators on real variables, in the bounded forms of Deb's reference
// implementation (nsga2r, K. Deb, IIT Kanpur / KanGAL: crossover.c `realcross`, mutation.c
// `real_mutate_ind`).
//
// Simulated binary crossover (SBX, Deb & Agrawal 1995) of parent values y1 < y2 in [l, u] with
// distribution index eta and one uniform draw u in [0, 1):
//   beta_1 = 1 + 2 (y1 - l) / (y2 - y1),   beta_2 = 1 + 2 (u_b - y2) / (y2 - y1)
//   alpha_k = 2 - beta_k^-(eta + 1)
//   beta_q,k = (u alpha_k)^(1 / (eta + 1))              if u <= 1 / alpha_k
//            = (1 / (2 - u alpha_k))^(1 / (eta + 1))    otherwise
//   c1 = ((y1 + y2) - beta_q,1 (y2 - y1)) / 2,   c2 = ((y1 + y2) + beta_q,2 (y2 - y1)) / 2
// clamped into [l, u]. Without bounds (beta -> infinity, alpha = 2) the spread factor
// beta_q = |c2 - c1| / |y2 - y1| has Deb & Agrawal's density 0.5 (eta + 1) beta^eta (beta <= 1),
// 0.5 (eta + 1) / beta^(eta + 2) (beta > 1), i.e. the CDF F(b) = b^(eta+1) / 2 (b <= 1),
// 1 - b^-(eta+1) / 2 (b > 1); with bounds, beta_q,k follows F truncated at beta_k:
// F(b) / F(beta_k) (F(beta_k) = alpha_k / 2), so no child leaves the bounds.
// Parents closer than 1e-14 are copied unchanged (as in nsga2r).
//
// Polynomial mutation (Deb & Goyal 1996), bounded form, of y in [l, u] with index eta and a draw
// u: delta_1 = (y - l) / (u_b - l), delta_2 = (u_b - y) / (u_b - l), p = 1 / (eta + 1),
//   delta_q = (2u + (1 - 2u)(1 - delta_1)^(eta+1))^p - 1             if u <= 0.5
//           = 1 - (2(1 - u) + 2(u - 0.5)(1 - delta_2)^(eta+1))^p     otherwise
//   y' = y + delta_q (u_b - l), clamped into [l, u_b].
// delta_q lies in [-delta_1, delta_2] with CDF, for d in [-delta_1, 0],
// ((1 + d)^(eta+1) - (1 - delta_1)^(eta+1)) / (2 (1 - (1 - delta_1)^(eta+1))), and the mirror
// image above 0.
//
// The vector forms draw, per variable, exactly as nsga2r does: SBX crosses each variable with
// probability 1/2, draws u, then swaps the two children with probability 1/2; mutation changes
// each variable with probability p_m, then draws u. All draws come from pkmopt::Random.
//
// Example:
//   auto [c1, c2] = pkmopt::sbx_children(0.2, 0.6, 0.0, 1.0, 15.0, 0.3);
//   double y = pkmopt::polynomial_mutation_value(0.5, 0.0, 1.0, 20.0, 0.9);
#pragma once

#include <utility>
#include <vector>

#include "optimizer/problem.hpp"
#include "optimizer/random.hpp"

namespace pkmopt {

/// The two SBX children (c1 <= c2 before clamping) of parents y1 < y2 in [lower, upper] for
/// the draw u in [0, 1) (see header comment).
std::pair<double, double> sbx_children(double y1, double y2, double lower, double upper, double eta,
                                       double u);

/// The polynomially mutated value of y in [lower, upper] for the draw u in [0, 1).
double polynomial_mutation_value(double y, double lower, double upper, double eta, double u);

/// SBX of two whole designs in place (nsga2r's `realcross`, per-variable probability 1/2).
void sbx_crossover(std::vector<double>& child1, std::vector<double>& child2, const Bounds& bounds,
                   double eta, Random& rng);

/// Polynomial mutation of a whole design in place, each variable with `probability`.
void polynomial_mutation(std::vector<double>& x, const Bounds& bounds, double probability,
                         double eta, Random& rng);

}  // namespace pkmopt
