#include <filesystem>

#include "roadload/geo_files.hpp"

namespace roadload {
namespace {

Parsed<std::vector<GeoSection>> read_any(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".geojson" || ext == ".json") return detail::read_geojson(path);
  if (ext == ".gpx") return detail::read_gpx(path);
  return ParseError{path, 0, "", "unknown kind of GIS file: expected .geojson, .json or .gpx"};
}

}  // namespace

Parsed<std::vector<GeoPoint>> load_geo_line(const std::string& path) {
  auto sections = read_any(path);
  if (!sections) return sections.error();
  const auto& all = sections.value();
  if (all.empty()) return ParseError{path, 0, "", "draws no line"};
  // A GPX file's first track is the drive; a GeoJSON line must be the only one, not a guess.
  if (all.size() > 1 && all.front().where.rfind("trk", 0) != 0 && all.front().where.rfind("rte", 0) != 0) {
    return ParseError{path, 0, "features", "expected one line, found " + std::to_string(all.size())};
  }
  return all.front().line;
}

Parsed<std::vector<GeoSection>> load_geo_sections(const std::string& path) {
  auto sections = read_any(path);
  if (sections && sections.value().empty()) return ParseError{path, 0, "", "draws no section"};
  return sections;
}

}  // namespace roadload
