#include "roadload/cli/values.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string_view>

namespace roadload::cli {
namespace {

// "1000", "0.0001", "1e+06": the bounds as a user would write them.
std::string shortest(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// `range` names [min, max] in the message; empty for any finite number.
CLI::Validator real_check(double min, double max, const std::string& range) {
  return CLI::Validator(
      [min, max, range](std::string& text) {
        double v = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec == std::errc() && end == text.data() + text.size() && std::isfinite(v) && v >= min && v <= max) return std::string();
        return "'" + text + "' is not a finite number" + (range.empty() ? "" : " in " + range);
      },
      "");
}

}  // namespace

CLI::Validator real_in(double min, double max) { return real_check(min, max, shortest(min) + ".." + shortest(max)); }

CLI::Validator finite() {
  constexpr double kLargest = std::numeric_limits<double>::max();
  return real_check(-kLargest, kLargest, "");
}

CLI::Validator whole_in(std::int64_t min, std::int64_t max) {
  return CLI::Validator(
      [min, max](std::string& text) {
        std::string_view digits = text;
        int base = 10;
        if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
          digits.remove_prefix(2);
          base = 16;
        }
        std::int64_t n = 0;
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n, base);
        if (ec != std::errc() || end != digits.data() + digits.size() || n < min || n > max) {
          return "'" + text + "' is not a whole number in " + std::to_string(min) + ".." + std::to_string(max);
        }
        text = std::to_string(n);
        return std::string();
      },
      "");
}

CLI::Validator one_of(std::vector<std::string> words) {
  std::string expected;
  for (std::size_t i = 0; i < words.size(); ++i) {
    expected += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
  }
  return CLI::Validator(
      [words, expected](std::string& text) {
        for (const std::string& w : words) {
          if (text == w) return std::string();
        }
        return "expected " + expected + ", not '" + text + "'";
      },
      "");
}

}  // namespace roadload::cli
