// Parsing of command-line values that CLI11 leaves as text ("fx,fy,fz,mx,my,mz").
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace pkmopt {

/// `count` comma-separated finite numbers within the input number policy
/// (io/format/number_policy.hpp) and of magnitude at most `max_magnitude`; throws InputError
/// "--wrench: expected 6 comma-separated finite numbers, found '1,2'".
std::vector<double> parse_number_list(std::string_view option, const std::string& text,
                                      std::size_t count, double max_magnitude = 1e15);

/// A wrench option (--wrench fx,fy,fz,mx,my,mz): six numbers, each within +-1e9 N or N*m.
std::vector<double> parse_wrench_option(const std::string& text);

/// Throws InputError "DIR: expected a results folder of `pkmopt run`, found no such folder" (or
/// "a file") unless `dir` is a folder.
void require_results_folder(const std::string& dir);

/// Throws InputError "OPTION: expected a file name, found the folder 'PATH'" when `path` names a
/// folder.
void require_not_a_folder(std::string_view option, const std::string& path);

/// Throws InputError "OPTION: expected EXPECTED, found FOUND" for a bad numeric option value.
[[noreturn]] void bad_option(std::string_view option, std::string_view expected, double found);

}  // namespace pkmopt
