#include "roadload/definitions.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "roadload/j1939/dbc.hpp"

namespace roadload {

namespace {

// The installed data folder relative to the program's own folder (GNUInstallDirs' bin and sbin
// are siblings of share), so a package or a `cmake --install --prefix` anywhere finds its files.
std::string installed_data_dir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  const std::filesystem::path dir = exe.parent_path() / ROADLOAD_BIN_TO_DATADIR;
  if (!std::filesystem::is_regular_file(dir / "j1939-core.dbc", ec)) return {};
  return dir.lexically_normal().string();
}

}  // namespace

std::string data_dir() {
  const char* dir = std::getenv("ROADLOAD_DATADIR");
  if (dir != nullptr && *dir != '\0') return dir;
  static const std::string installed = installed_data_dir();
  return installed.empty() ? ROADLOAD_SOURCE_DATADIR : installed;
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
