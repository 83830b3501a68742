// Reads fixes from a gpsd with GpsdSource as the daemon would, for the gpsfake tests: the fixes as
// gnss.csv rows (docs/recording-format.md) on stdout; each change of state, and the counters at
// the end, on stderr, with the heap allocations made inside read() calls that began connected
// (reconnecting allocates in libgps: its buffer, the address lookup).
//
// usage: gpsd_probe HOST PORT FIXES TIMEOUT_S
// Exits 0 after FIXES fixes, 2 when TIMEOUT_S passes first, 1 when gpsd cannot be reached.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "roadload/gnss/gpsd_source.hpp"
#include "roadload/recording/writer.hpp"

namespace {
bool g_counting = false;  // one thread
std::size_t g_allocations = 0;
}  // namespace

// libgps is C, so operator new would not see its allocations: malloc itself is counted and passed
// on to glibc's. AddressSanitizer owns malloc; under it nothing is counted ("-").
#ifndef __SANITIZE_ADDRESS__
constexpr bool kCounted = true;
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* __libc_calloc(std::size_t n, std::size_t size);
extern "C" void* __libc_realloc(void* p, std::size_t size);
extern "C" void* malloc(std::size_t size) noexcept {
  g_allocations += g_counting;
  return __libc_malloc(size);
}
extern "C" void* calloc(std::size_t n, std::size_t size) noexcept {
  g_allocations += g_counting;
  return __libc_calloc(n, size);
}
extern "C" void* realloc(void* p, std::size_t size) noexcept {
  g_allocations += g_counting;
  return __libc_realloc(p, size);
}
#else
constexpr bool kCounted = false;
#endif

namespace {

using roadload::Nanoseconds;
using roadload::gnss::GpsdSource;

void put(std::string_view text) { std::fwrite(text.data(), 1, text.size(), stdout); }

void print_state(const roadload::io::SourceStatus& s) {
  std::fprintf(stderr, "state %s: %s\n", roadload::io::to_string(s.state), s.detail);
}

unsigned long long u(std::uint64_t v) { return static_cast<unsigned long long>(v); }

void print_counters(const GpsdSource& g, std::size_t allocations) {
  const auto& s = g.status();
  const auto& c = g.counters();
  char counted[24] = "-";
  if (kCounted) std::snprintf(counted, sizeof counted, "%zu", allocations);
  std::fprintf(stderr,
               "counters: items %llu errors %llu restarts %llu no_fix %llu repeats %llu toff %llu pps %llu "
               "pps_refused %llu unplaced %llu allocations_in_reads %s\n",
               u(s.items), u(s.errors), u(s.restarts), u(c.no_fix), u(c.repeats), u(c.toff), u(c.pps), u(c.pps_refused),
               u(c.unplaced), counted);
  const auto utc = g.utc_map().offset();
  std::fprintf(stderr, "utc: offset_ns %lld sigma_ns %lld source %s\n", static_cast<long long>(utc.utc_minus_capture_ns),
               static_cast<long long>(utc.sigma_ns), roadload::gnss::to_string(utc.source));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: gpsd_probe HOST PORT FIXES TIMEOUT_S\n");
    return 64;
  }
  const long want = std::atol(argv[3]);
  const double timeout_s = std::atof(argv[4]);
  auto opened = GpsdSource::open(argv[1], argv[2]);
  if (!opened) {
    std::fprintf(stderr, "gpsd_probe: %s\n", opened.error().to_string().c_str());
    return 1;
  }
  GpsdSource& gpsd = *opened.value();
  roadload::io::MonotonicClock clock;
  const auto give_up = clock.now() + Nanoseconds{static_cast<std::int64_t>(timeout_s * 1e9)};

  put(roadload::recording::kGnssFormat.header);
  roadload::recording::LineBuilder line;
  roadload::GnssFix fixes[8];
  long got = 0;
  std::size_t allocations = 0;
  print_state(gpsd.status());
  auto shown = gpsd.status().state;
  char detail[sizeof gpsd.status().detail];
  std::memcpy(detail, gpsd.status().detail, sizeof detail);
  while (got < want && clock.now() < give_up) {
    const bool was_down = gpsd.status().state == roadload::io::SourceState::down;
    g_allocations = 0;
    g_counting = true;
    const std::size_t n = gpsd.read(fixes, Nanoseconds{200'000'000});
    g_counting = false;
    if (!was_down) allocations += g_allocations;
    for (std::size_t i = 0; i < n && got < want; ++i, ++got) put(roadload::recording::format_row(fixes[i], line));
    const auto& s = gpsd.status();
    if (s.state != shown || std::strcmp(s.detail, detail) != 0) {
      shown = s.state;
      std::memcpy(detail, s.detail, sizeof detail);
      print_state(s);
    }
  }
  std::fflush(stdout);
  print_counters(gpsd, allocations);
  return got >= want ? 0 : 2;
}
