// GPX 1.1 tracks and routes: each <trk> or <rte> one line, its <name> and its <type> (read as
// the surface). Expat reports where each element starts, so every error names its line.
#include <expat.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>

#include "roadload/geo_files.hpp"

namespace roadload::detail {
namespace {

struct GpxReader {
  std::string path;
  XML_Parser parser = nullptr;
  std::vector<GeoSection> sections;
  std::optional<ParseError> error;
  std::string text;       // character data of the element being read
  std::string element;    // innermost element's local name
  bool in_line = false;   // inside a <trk> or <rte>
  bool in_point = false;  // inside a <trkpt> or <rtept>
  std::size_t tracks = 0, routes = 0;

  long line() const { return static_cast<long>(XML_GetCurrentLineNumber(parser)); }
  void fail(std::string field, std::string message) {
    if (!error) error = ParseError{path, line(), std::move(field), std::move(message)};
    XML_StopParser(parser, XML_FALSE);
  }
};

// "http://www.topografix.com/GPX/1/1 trkpt" (expat's namespace separator is a space) -> "trkpt".
std::string local(const XML_Char* name) {
  const char* space = std::strrchr(name, ' ');
  return space ? space + 1 : name;
}

std::optional<double> number(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

void start(void* data, const XML_Char* name, const XML_Char** attrs) {
  auto& r = *static_cast<GpxReader*>(data);
  r.element = local(name);
  r.text.clear();
  if (r.element == "trk" || r.element == "rte") {
    GeoSection s;
    s.where = r.element + "[" + std::to_string(r.element == "trk" ? r.tracks++ : r.routes++) + "]";
    r.sections.push_back(std::move(s));
    r.in_line = true;
    r.in_point = false;  // a line opened inside a point (malformed, yet well-formed XML) starts without one
  } else if (r.in_line && (r.element == "trkpt" || r.element == "rtept")) {
    GeoPoint p{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN(),
               std::numeric_limits<double>::quiet_NaN()};
    for (const XML_Char** a = attrs; *a != nullptr; a += 2) {
      const std::string key = local(a[0]);
      if (key != "lat" && key != "lon") continue;
      const auto v = number(a[1]);
      if (!v) return r.fail(r.element + "." + key, std::string("not a number: \"") + a[1] + "\"");
      (key == "lat" ? p.lat_deg : p.lon_deg) = *v;
    }
    if (!(std::abs(p.lat_deg) <= 90)) return r.fail(r.element + ".lat", "missing or outside -90..90");
    if (!(std::abs(p.lon_deg) <= 180)) return r.fail(r.element + ".lon", "missing or outside -180..180");
    r.sections.back().line.push_back(p);
    r.in_point = true;
  }
}

void end(void* data, const XML_Char* name) {
  auto& r = *static_cast<GpxReader*>(data);
  const std::string element = local(name);
  if (element == "trk" || element == "rte") {
    if (r.sections.back().line.size() < 2) return r.fail(r.sections.back().where, "a line needs at least two points");
    r.in_line = false;
  } else if (element == "trkpt" || element == "rtept") {
    r.in_point = false;
  } else if (r.in_point && element == "ele" && !r.sections.back().line.empty()) {
    const auto v = number(r.text);
    if (!v) return r.fail("ele", "not a number: \"" + r.text + "\"");
    r.sections.back().line.back().elev_m = *v;
  } else if (r.in_line && !r.in_point && element == "name") {
    r.sections.back().name = r.text;
  } else if (r.in_line && !r.in_point && element == "type") {
    std::string surface = r.text;
    for (char& c : surface) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (surface == "asphalt") surface = "bituminous";
    if (surface != "concrete" && surface != "bituminous") return r.fail("type", "expected concrete, bituminous or asphalt");
    r.sections.back().surface = surface;
  }
  r.text.clear();
}

void characters(void* data, const XML_Char* s, int len) {
  auto& r = *static_cast<GpxReader*>(data);
  if (r.text.size() < 4096) r.text.append(s, static_cast<std::size_t>(len));
}

}  // namespace

Parsed<std::vector<GeoSection>> read_gpx(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return ParseError{path, 0, "", "cannot open"};
  std::unique_ptr<XML_ParserStruct, decltype(&XML_ParserFree)> parser(XML_ParserCreateNS(nullptr, ' '), &XML_ParserFree);
  GpxReader r;
  r.path = path;
  r.parser = parser.get();
  XML_SetUserData(r.parser, &r);
  XML_SetElementHandler(r.parser, start, end);
  XML_SetCharacterDataHandler(r.parser, characters);
  char buffer[65536];
  for (;;) {
    in.read(buffer, sizeof buffer);
    const auto n = static_cast<int>(in.gcount());
    const bool last = n < static_cast<int>(sizeof buffer);
    if (XML_Parse(r.parser, buffer, n, last ? XML_TRUE : XML_FALSE) == XML_STATUS_ERROR) {
      if (r.error) return *r.error;
      return ParseError{path, r.line(), "", std::string("not XML: ") + XML_ErrorString(XML_GetErrorCode(r.parser))};
    }
    if (last) break;
  }
  if (r.error) return *r.error;
  return std::move(r.sections);
}

}  // namespace roadload::detail
