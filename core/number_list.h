// The numbers of an option's value after its name, separated by colons ("linear:0.001:0.01:0.25" from 7 on), as the
// rules of --survival and --interpolation write them.
#ifndef HPSF_CORE_NUMBER_LIST_H
#define HPSF_CORE_NUMBER_LIST_H

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace hpsf {

// Every number from `from` on, or nothing where one does not parse whole (std::from_chars: "inf" and "nan" parse, so
// a caller checks that its numbers are finite).
std::optional<std::vector<double>> ParseNumberList(const std::string& text, std::size_t from);

}  // namespace hpsf

#endif  // HPSF_CORE_NUMBER_LIST_H
