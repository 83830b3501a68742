// A response library as text, one record per line, fields separated by tabs, numbers in
// hexadecimal floating point so that reading them back gives the same bits.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "roadload/gap/library_cache.hpp"
#include "roadload/gap/resimulate.hpp"

namespace roadload::gap {
namespace {

constexpr std::string_view kMagic = "roadload-gap-library";
constexpr std::string_view kVersion = "2";

class Line {
 public:
  Line& text(std::string_view s) {
    s_ += s_.empty() ? "" : "\t";
    s_ += s;
    return *this;
  }
  Line& number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%a", v);
    return text(buf);
  }
  Line& numbers(const Eigen::VectorXd& v) {
    for (Eigen::Index i = 0; i < v.size(); ++i) number(v(i));
    return *this;
  }
  std::string done() { return s_ + "\n"; }

 private:
  std::string s_;
};

double duration_s(const sim::Scenario& s) { return s.duration ? s.duration->count() : NAN; }

}  // namespace

std::string encode_library(const ModelLibrary& lib, std::string_view fingerprint) {
  std::string out = Line().text(kMagic).text(kVersion).text(fingerprint).done();
  for (const sim::Scenario& s : lib.scenarios) {
    const sim::WeatherSpec& w = s.weather;
    out += Line()
               .text("drive")
               .number(s.speed_mps)
               .number(s.load_scale)
               .number(w.air_temp_c)
               .number(w.pressure_pa)
               .number(w.wind_speed_mps)
               .number(w.wind_from_deg)
               .number(duration_s(s))
               .number(s.driven_before.count())
               .done();
  }
  out += Line()
             .text("noise")
             .number(lib.null_chi2_mean)
             .number(lib.null_chi2_sd)
             .number(static_cast<double>(lib.null_chi2_count))
             .done();
  std::map<std::string, std::size_t> run_of;
  for (std::size_t r = 0; r < lib.labels.size(); ++r) run_of.emplace(lib.labels[r], r);
  for (std::size_t i = 0; i < lib.keys.size(); ++i) {
    const FeatureKey& k = lib.keys[i];
    out += Line()
               .text("feature")
               .number(static_cast<double>(run_of.at(k.run)))
               .number(k.half)
               .number(lib.feature_half[i])
               .text(k.channel)
               .text(k.where)
               .done();
  }
  out += Line().text("baseline").numbers(lib.baseline).done();
  out += Line().text("sigma").numbers(lib.sigma).done();
  for (std::size_t e = 0; e < lib.responses.size(); ++e) {
    const auto& r = lib.responses[e];
    out += Line()
               .text("response")
               .text(sim::effect_info(r.effect).name)
               .number(r.base)
               .number(r.m1)
               .number(r.m2)
               .number(e < lib.null_gain.size() ? lib.null_gain[e] : 0.0)
               .done();
    out += Line().text("f1").numbers(r.f1).done();
    out += Line().text("f2").numbers(r.f2).done();
  }
  for (std::size_t r = 0; r < lib.priors.size(); ++r) {
    for (const NominalPrior& p : lib.priors[r]) {
      out += Line().text("prior").number(static_cast<double>(r)).text(nominal_name(p.id)).number(p.value).number(p.sigma).done();
    }
  }
  for (Eigen::Index j = 0; j < lib.nominal_delta.cols(); ++j) out += Line().text("nominal").numbers(lib.nominal_delta.col(j)).done();
  out += Line()
             .text("miss")
             .numbers(Eigen::Map<const Eigen::VectorXd>(lib.nominal_miss.data(), static_cast<Eigen::Index>(lib.nominal_miss.size())))
             .done();
  return out + Line().text("end").done();
}

}  // namespace roadload::gap
