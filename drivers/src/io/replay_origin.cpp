#include "roadload/io/replay_origin.hpp"

#include <filesystem>
#include <fstream>

#include "roadload/toml_fields.hpp"

namespace roadload::io {

std::optional<ParseError> write_replay_origin(const std::string& path, const ReplayOrigin& origin) {
  const ReplayTiming& timing = origin.timing;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << "# roadload replay: recorded time -> capture time\n"
        << "recorded_origin_ns = " << to_ns(timing.recorded_origin) << "\n"
        << "capture_origin_ns = " << to_ns(timing.capture_origin) << "\n"
        << "rate = " << timing.rate << "\n";
    // The spec's grammar has no quote or backslash, so it needs no escaping.
    if (!origin.faults.empty()) out << "faults = \"" << origin.faults.spec << "\"\n";
    out.close();
    if (!out) return ParseError{tmp, 0, "file", "could not be written"};
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) return ParseError{path, 0, "file", ec.message()};
  return std::nullopt;
}

Parsed<ReplayOrigin> read_replay_origin(const std::string& path) {
  auto parsed = detail::parse_toml_file(path);
  if (!parsed) return parsed.error();
  const detail::TomlFields f(path);
  ReplayOrigin origin;
  ReplayTiming& t = origin.timing;
  std::string faults;
  try {
    f.only(parsed.value(), {"recorded_origin_ns", "capture_origin_ns", "rate", "faults"}, "");
    auto integer = [&](std::string_view key) {
      const toml::node* n = parsed.value().get(key);
      if (n == nullptr || !n->is_integer()) f.fail(n != nullptr ? n : &parsed.value(), std::string(key), "expected an integer");
      return *n->value<std::int64_t>();
    };
    t.recorded_origin = capture_time_from_ns(integer("recorded_origin_ns"));
    t.capture_origin = capture_time_from_ns(integer("capture_origin_ns"));
    t.rate = f.required_number(parsed.value(), "rate", "");
    if (const toml::node* n = parsed.value().get("faults")) {
      if (!n->is_string()) f.fail(n, "faults", "expected a string");
      faults = *n->value<std::string>();
    }
  } catch (const detail::TomlFailure& e) {
    return e.error;
  }
  if (!(t.rate >= 0)) return ParseError{path, 0, "rate", "expected 0 (as fast as possible) or a positive factor"};
  auto parsed_faults = parse_replay_faults(faults);
  if (!parsed_faults) return ParseError{path, 0, "faults", parsed_faults.error().to_string()};
  origin.faults = std::move(parsed_faults.value());
  return origin;
}

}  // namespace roadload::io
