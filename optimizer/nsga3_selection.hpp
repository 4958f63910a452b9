// The selection steps of NSGA-III (Deb & Jain, IEEE TEVC 18(4), 2014, Algorithms 2-4) that
// replace NSGA-II's crowding distance when the last front that fits only partly must be thinned:
// normalise the objectives, associate every member with its nearest reference direction, and fill
// the remaining places niche by niche.
//
// Normalisation (Algorithm 2) over the objective vectors f of the members S_t:
//   ideal z_j = min_s f_j(s);  f' = f - z;
//   extreme point of axis j: argmin_s max_i f'_i(s) / w_i with w = e_j (1e-6 elsewhere), the
//   achievement scalarising function of the axis;
//   intercepts a: the hyperplane through the M extreme points, E b = 1, a_j = 1 / b_j (E: rows the
//   extreme points). When E is singular or an intercept is not positive and finite (duplicate
//   extremes, a degenerate front), a_j = max_s f'_j(s) instead, and an axis on which every member
//   is equal takes a_j = 1;
//   normalised f_n = f' / a.
//   With a NormalizationMemory across generations the ideal point is the smallest seen so far and
//   the previous extreme points stay candidates (Blank, Deb & Roy, EMO 2019; pymoo's NSGA3).
// Association (Algorithm 3): each member's nearest reference line through the origin and its
// perpendicular distance d = |f_n - (w . f_n / |w|^2) w|; ties go to the lower index.
// Niching (Algorithm 4): with rho_j the members already selected per direction, repeat K times:
// among the directions not yet excluded take those with the least rho (one at random); if no
// member of the last front is left on it, exclude it; otherwise take, when rho = 0, its member
// nearest to the line (lower index on a tie), else one of its members at random; rho += 1.
// Every random choice comes from the caller's Random, so a seed gives the same selection.
//
// Example:
//   const Normalization n = normalize_objectives(f);           // f: S_t's objective vectors
//   std::vector<Association> a = associate(normalized(n, f), directions);
//   std::vector<std::size_t> chosen = niche_select(K, rho, last_front_associations, rng);
#pragma once

#include <cstddef>
#include <vector>

#include "optimizer/random.hpp"

namespace pkmopt {

struct Normalization {
  std::vector<double> ideal;       ///< z, per objective
  std::vector<double> intercepts;  ///< a, per objective, > 0
  bool from_hyperplane = false;    ///< the extreme points' hyperplane gave every intercept
};

/// What the normalisation carries from one generation to the next (Blank, Deb & Roy, "Investigating
/// the Normalization Procedure of NSGA-III", EMO 2019, as pymoo does): the ideal point found so far
/// and the last extreme points, which stay candidates for the next ones. Empty at the start.
struct NormalizationMemory {
  std::vector<double> ideal;
  std::vector<std::vector<double>> extremes;  ///< in objective units
};

/// Algorithm 2 over a non-empty set of objective vectors of equal size M >= 1; with `memory`, the
/// ideal point is also the smallest seen before and the extreme points are chosen among f and the
/// previous extremes (memory is updated).
Normalization normalize_objectives(const std::vector<std::vector<double>>& f,
                                   NormalizationMemory* memory = nullptr);

/// (f - ideal) / intercepts for each vector.
std::vector<std::vector<double>> normalized(const Normalization& n,
                                            const std::vector<std::vector<double>>& f);

struct Association {
  std::size_t direction = 0;  ///< index of the nearest reference direction
  double distance = 0.0;      ///< perpendicular distance to its line
};

/// Algorithm 3: the nearest reference line of each normalised point.
std::vector<Association> associate(const std::vector<std::vector<double>>& points,
                                   const std::vector<std::vector<double>>& directions);

/// Algorithm 4: `count` members of the last front (indices into `last_front`, its members'
/// associations) given rho, the selected members per direction (size: the number of directions;
/// updated). Returns fewer only when the last front has fewer members.
std::vector<std::size_t> niche_select(std::size_t count, std::vector<std::size_t>& rho,
                                      const std::vector<Association>& last_front, Random& rng);

}  // namespace pkmopt
