// Parsing of command-line values that CLI11 leaves as text ("fx,fy,fz,mx,my,mz").
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace pkmopt {

/// `count` comma-separated finite numbers; throws InputError
/// "--wrench: expected 6 comma-separated finite numbers, found '1,2'".
std::vector<double> parse_number_list(std::string_view option, const std::string& text,
                                      std::size_t count);

/// Throws InputError "OPTION: expected EXPECTED, found FOUND" for a bad numeric option value.
[[noreturn]] void bad_option(std::string_view option, std::string_view expected, double found);

}  // namespace pkmopt
