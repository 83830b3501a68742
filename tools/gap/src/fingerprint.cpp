// A library's identity: everything its simulations depend on that a later drive of the same truck
// on the same road must share exactly. Drive-to-drive differences (speed, weather, load, duration)
// are left to library_serves(), which allows for them.
#include <link.h>

#include <cstdio>
#include <cstring>

#include "roadload/gap/library_cache.hpp"
#include "roadload/vehicle_file.hpp"

namespace roadload::gap {
namespace {

class Hash {
 public:
  void text(std::string_view s) {
    for (const char c : s) byte(static_cast<unsigned char>(c));
    byte(0);
  }
  void number(double v) {
    char buf[40];
    const int n = std::snprintf(buf, sizeof buf, "%a", v);
    text({buf, static_cast<std::size_t>(n)});
  }
  void bytes(const unsigned char* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) byte(p[i]);
  }
  std::string hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
    return buf;
  }

 private:
  void byte(unsigned char c) { h_ = (h_ ^ c) * 0x100000001b3ULL; }  // FNV-1a
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

// The GNU build id of every object in the process (the program, GeographicLib, libm, ...): any
// change to the code that simulates changes one of them.
bool hash_build_ids(Hash& h) {
  struct Seen {
    Hash* h;
    bool program = false;
  } seen{&h};
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* data) {
        auto* s = static_cast<Seen*>(data);
        for (ElfW(Half) i = 0; i < info->dlpi_phnum; ++i) {
          const ElfW(Phdr)& ph = info->dlpi_phdr[i];
          if (ph.p_type != PT_NOTE) continue;
          const auto* p = reinterpret_cast<const unsigned char*>(info->dlpi_addr + ph.p_vaddr);
          const unsigned char* end = p + ph.p_memsz;
          while (p + sizeof(ElfW(Nhdr)) <= end) {
            ElfW(Nhdr) note;
            std::memcpy(&note, p, sizeof note);
            const unsigned char* name = p + sizeof note;
            const unsigned char* desc = name + ((note.n_namesz + 3) & ~3U);
            if (note.n_type == NT_GNU_BUILD_ID && note.n_namesz == 4 && std::memcmp(name, "GNU", 4) == 0 &&
                desc + note.n_descsz <= end) {
              s->h->bytes(desc, note.n_descsz);
              if (info->dlpi_name == nullptr || info->dlpi_name[0] == '\0') s->program = true;
            }
            p = desc + ((note.n_descsz + 3) & ~3U);
          }
        }
        return 0;
      },
      &seen);
  return seen.program;
}

void hash_route(Hash& h, const sim::RouteDef& r) {
  h.text(r.name);
  for (const auto& p : r.points) {
    for (const double v : {p.lat_deg, p.lon_deg, p.elev_m}) h.number(v);
  }
  for (const auto& c : r.cells) {
    h.text(c.id);
    h.text(c.surface);
    for (const double v : {c.start_m, c.end_m, c.crr, c.gd_n0_m3, c.joint_spacing_m}) h.number(v);
  }
  h.number(r.default_crr);
  h.number(r.default_gd_n0_m3);
}

void hash_scenario(Hash& h, const sim::Scenario& s) {
  h.text(format_vehicle(s.vehicle));
  hash_route(h, s.route);
  const sim::ClockSpec& c = s.clocks;
  for (const double v : {c.can_rx_latency.count(), c.can_rx_jitter.count(), c.ecu_drift_ppm, c.accel_offset.count(),
                         c.accel_drift_ppm, c.gnss_latency.count(), c.weather_offset.count()}) {
    h.number(v);
  }
  for (const auto& e : sim::effect_catalog()) {
    h.text(e.name);
    h.number(s.effects.on(e.id) ? s.effects.magnitude(e.id) : 0.0);
  }
  for (const double v : {s.start_m, s.end_m, static_cast<double>(s.road_seed), s.weather.wander_mps, static_cast<double>(s.unsprung),
                         s.accel_rate_hz, static_cast<double>(s.accelerometers), s.gnss_rate_hz, s.physics_rate_hz,
                         s.engine_friction_scale, s.accessory_scale, s.cda_scale, s.tire_radius_scale, s.tire_crr_scale,
                         s.coast ? 1.0 : 0.0, s.stops.every_m, s.stops.crawl_mps, s.stops.crawl_m, s.hold.count()}) {
    h.number(v);
  }
  for (const double v : s.hold_rpm) h.number(v);
}

void hash_database(Hash& h, const j1939::Database& db) {
  for (const auto& m : db.messages()) {
    h.number(m.pgn);
    h.number(m.length);
    h.number(m.cycle_time_ms);
    for (const auto& g : m.signals) {
      h.text(g.name);
      for (const double v :
           {static_cast<double>(g.spn), static_cast<double>(g.start_bit), static_cast<double>(g.length), static_cast<double>(g.order),
            g.is_signed ? 1.0 : 0.0, g.factor, g.offset, g.minimum, g.maximum, g.j1939_ranges ? 1.0 : 0.0}) {
        h.number(v);
      }
    }
  }
}

}  // namespace

std::string library_fingerprint(const std::vector<sim::Scenario>& resims, const j1939::Database& db, const GapOptions& options) {
  Hash h;
  if (!hash_build_ids(h)) return {};
  h.text("roadload-gap-library 1");
  for (const sim::Scenario& s : resims) hash_scenario(h, s);
  hash_database(h, db);
  const DecisionRule& r = options.rule;
  for (const double v : {static_cast<double>(options.noise_runs), static_cast<double>(options.holdout), r.null_gain, r.null_factor,
                         r.pair_gain, r.pair_share, r.penalty, static_cast<double>(r.pair_pool), r.range_tolerance, r.truck_sigmas}) {
    h.number(v);
  }
  return h.hex();
}

}  // namespace roadload::gap
