// A stored response library read back for the runs at hand. Anything unexpected is an error naming
// the line and field: a cache that cannot be trusted is rebuilt, never half used.
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "roadload/gap/library_cache.hpp"
#include "roadload/gap/resimulate.hpp"
#include "roadload/gap/unseen.hpp"

namespace roadload::gap {
namespace {

struct Bad {
  std::string field, message;
};

class Records {
 public:
  explicit Records(std::string_view text) : text_(text) {}

  // The next line's fields, which must start with `tag`.
  const std::vector<std::string_view>& expect(std::string_view tag) {
    if (!next_is(tag)) throw Bad{std::string(tag), "expected here, found '" + std::string(peek_tag()) + "'"};
    return take();
  }
  bool next_is(std::string_view tag) { return peek_tag() == tag; }
  long line() const { return line_; }

  static double number(std::string_view s, const std::string& field) {
    const std::string copy(s);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(copy.c_str(), &end);
    if (copy.empty() || end != copy.c_str() + copy.size() || errno == ERANGE) throw Bad{field, "not a number: '" + copy + "'"};
    return v;
  }
  static std::size_t index(std::string_view s, const std::string& field, std::size_t count) {
    const double v = number(s, field);
    if (!(v >= 0 && v < static_cast<double>(count)) || v != std::floor(v)) throw Bad{field, "out of range: '" + std::string(s) + "'"};
    return static_cast<std::size_t>(v);
  }
  // A line of numbers after its tag, exactly `n` of them.
  Eigen::VectorXd vector(std::string_view tag, std::size_t n) {
    const auto& f = expect(tag);
    if (f.size() != n + 1) {
      throw Bad{std::string(tag), std::to_string(f.size() - 1) + " values, expected " + std::to_string(n)};
    }
    Eigen::VectorXd v(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) v(static_cast<Eigen::Index>(i)) = number(f[i + 1], std::string(tag));
    return v;
  }

 private:
  std::string_view peek_tag() {
    load();
    return fields_.empty() ? std::string_view("end of file") : fields_.front();
  }
  const std::vector<std::string_view>& take() {
    load();
    loaded_ = false;
    return fields_;
  }
  void load() {
    if (loaded_) return;
    loaded_ = true;
    fields_.clear();
    if (pos_ >= text_.size()) return;
    const std::size_t eol = text_.find('\n', pos_);
    if (eol == std::string_view::npos) throw Bad{"line", "not ended by a newline (a file cut short)"};
    const std::string_view line = text_.substr(pos_, eol - pos_);
    pos_ = eol + 1;
    ++line_;
    for (std::size_t at = 0;;) {
      const std::size_t tab = line.find('\t', at);
      fields_.push_back(line.substr(at, tab == std::string_view::npos ? std::string_view::npos : tab - at));
      if (tab == std::string_view::npos) break;
      at = tab + 1;
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  long line_ = 0;
  bool loaded_ = false;
  std::vector<std::string_view> fields_;
};

void need(const std::vector<std::string_view>& f, std::size_t n, std::string_view tag) {
  if (f.size() != n) throw Bad{std::string(tag), std::to_string(f.size()) + " fields, expected " + std::to_string(n)};
}

Nominal nominal_named(std::string_view name) {
  for (int i = 0; i <= static_cast<int>(Nominal::tire_radius); ++i) {
    if (nominal_name(static_cast<Nominal>(i)) == name) return static_cast<Nominal>(i);
  }
  throw Bad{"prior", "unknown nominal parameter '" + std::string(name) + "'"};
}

void read_drives(Records& in, ModelLibrary& lib) {
  for (sim::Scenario& s : lib.scenarios) {
    const auto& f = in.expect("drive");
    need(f, 9, "drive");
    double v[8];
    for (std::size_t i = 0; i < 8; ++i) v[i] = Records::number(f[i + 1], "drive");
    s.speed_mps = v[0];
    s.load_scale = v[1];
    s.weather.air_temp_c = v[2];
    s.weather.pressure_pa = v[3];
    s.weather.wind_speed_mps = v[4];
    s.weather.wind_from_deg = v[5];
    s.duration.reset();
    if (std::isfinite(v[6])) s.duration = Seconds{v[6]};
    if (!(v[7] >= 0 && v[7] <= sim::kMaxDrivenBefore.count())) {
      throw Bad{"drive", "driving before the run outside 0-86400 s: " + std::to_string(v[7])};
    }
    s.driven_before = Seconds{v[7]};
  }
}

void read_features(Records& in, ModelLibrary& lib) {
  while (in.next_is("feature")) {
    const auto& f = in.expect("feature");
    need(f, 6, "feature");
    const std::size_t run = Records::index(f[1], "feature run", lib.labels.size());
    const auto half = static_cast<std::uint8_t>(Records::index(f[2], "feature half", 2));
    lib.feature_half.push_back(static_cast<std::uint8_t>(Records::index(f[3], "feature half", 2)));
    lib.keys.push_back({lib.labels[run], std::string(f[4]), std::string(f[5]), half});
  }
  if (lib.keys.empty()) throw Bad{"feature", "none"};
}

void read_responses(Records& in, ModelLibrary& lib) {
  const std::size_t n = lib.keys.size();
  while (in.next_is("response")) {
    const auto& f = in.expect("response");
    need(f, 6, "response");
    const auto effect = sim::find_effect(f[1]);
    if (!effect) throw Bad{"response", "unknown effect '" + std::string(f[1]) + "'"};
    ModelLibrary::Response r{*effect,
                             Records::number(f[2], "response base"),
                             Records::number(f[3], "response m1"),
                             Records::number(f[4], "response m2"),
                             {},
                             {}};
    lib.null_gain.push_back(Records::number(f[5], "response null gain"));
    r.f1 = in.vector("f1", n);
    r.f2 = in.vector("f2", n);
    lib.responses.push_back(std::move(r));
  }
  // Every effect this program fits, in its catalog's order, or the library is another program's.
  const std::vector<sim::Effect> fitted = fitted_effects();
  if (lib.responses.size() != fitted.size()) throw Bad{"response", "not the effects this program fits"};
  for (std::size_t e = 0; e < fitted.size(); ++e) {
    if (lib.responses[e].effect != fitted[e]) throw Bad{"response", "effects out of the catalog's order"};
  }
}

void read_nominal(Records& in, ModelLibrary& lib) {
  lib.priors.assign(lib.labels.size(), {});
  while (in.next_is("prior")) {
    const auto& f = in.expect("prior");
    need(f, 5, "prior");
    const std::size_t run = Records::index(f[1], "prior run", lib.labels.size());
    lib.priors[run].push_back({nominal_named(f[2]), Records::number(f[3], "prior value"), Records::number(f[4], "prior sigma")});
  }
  const std::size_t params = lib.priors.front().size();
  for (const auto& p : lib.priors) {
    if (p.size() != params) throw Bad{"prior", "runs with different nominal parameters"};
  }
  lib.nominal_delta.resize(static_cast<Eigen::Index>(lib.keys.size()), static_cast<Eigen::Index>(params));
  for (std::size_t j = 0; j < params; ++j)
    lib.nominal_delta.col(static_cast<Eigen::Index>(j)) = in.vector("nominal", lib.keys.size());
  const Eigen::VectorXd miss = in.vector("miss", params);
  lib.nominal_miss.assign(miss.data(), miss.data() + miss.size());
}

ModelLibrary read(Records& in, std::string_view fingerprint, const std::vector<RealRun>& runs) {
  const auto& head = in.expect("roadload-gap-library");
  need(head, 3, "roadload-gap-library");
  if (head[1] != "2") throw Bad{"version", "'" + std::string(head[1]) + "', this program reads 2"};
  if (head[2] != fingerprint) throw Bad{"fingerprint", "made for other inputs or by another build"};
  ModelLibrary lib;
  lib.scenarios = resimulations(runs);
  for (const RealRun& r : runs) {
    lib.labels.push_back(r.label);
    lib.layouts.push_back(layout_for(r.model.route));
  }
  read_drives(in, lib);
  const auto& noise = in.expect("noise");
  need(noise, 4, "noise");
  lib.null_chi2_mean = Records::number(noise[1], "noise mean");
  lib.null_chi2_sd = Records::number(noise[2], "noise sd");
  lib.null_chi2_count = Records::index(noise[3], "noise count", 1u << 20);
  read_features(in, lib);
  lib.baseline = in.vector("baseline", lib.keys.size());
  lib.sigma = in.vector("sigma", lib.keys.size());
  read_responses(in, lib);
  read_nominal(in, lib);
  in.expect("end");
  if (!in.next_is("end of file")) throw Bad{"end", "lines after the end"};
  return lib;
}

}  // namespace

Parsed<ModelLibrary> decode_library(std::string_view text, const std::string& file, std::string_view fingerprint,
                                    const std::vector<RealRun>& runs) {
  Records in(text);
  try {
    return read(in, fingerprint, runs);
  } catch (const Bad& bad) {
    return ParseError{file, in.line(), bad.field, bad.message};
  }
}

}  // namespace roadload::gap
