#include "roadload/io/replay_faults.hpp"

#include <algorithm>
#include <cmath>

#include "roadload/recording/csv.hpp"

namespace roadload::io {
namespace {

constexpr const char* kSource = "--faults";
constexpr const char* kKnown =
    "unknown fault; known: drop=P dup=P seed=N error@T busoff@T+D tp-truncate@T gnss-outage@T+D accel-overflow@T clock-step@T=S";

ParseError bad(std::string_view item, const std::string& message) { return ParseError{kSource, 0, std::string(item), message}; }

std::optional<Nanoseconds> seconds(std::string_view text, bool allow_negative) {
  const auto v = recording::parse_f64(text);
  if (!v || !std::isfinite(*v) || std::abs(*v) > 1e7 || (!allow_negative && *v < 0)) return std::nullopt;
  return Nanoseconds{static_cast<std::int64_t>(std::llround(*v * 1e9))};
}

// "name@T", "name@T+D" or "name@T=S": the time and what follows it.
struct Timed {
  Nanoseconds at{};
  char sep = 0;
  std::string_view rest;
};

std::optional<Timed> timed(std::string_view args) {
  const std::size_t split = args.find_first_of("+=");
  const auto at = seconds(args.substr(0, split), false);
  if (!at) return std::nullopt;
  if (split == std::string_view::npos) return Timed{*at, 0, {}};
  return Timed{*at, args[split], args.substr(split + 1)};
}

}  // namespace

Parsed<ReplayFaults> parse_replay_faults(std::string_view spec) {
  ReplayFaults f;
  f.spec = std::string(spec);
  while (!spec.empty()) {
    const std::size_t comma = spec.find(',');
    const std::string_view item = spec.substr(0, comma);
    spec = comma == std::string_view::npos ? std::string_view() : spec.substr(comma + 1);
    if (item.empty()) return bad(item, "empty item (two commas in a row?)");
    const std::size_t eq = item.find('='), at = item.find('@');
    if (at == std::string_view::npos) {
      const std::string_view name = item.substr(0, eq);
      // NaN where there is no number: every range check below fails on it.
      const double v = eq == std::string_view::npos ? std::nan("") : recording::parse_f64(item.substr(eq + 1)).value_or(std::nan(""));
      if (name == "drop" || name == "dup") {
        if (!(v >= 0 && v <= 1)) return bad(item, "expected a probability from 0 to 1, as " + std::string(name) + "=0.01");
        (name == "drop" ? f.drop_fraction : f.duplicate_fraction) = v;
      } else if (name == "seed") {
        if (!(v >= 0 && v < 1e18) || v != std::floor(v)) return bad(item, "expected a whole number, as seed=7");
        f.seed = static_cast<std::uint64_t>(v);
      } else {
        return bad(item, kKnown);
      }
      continue;
    }
    const std::string_view name = item.substr(0, at);
    const auto t = timed(item.substr(at + 1));
    if (!t) return bad(item, "expected the time in seconds after '@', as " + std::string(name) + "@60");
    const bool instant = name == "error" || name == "tp-truncate" || name == "accel-overflow";
    if (instant) {
      if (t->sep != 0) return bad(item, "takes a time only, as " + std::string(name) + "@60");
      (name == "error" ? f.error_frames : name == "tp-truncate" ? f.tp_truncations : f.accel_overflows).push_back(t->at);
    } else if (name == "busoff" || name == "gnss-outage") {
      const auto d = t->sep == '+' ? seconds(t->rest, false) : std::nullopt;
      if (!d || d->count() <= 0) return bad(item, "expected a time and a positive duration, as " + std::string(name) + "@60+5");
      (name == "busoff" ? f.bus_off : f.gnss_outages).push_back({t->at, *d});
    } else if (name == "clock-step") {
      const auto s = t->sep == '=' ? seconds(t->rest, true) : std::nullopt;
      if (!s || s->count() == 0) return bad(item, "expected a time and a non-zero step in seconds, as clock-step@60=-3.5");
      f.clock_steps.push_back({t->at, *s});
    } else {
      return bad(item, kKnown);
    }
  }
  const auto by_time = [](const auto& a, const auto& b) { return a.at < b.at; };
  std::sort(f.bus_off.begin(), f.bus_off.end(), by_time);
  std::sort(f.gnss_outages.begin(), f.gnss_outages.end(), by_time);
  std::sort(f.clock_steps.begin(), f.clock_steps.end(), by_time);
  return f;
}

}  // namespace roadload::io
