#include "roadload/recording/csv.hpp"

#include <charconv>
#include <cmath>
#include <limits>

namespace roadload::recording {
namespace {

std::size_t split(std::string_view line, std::array<std::string_view, CsvReader::kMaxColumns>& out) {
  std::size_t n = 0;
  for (;;) {
    const std::size_t comma = line.find(',');
    if (n == out.size()) return n + 1;  // too many: caller reports it
    out[n++] = line.substr(0, comma);
    if (comma == std::string_view::npos) return n;
    line.remove_prefix(comma + 1);
  }
}

bool skippable(std::string_view line) { return line.empty() || line[0] == '#'; }

// A plain decimal ("-12.345678") of at most 15 digits is an integer below 2^53 over a power of ten
// below 10^22, both exact in a double, so one IEEE division gives the correctly rounded value
// from_chars gives (Clinger's fast path). Anything else (exponents, more digits) is left to it.
std::optional<double> plain_decimal(std::string_view s) {
  static constexpr double kPow10[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  const bool negative = !s.empty() && s[0] == '-';
  std::size_t i = negative ? 1 : 0;
  const std::size_t first = i;
  std::uint64_t mantissa = 0;
  for (; i < s.size() && static_cast<unsigned char>(s[i] - '0') <= 9; ++i)
    mantissa = mantissa * 10 + static_cast<unsigned>(s[i] - '0');
  const std::size_t whole = i - first;
  std::size_t fraction = 0;
  if (i < s.size() && s[i] == '.') {
    const std::size_t begin = ++i;
    for (; i < s.size() && static_cast<unsigned char>(s[i] - '0') <= 9; ++i)
      mantissa = mantissa * 10 + static_cast<unsigned>(s[i] - '0');
    fraction = i - begin;
    if (fraction == 0) return std::nullopt;
  }
  // Anything left (an exponent, a second point) or more digits than a double holds exactly.
  if (i != s.size() || whole + fraction == 0 || whole + fraction > 15) return std::nullopt;
  const double v = static_cast<double>(mantissa) / kPow10[fraction];
  return negative ? -v : v;
}

// The stamps and sensor numbers: non-negative decimal integers of at most 19 digits, which a
// uint64 holds. Anything else (a sign, an int64 overflowed) is left to from_chars.
std::optional<std::int64_t> plain_integer(std::string_view s) {
  if (s.empty() || s.size() > 19) return std::nullopt;
  std::uint64_t v = 0;
  for (const char c : s) {
    if (static_cast<unsigned char>(c - '0') > 9) return std::nullopt;
    v = v * 10 + static_cast<unsigned>(c - '0');
  }
  if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) return std::nullopt;
  return static_cast<std::int64_t>(v);
}

}  // namespace

std::optional<std::int64_t> parse_i64(std::string_view s) {
  if (const auto fast = plain_integer(s)) return fast;
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

std::optional<double> parse_f64(std::string_view s) {
  if (const auto fast = plain_decimal(s)) return fast;
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty() || !std::isfinite(v)) return std::nullopt;
  return v;
}

Parsed<CsvReader> CsvReader::open(const std::string& path, std::span<const std::string_view> required,
                                  std::span<const std::string_view> optional) {
  auto lines = LineReader::open(path);
  if (!lines) return lines.error();
  std::optional<std::string_view> header;
  while ((header = lines.value().next()) && skippable(*header)) {
    if (lines.value().overlong()) return lines.value().overlong_error();
  }
  if (!header) {
    if (lines.value().error()) return *lines.value().error();
    return ParseError{path, 0, "header", "file is empty: expected a header line"};
  }
  std::array<std::string_view, kMaxColumns> cols{};
  const std::size_t n = split(*header, cols);
  const long line = lines.value().line_number();
  if (n > kMaxColumns) return ParseError{path, line, "header", "more than 32 columns"};
  std::vector<std::string> names;
  std::vector<std::size_t> map;
  auto position = [&](std::string_view want) {
    for (std::size_t i = 0; i < n; ++i) {
      if (cols[i] == want) return i;
    }
    return kAbsent;
  };
  for (std::string_view want : required) {
    const std::size_t found = position(want);
    if (found == kAbsent) return ParseError{path, line, std::string(want), "required column missing from header"};
    names.emplace_back(want);
    map.push_back(found);
  }
  for (std::string_view want : optional) {
    names.emplace_back(want);
    map.push_back(position(want));
  }
  CsvReader r(std::move(lines.value()), std::move(names), std::move(map));
  r.file_columns_ = n;
  return r;
}

CsvReader::Status CsvReader::next(std::span<const std::string_view>& row) {
  for (;;) {
    const auto line = lines_.next();
    if (!line) {
      error_ = lines_.error();
      return Status::end;
    }
    if (lines_.overlong()) {
      error_ = lines_.overlong_error();
      return Status::bad_row;
    }
    if (skippable(*line)) continue;
    const std::size_t n = split(*line, split_);
    if (n != file_columns_) {
      error_ = ParseError{path(), line_number(), "row",
                          "expected " + std::to_string(file_columns_) + " fields, found " +
                              (n > kMaxColumns ? std::string("more than 32") : std::to_string(n))};
      return Status::bad_row;
    }
    for (std::size_t i = 0; i < map_.size(); ++i) row_[i] = map_[i] == kAbsent ? std::string_view() : split_[map_[i]];
    row = std::span<const std::string_view>(row_.data(), map_.size());
    return Status::row;
  }
}

ParseError CsvReader::field_error(std::size_t column, std::string message) const {
  return ParseError{path(), line_number(), names_[column], std::move(message)};
}

}  // namespace roadload::recording
