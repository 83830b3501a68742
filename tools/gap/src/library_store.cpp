// The library cache's folder: one file per library, named by its fingerprint, written whole and
// renamed into place so a reader never sees half of one, and trimmed to the most recently used.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "roadload/gap/library_cache.hpp"

namespace roadload::gap {
namespace {

namespace fs = std::filesystem;
constexpr std::string_view kSuffix = ".lib";

std::vector<fs::path> entries(const fs::path& dir, const std::string& prefix) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.starts_with(prefix) && name.ends_with(kSuffix) && it->is_regular_file(ec)) out.push_back(it->path());
  }
  return out;
}

std::optional<std::string> read_whole(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return s.str();
}

// The least recently used libraries beyond `keep` go.
void trim(const fs::path& dir, std::size_t keep) {
  std::vector<fs::path> all = entries(dir, "");
  if (all.size() <= keep) return;
  std::error_code ec;
  auto used = [&](const fs::path& p) { return fs::last_write_time(p, ec); };
  std::sort(all.begin(), all.end(), [&](const fs::path& a, const fs::path& b) { return used(a) > used(b); });
  for (std::size_t i = keep; i < all.size(); ++i) fs::remove(all[i], ec);
}

std::string store(const fs::path& dir, const std::string& fingerprint, const ModelLibrary& lib, std::size_t keep) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return dir.string() + ": " + ec.message();
  const auto stamp = std::chrono::system_clock::now().time_since_epoch().count();
  const std::string name = fingerprint + "-" + std::to_string(stamp) + "-" + std::to_string(::getpid());
  const fs::path tmp = dir / ("." + name + ".tmp"), path = dir / (name + std::string(kSuffix));
  {
    std::ofstream out(tmp, std::ios::binary);
    out << encode_library(lib, fingerprint);
    out.close();
    if (!out) {
      fs::remove(tmp, ec);
      return tmp.string() + ": cannot write";
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) return path.string() + ": " + ec.message();
  trim(dir, keep);
  return {};
}

}  // namespace

std::string default_cache_dir() {
  if (const char* d = std::getenv("ROADLOAD_CACHE_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/roadload/gap";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/roadload/gap";
  return {};
}

CachedLibrary cached_library(const std::string& dir, const std::vector<RealRun>& runs, const j1939::Database& db,
                             const GapOptions& options, std::size_t keep) {
  CachedLibrary out;
  const std::vector<sim::Scenario> resims = resimulations(runs);
  const std::string fingerprint = dir.empty() ? std::string() : library_fingerprint(resims, db, options);
  if (dir.empty() || fingerprint.empty()) {
    out.library = build_library(runs, db, options);
    if (!dir.empty()) out.warnings.push_back("this build has no build id, so no library is cached");
    return out;
  }
  for (const fs::path& path : entries(dir, fingerprint + "-")) {
    const auto text = read_whole(path);
    if (!text) continue;
    auto lib = decode_library(*text, path.string(), fingerprint, runs);
    std::error_code ec;
    if (!lib) {
      out.warnings.push_back(lib.error().to_string() + " (removed)");
      fs::remove(path, ec);
      continue;
    }
    if (!library_serves(lib.value(), resims)) continue;
    fs::last_write_time(path, fs::file_time_type::clock::now(), ec);
    out.library = std::move(lib.value());
    out.from_cache = true;
    out.note = "library read from " + path.string();
    return out;
  }
  out.library = build_library(runs, db, options);
  const std::string failed = store(dir, fingerprint, out.library, keep);
  if (failed.empty()) {
    out.note = "library stored in " + dir;
  } else {
    out.warnings.push_back(failed);
  }
  return out;
}

}  // namespace roadload::gap
