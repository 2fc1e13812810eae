#pragma once

#include <optional>
#include <string_view>

namespace isg::common {

// A number as a person writes one on a command line: an optional sign, decimal digits with an
// optional point, an optional exponent ("-1.5", "+2", ".5", "3e2"). Nothing else is a number here:
// not "0x10" (strtod's hexadecimal), "nan", "inf", spaces around it, or a value beyond a double
// (1e999). Empty when `text` is not one.
std::optional<double> parseDecimal(std::string_view text);

}  // namespace isg::common
