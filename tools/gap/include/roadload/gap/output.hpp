#pragma once
// What `roadload gap` prints and writes: the ranked places, the named effect with its magnitude,
// the held-out residual per channel before and after; the same as JSON (docs/gap.md).
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "roadload/gap/engine.hpp"
#include "roadload/parse_error.hpp"

namespace roadload::gap {

void print_result(std::FILE* out, const GapResult& g, const std::vector<std::string>& run_lines);
std::string result_json(const GapResult& g, const std::vector<std::string>& run_lines);
// One row per feature: run, channel, where, half, real, model, sigma, z, after (docs/gap.md).
std::string features_csv(const GapResult& g);
std::optional<ParseError> write_text_file(const std::string& path, const std::string& text);

// A JSON number; one that is not finite becomes null.
std::string json_number(double v);

}  // namespace roadload::gap
