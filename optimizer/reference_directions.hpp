// Reference directions on the unit simplex for many-objective selection (NSGA-III; Deb & Jain,
// "An Evolutionary Many-Objective Optimization Algorithm Using Reference-Point-Based
// Nondominated Sorting Approach, Part I", IEEE TEVC 18(4), 2014).
//
// Das–Dennis directions (Das & Dennis, SIAM J. Optim. 8(3), 1998): every w with components
// w_i = k_i / H, k_i >= 0 integers, sum k_i = H, in M objectives:
//     count = C(H + M - 1, M - 1)     (M = 3, H = 12: 91; M = 5, H = 6: 210)
// Neighbouring directions are sqrt(2)/H apart; the M vertices e_i are among them.
//
// Two layers (Deb & Jain 2014, sec. V-B, for M >= 8, where one layer with H < M has no interior
// point): a boundary layer with H1 divisions and an inside layer with H2 divisions shrunk towards
// the centroid, w = (1 - tau)/M + tau w' with tau = 1/2. Deb & Jain's sizes: M = 8, (H1, H2) =
// (3, 2): 120 + 36 = 156; M = 10, (3, 2): 220 + 55 = 275; M = 15, (2, 1): 120 + 15 = 135.
//
// Directions are in lexicographic order of (k_1, ..., k_M) descending: (H, 0, ..., 0) first.
//
// Example:
//   std::vector<std::vector<double>> w = pkmopt::das_dennis_directions(3, 12);   // 91
//   auto two = pkmopt::two_layer_directions(8, 3, 2);                            // 156
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

namespace pkmopt {

/// C(H + M - 1, M - 1), the number of Das–Dennis directions; throws std::invalid_argument when
/// it exceeds 10^7 or M < 1.
std::size_t das_dennis_count(std::size_t objectives, std::size_t divisions);

/// Every Das–Dennis direction (see the header comment). Throws std::invalid_argument for M < 1,
/// H < 1 or more than 10^7 directions.
std::vector<std::vector<double>> das_dennis_directions(std::size_t objectives,
                                                       std::size_t divisions);

/// The boundary layer (H1 divisions) then the inside layer (H2, shrunk halfway to the centroid);
/// H2 = 0 gives the boundary layer only.
std::vector<std::vector<double>> two_layer_directions(std::size_t objectives,
                                                      std::size_t outer_divisions,
                                                      std::size_t inner_divisions);

/// Checks directions a user gave: each of `objectives` finite components >= 0, not all 0; throws
/// std::invalid_argument "WHO: expected WHAT of M finite components >= 0, not all 0" otherwise.
void check_given_directions(const std::vector<std::vector<double>>& directions,
                            std::size_t objectives, std::string_view who, std::string_view what);

}  // namespace pkmopt
