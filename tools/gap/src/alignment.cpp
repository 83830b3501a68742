// The recordings' features against the library's: in its order, and the channels only one side has.
#include <map>
#include <set>
#include <tuple>

#include "resimulated.hpp"
#include "roadload/numbers.hpp"

namespace roadload::gap {

Eigen::VectorXd aligned(const std::vector<RealRun>& runs, const ModelLibrary& lib) {
  std::map<std::tuple<std::string, std::string, std::string, std::uint8_t>, double> real;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    for (const Feature& f : runs[r].recorded.features.features) real[{lib.labels[r], f.channel, f.where, f.half}] = f.value;
  }
  Eigen::VectorXd v(static_cast<Eigen::Index>(lib.keys.size()));
  for (std::size_t i = 0; i < lib.keys.size(); ++i) {
    const FeatureKey& k = lib.keys[i];
    const auto it = real.find({k.run, k.channel, k.where, lib.feature_half[i]});
    v(static_cast<Eigen::Index>(i)) = it == real.end() ? kNaN : it->second;
  }
  return v;
}

std::vector<UnmatchedChannel> unmatched_channels(const std::vector<RealRun>& runs, const ModelLibrary& lib) {
  std::vector<UnmatchedChannel> out;
  for (std::size_t r = 0; r < runs.size() && r < lib.labels.size(); ++r) {
    std::set<std::string> real, model;
    for (const Feature& f : runs[r].recorded.features.features) real.insert(f.channel);
    for (const FeatureKey& k : lib.keys) {
      if (k.run == lib.labels[r]) model.insert(k.channel);
    }
    for (const std::string& c : real) {
      if (!model.contains(c)) out.push_back({lib.labels[r], c, true});
    }
    for (const std::string& c : model) {
      if (!real.contains(c)) out.push_back({lib.labels[r], c, false});
    }
  }
  return out;
}

}  // namespace roadload::gap
