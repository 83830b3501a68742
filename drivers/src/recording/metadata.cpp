#include "roadload/recording/metadata.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <sstream>

#include "roadload/toml_text.hpp"
#include "roadload/vehicle_file.hpp"
#include "roadload/vehicle_table.hpp"

namespace roadload::recording {
namespace {

constexpr std::string_view kFormatName = "roadload-recording";

struct Bad {
  ParseError error;
};

long line_of(const toml::node& n) { return static_cast<long>(n.source().begin.line); }

class Reader {
 public:
  explicit Reader(std::string_view source) : source_(source) {}

  [[noreturn]] void fail(const toml::node* n, std::string field, std::string message) const {
    throw Bad{ParseError{std::string(source_), n != nullptr ? line_of(*n) : 0, std::move(field), std::move(message)}};
  }

  std::string text(const toml::table& t, std::string_view key, std::string_view where, bool required = false) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) {
      if (required) fail(&t, std::string(where) + std::string(key), "required key missing");
      return {};
    }
    if (!n->is_string()) fail(n, std::string(where) + std::string(key), "expected a string");
    return std::string(*n->value<std::string_view>());
  }

  // A free key named with its unit holds a number: text there is a mistake, not a label.
  static bool names_a_unit(std::string_view key) {
    for (std::string_view unit :
         {"_kg", "_m", "_m2", "_mps", "_mps2", "_nm", "_pa", "_c", "_deg", "_s", "_ns", "_hz", "_w", "_l", "_pct", "_rpm", "_kw"}) {
      if (key.ends_with(unit)) return true;
    }
    return false;
  }

  // A table the format defines: absent is allowed, any other type is an error.
  const toml::table* table(const toml::table& root, std::string_view key) const {
    const toml::node* n = root.get(key);
    if (n == nullptr) return nullptr;
    if (!n->is_table()) fail(n, std::string(key), "expected a table ([" + std::string(key) + "])");
    return n->as_table();
  }

  // A vehicle number a truck can have: finite; a mass (its name ends in _kg) above 0 and below
  // 200 t; an axle's position between 0 and 50 m behind the front axle; the driving before the
  // recording within a day (a tire's warm-up is gone after two hours).
  static const char* unphysical(std::string_view key, double v) {
    if (!std::isfinite(v)) return "not a finite number";
    if (key.ends_with("_kg") && !(v > 0 && v < 200'000)) return "a mass must lie between 0 and 200,000 kg";
    if (key.ends_with("_position_m") && !(v >= 0 && v <= 50)) return "an axle's position must lie 0-50 m behind the front axle";
    if (key == "driven_before_s" && !(v >= 0 && v <= 86'400)) return "the driving before the recording must lie 0-86,400 s";
    return nullptr;
  }

  double number(const toml::node& n, const std::string& field) const {
    if (auto v = n.value<double>()) return *v;
    fail(&n, field, "expected a number");
  }

  std::int64_t integer(const toml::node& n, const std::string& field) const {
    if (!n.is_integer()) fail(&n, field, "expected an integer");
    return *n.value<std::int64_t>();
  }

  Metadata read(const toml::table& root) const {
    Metadata m;
    if (text(root, "format", "", true) != kFormatName) {
      fail(root.get("format"), "format", "expected \"roadload-recording\"");
    }
    const toml::node* version = root.get("version");
    if (version == nullptr) fail(&root, "version", "required key missing");
    m.version = integer(*version, "version");
    if (m.version != kFormatVersion) fail(version, "version", "unsupported format version");
    m.created_by = text(root, "created_by", "");
    m.recording_id = text(root, "recording_id", "");
    if (const toml::node* segment = root.get("segment")) {
      m.segment = integer(*segment, "segment");
      if (m.segment < 1) fail(segment, "segment", "expected a segment number from 1");
    }
    if (const toml::table* clock = table(root, "clock")) {
      m.clock_source = text(*clock, "source", "clock.");
      if (const toml::node* off = clock->get("utc_offset_ns")) m.utc_offset_ns = integer(*off, "clock.utc_offset_ns");
    }
    if (const toml::table* vehicle = table(root, "vehicle")) {
      for (const auto& [key, node] : *vehicle) {
        const std::string field = "vehicle." + std::string(key.str());
        if (key.str() == "file" && node.is_table()) {
          m.vehicle_file = described_vehicle(*node.as_table());
        } else if (node.is_string() && !names_a_unit(key.str())) {
          m.vehicle_text[std::string(key.str())] = std::string(*node.value<std::string_view>());
        } else {
          const double v = number(node, field);
          if (const char* why = unphysical(key.str(), v)) fail(&node, field, why);
          m.vehicle[std::string(key.str())] = v;
        }
      }
    }
    if (const toml::table* can = table(root, "can")) {
      if (const toml::node* ifs = can->get("interfaces")) {
        const toml::array* arr = ifs->as_array();
        if (arr == nullptr) fail(ifs, "can.interfaces", "expected an array of names");
        for (const toml::node& n : *arr) {
          if (!n.is_string()) fail(&n, "can.interfaces", "expected a string");
          m.can_interfaces.emplace_back(*n.value<std::string_view>());
        }
      }
    }
    if (const toml::node* sensors = root.get("sensor")) {
      const toml::array* arr = sensors->as_array();
      if (arr == nullptr) fail(sensors, "sensor", "expected [[sensor]] tables");
      for (const toml::node& n : *arr) m.sensors.push_back(sensor(n, m.sensors.size()));
    }
    return m;
  }

 private:
  Vehicle described_vehicle(const toml::table& t) const {
    try {
      Vehicle v = detail::read_vehicle(detail::TomlFields(std::string(source_)), t, "vehicle.file.");
      v.source = std::string(source_) + " [vehicle.file]";
      return v;
    } catch (const detail::TomlFailure& e) {
      throw Bad{e.error};
    }
  }

  SensorInfo sensor(const toml::node& n, std::size_t index) const {
    const std::string where = "sensor[" + std::to_string(index) + "].";
    const toml::table* t = n.as_table();
    if (t == nullptr) fail(&n, where, "expected a table");
    SensorInfo s;
    const toml::node* id = t->get("id");
    if (id == nullptr) fail(t, where + "id", "required key missing");
    s.id = integer(*id, where + "id");
    s.name = text(*t, "name", where, true);
    s.kind = text(*t, "kind", where, true);
    s.position = text(*t, "position", where);
    s.part = text(*t, "part", where);
    if (const toml::node* rate = t->get("rate_hz")) s.rate_hz = number(*rate, where + "rate_hz");
    return s;
  }

  std::string_view source_;
};

// toml++ 3.3 reaches undefined behaviour on some non-ASCII bare keys (found by fuzzing), so
// the metadata is ASCII; strings can still carry any character as a \uXXXX escape.
std::optional<ParseError> non_ascii(std::string_view text, std::string_view source) {
  long line = 1;
  for (const char c : text) {
    if (c == '\n') ++line;
    if (static_cast<unsigned char>(c) >= 0x80) {
      return ParseError{std::string(source), line, "toml", "non-ASCII byte; write such characters as \\uXXXX escapes"};
    }
  }
  return std::nullopt;
}

}  // namespace

Parsed<Metadata> parse_metadata(std::string_view text, std::string_view source) {
  if (auto e = non_ascii(text, source)) return *e;
  toml::parse_result parsed = toml::parse(text, source);
  if (!parsed) {
    const toml::parse_error& e = parsed.error();
    return ParseError{std::string(source), static_cast<long>(e.source().begin.line), "toml", std::string(e.description())};
  }
  try {
    return Reader(source).read(parsed.table());
  } catch (const Bad& b) {
    return b.error;
  }
}

std::string format_metadata(const Metadata& m) {
  std::ostringstream o;
  o << "format = \"roadload-recording\"\nversion = " << m.version << "\n";
  if (!m.created_by.empty()) o << "created_by = " << toml_quoted(m.created_by) << "\n";
  if (!m.recording_id.empty()) o << "recording_id = " << toml_quoted(m.recording_id) << "\n";
  if (m.segment > 0) o << "segment = " << m.segment << "\n";
  o << "\n[clock]\nsource = " << toml_quoted(m.clock_source) << "\n";
  if (m.utc_offset_ns) o << "utc_offset_ns = " << *m.utc_offset_ns << "\n";
  o << "\n[vehicle]\n";
  for (const auto& [k, v] : m.vehicle_text) o << k << " = " << toml_quoted(v) << "\n";
  o.precision(17);
  for (const auto& [k, v] : m.vehicle) o << k << " = " << toml::value<double>(v) << "\n";
  if (m.vehicle_file) o << format_vehicle(*m.vehicle_file, {}, "vehicle.file");
  o << "\n[can]\ninterfaces = [";
  for (std::size_t i = 0; i < m.can_interfaces.size(); ++i) o << (i ? ", " : "") << toml_quoted(m.can_interfaces[i]);
  o << "]\n";
  for (const SensorInfo& s : m.sensors) {
    o << "\n[[sensor]]\nid = " << s.id << "\nname = " << toml_quoted(s.name) << "\nkind = " << toml_quoted(s.kind) << "\n";
    if (!s.position.empty()) o << "position = " << toml_quoted(s.position) << "\n";
    if (!s.part.empty()) o << "part = " << toml_quoted(s.part) << "\n";
    if (s.rate_hz > 0) o << "rate_hz = " << toml::value<double>(s.rate_hz) << "\n";
  }
  return o.str();
}

}  // namespace roadload::recording
