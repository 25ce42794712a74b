#pragma once
// The command line's checks of option values, with messages a person can act
// on: a name that is not one of the choices gets "did you mean", a number out of
// range says the range (CLI11's own says "Value 0 not in range 0.000000 to
// 1797…" with 300 digits, or "Could not convert"). Used by compare/main.cpp only.
#include "compare/suggest.hpp"

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace gacompare::compare::cli {

// One of `names` (e.g. the backends); CLI11 prefixes the option's name.
inline CLI::Validator one_of(const std::string& what, const std::vector<std::string>& names) {
  return CLI::Validator(
      [what, names](std::string& value) -> std::string {
        for (const auto& n : names)
          if (n == value) return "";
        return not_one_of(what, value, names);
      },
      "", what);
}

// A whole number in [lo, hi].
inline CLI::Validator whole_number(long long lo, long long hi = std::numeric_limits<int>::max()) {
  return CLI::Validator(
      [lo, hi](std::string& value) -> std::string {
        long long x = 0;
        const char* end = value.data() + value.size();
        const auto [p, ec] = std::from_chars(value.data(), end, x);
        const std::string range = hi == std::numeric_limits<int>::max() ? "≥ " + std::to_string(lo)
                                                                        : "from " + std::to_string(lo) + " to " + std::to_string(hi);
        const bool too_big = ec == std::errc::result_out_of_range ? value[0] != '-' : ec == std::errc() && x > hi;
        if (too_big && p == end) return "expected a whole number " + range + ", got " + value + ", above " + std::to_string(hi);
        if (ec == std::errc::result_out_of_range || (ec == std::errc() && p == end && x < lo))
          return "expected a whole number " + range + ", got " + value;
        if (ec != std::errc() || p != end) return "expected a whole number " + range + ", got '" + value + "'";
        return "";
      },
      "", "whole number");
}

// A finite number > 0.
inline CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        double x = 0;
        const char* end = value.data() + value.size();
        const auto [p, ec] = std::from_chars(value.data(), end, x);
        if (ec != std::errc() || p != end || !std::isfinite(x) || !(x > 0))
          return "expected a number > 0, got '" + value + "'";
        return "";
      },
      "", "number > 0");
}

}  // namespace gacompare::compare::cli
