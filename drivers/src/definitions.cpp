#include "roadload/definitions.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "roadload/j1939/dbc.hpp"

namespace roadload {

std::string data_dir() {
  const char* dir = std::getenv("ROADLOAD_DATADIR");
  return dir != nullptr && *dir != '\0' ? dir : ROADLOAD_DATADIR;
}

std::string core_dbc_path() { return data_dir() + "/j1939-core.dbc"; }

std::optional<ParseError> load_dbc_file(j1939::Database& db, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return ParseError{path, 0, "", std::strerror(errno)};
  std::stringstream text;
  text << in.rdbuf();
  return j1939::load_dbc(db, text.str(), path);
}

}  // namespace roadload
