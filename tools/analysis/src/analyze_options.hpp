#pragma once
// The analysis's options under the name its provenance (analyze_provenance.hpp) knows them by.
#include "roadload/analysis/analyze.hpp"

namespace roadload::cli {

using analysis::AnalyzeOptions;

}  // namespace roadload::cli
