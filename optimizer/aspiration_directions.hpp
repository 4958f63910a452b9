// Reference directions around a decision maker's aspiration points, for the reference-point
// NSGA-III (R-NSGA-III: Vesikar, Deb & Blank, "Reference Point Based NSGA-III for Preferred
// Solutions", IEEE SSCI 2018; pymoo's RNSGA3). Instead of directions spread over the whole unit
// simplex, each aspiration point gets a small Das–Dennis set around its projection, so that the
// population gathers on the part of the front the decision maker asked about; the M axis
// directions e_j are added so that the normalisation keeps finding the extremes.
//
// For aspiration points z^ already normalised (by the same ideal point and intercepts as the
// population, optimizer/nsga3_selection.hpp), each point is projected onto the simplex plane
// sum w = 1 along the diagonal, p = z^ + (1 - sum_i z^_i) / M (1, ..., 1) (the line along which
// the achievement scalarizing function of optimizer/decision.hpp measures), and the population
// gathers about the front's crossing of the line from the ideal point through p. (Vesikar et al.
// project along the ray from the origin, p = z^ / sum z^, which is not defined for an aspiration
// at or beyond the ideal point; the two agree for z^ on the diagonal or on the plane.) The local
// set is the Das–Dennis set with `divisions` shrunk by `spread` and moved
// so its centroid is p: w = spread w_DD + p - spread / M (1, ..., 1), still summing to 1; a
// direction with negative components has them set to 0 and is scaled back to sum 1.
//
// Example:
//   auto w = pkmopt::aspiration_directions({{0.3, 0.3, 0.3}}, 4, 0.1);  // 15 + 3 directions
#pragma once

#include <cstddef>
#include <vector>

namespace pkmopt {

/// The default divisions of the local sets: the largest H whose Das–Dennis set in M objectives
/// has at most 30 directions (at least 1).
std::size_t default_aspiration_divisions(std::size_t objectives);

/// The local sets of every normalised aspiration point (see the header comment), then e_1..e_M.
/// Throws std::invalid_argument for no point, points of other sizes, a non-finite component,
/// spread outside (0, 1] or divisions < 1.
std::vector<std::vector<double>> aspiration_directions(
    const std::vector<std::vector<double>>& normalised_points, std::size_t divisions,
    double spread);

}  // namespace pkmopt
