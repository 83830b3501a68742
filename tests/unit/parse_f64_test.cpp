// Numbers in recordings are read exactly as std::from_chars reads them, whether by the fast paths
// for plain decimals and plain integers or not: the same value for every text, the same refusals.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "roadload/recording/csv.hpp"

namespace roadload::recording {
namespace {

std::optional<double> reference(const std::string& s) {
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty() || !std::isfinite(v)) return std::nullopt;
  return v;
}

void expect_same(const std::string& s) {
  const auto got = parse_f64(s), want = reference(s);
  ASSERT_EQ(got.has_value(), want.has_value()) << "'" << s << "'";
  if (want) {
    ASSERT_EQ(std::signbit(*got), std::signbit(*want)) << "'" << s << "'";
    ASSERT_EQ(*got, *want) << "'" << s << "'";
  }
}

TEST(ParseF64, EveryDecimalReadsAsFromCharsReadsIt) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> value(-2000.0, 2000.0);
  std::uniform_int_distribution<int> decimals(0, 12);
  char text[64];
  for (int i = 0; i < 200'000; ++i) {
    std::snprintf(text, sizeof text, "%.*f", decimals(rng), value(rng) * std::pow(10.0, decimals(rng) - 6));
    expect_same(text);
  }
  for (const char* s : {"0",
                        "-0",
                        "-0.000000",
                        "0.5",
                        ".5",
                        "-.5",
                        "5.",
                        "007.250",
                        "123456789012345",
                        "1234567890123456",
                        "0.1234567890123456",
                        "9007199254740993",
                        "1e5",
                        "1.5e-3",
                        "",
                        "-",
                        ".",
                        "-.",
                        "1.2.3",
                        "--1",
                        "+1",
                        " 1",
                        "1 ",
                        "nan",
                        "inf",
                        "0x10",
                        "1,5",
                        "999999999999999.9"}) {
    expect_same(s);
  }
}

std::optional<std::int64_t> reference_i64(const std::string& s) {
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

TEST(ParseI64, EveryIntegerReadsAsFromCharsReadsIt) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 100'000; ++i) {
    const std::uint64_t bits = rng() >> (rng() % 64);
    const std::string s = std::to_string(static_cast<std::int64_t>(bits)) + (i % 1000 == 0 ? "x" : "");
    ASSERT_EQ(parse_i64(s), reference_i64(s)) << "'" << s << "'";
  }
  for (const char* s : {"0", "007", "-0", "-1", "+1", "", "-", " 1", "1 ", "1.0", "1e3", "9223372036854775807", "9223372036854775808",
                        "-9223372036854775808", "9999999999999999999", "18446744073709551616", "12345678901234567890"}) {
    ASSERT_EQ(parse_i64(s), reference_i64(s)) << "'" << s << "'";
  }
}

}  // namespace
}  // namespace roadload::recording
