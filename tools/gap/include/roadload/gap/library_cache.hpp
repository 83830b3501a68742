#pragma once
// A response library kept on disk, so that every later diagnosis of the same truck on the same
// road starts from it instead of simulating it again (docs/gap.md, "The library cache").
#include <string>
#include <string_view>
#include <vector>

#include "roadload/gap/engine.hpp"

namespace roadload::gap {

// What a library depends on besides what library_serves() compares (speed, weather, load,
// duration): the program that simulates (the build ids of every loaded object), the truck, the
// road, the sensors, the clocks, the effects the model already has, the J1939 database, the noise
// runs, the hold-out and the decision rule. 16 hex digits; empty when the program has no build id
// to vouch for its code, and then nothing is cached.
std::string library_fingerprint(const std::vector<sim::Scenario>& resims, const j1939::Database& db, const GapOptions& options);

// The library as text: tab-separated lines, numbers exact (hexadecimal floating point).
std::string encode_library(const ModelLibrary& lib, std::string_view fingerprint);
// The library back, for these runs: their labels, scenarios and layouts replace the stored ones
// (the scenarios keep the stored drive's speed, weather, load and duration, so library_serves()
// still judges them). Errors name the file, line and field.
Parsed<ModelLibrary> decode_library(std::string_view text, const std::string& file, std::string_view fingerprint,
                                    const std::vector<RealRun>& runs);

// The cache folder: $ROADLOAD_CACHE_DIR, else $XDG_CACHE_HOME/roadload/gap, else
// $HOME/.cache/roadload/gap; empty when none of them is set.
std::string default_cache_dir();

struct CachedLibrary {
  ModelLibrary library;
  bool from_cache = false;
  std::string note;                   // for the progress line: where the library was read or stored
  std::vector<std::string> warnings;  // what could not be read or written, each to be told
};

// A library for these runs from `dir` when one there serves them, else built and stored there
// (at most `keep` files are kept, the least recently used go first). A cache that cannot be read
// or written is noted and passed over: the diagnosis never depends on it.
CachedLibrary cached_library(const std::string& dir, const std::vector<RealRun>& runs, const j1939::Database& db,
                             const GapOptions& options, std::size_t keep = 64);

}  // namespace roadload::gap
