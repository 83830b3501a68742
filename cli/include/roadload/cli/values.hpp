#pragma once
// The checks on option values that both programs share. Each refuses what it cannot take with a
// message CLI11 prefixes with the option's name: "--mass: 'heavy' is not a finite number in
// 1000..200000", a usage error.
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace roadload::cli {

// A finite number in [min, max]: nan and inf are refused, whatever the range.
CLI::Validator real_in(double min, double max);
// A finite number, its range left to what the value configures (roadloadd's validate()).
CLI::Validator finite();

// A whole number in [min, max], decimal or 0x hexadecimal. A transform (Option::transform): it
// hands CLI11 the number in decimal, so that a leading zero is never read as octal.
CLI::Validator whole_in(std::int64_t min, std::int64_t max);

// One of `words` ("expected cells or runs, not 'halves'").
CLI::Validator one_of(std::vector<std::string> words);

}  // namespace roadload::cli
