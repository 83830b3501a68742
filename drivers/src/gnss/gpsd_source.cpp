#include "roadload/gnss/gpsd_source.hpp"

#include <gps.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "roadload/io/posix_time.hpp"

namespace roadload::gnss {

namespace {

constexpr Nanoseconds kFirstBackoff{250'000'000};
constexpr Nanoseconds kMaxBackoff{8 * kNsPerS};
// A PPS report arrives within milliseconds of its edge; a TOFF's stamp is the start of its fix's
// cycle on the serial line, up to a second (4800 baud, many sentences) before gpsd reports it.
constexpr clock::RealtimeMapConfig kRealtimeConfig{200'000, 2 * kNsPerS, 1'000'000};

std::int64_t ns(const timespec& ts) { return io::from_timespec(ts).count(); }

clock::ClockReading read_clocks() {
  const Nanoseconds before = io::read_clock(CLOCK_MONOTONIC);
  const Nanoseconds realtime = io::read_clock(CLOCK_REALTIME);
  const Nanoseconds after = io::read_clock(CLOCK_MONOTONIC);
  return {before.count(), realtime.count(), after.count()};
}

// gpsd reports 2D/3D in `mode` and how the fix was made (DGPS, RTK) in `status`.
GnssFixMode fix_mode(const gps_fix_t& f) {
  if (f.mode < MODE_2D) return GnssFixMode::none;
  if (f.status == STATUS_DGPS_FIX) return GnssFixMode::dgps;
  if (f.status == STATUS_RTK_FIX || f.status == STATUS_RTK_FLT) return GnssFixMode::rtk;
  return f.mode == MODE_2D ? GnssFixMode::fix_2d : GnssFixMode::fix_3d;
}

const char* mode_text(GnssFixMode m) {
  switch (m) {
    case GnssFixMode::none: return "no fix";
    case GnssFixMode::fix_2d: return "2D";
    case GnssFixMode::fix_3d: return "3D";
    case GnssFixMode::dgps: return "DGPS";
    case GnssFixMode::rtk: return "RTK";
  }
  return "?";
}

bool usable(const gps_fix_t& f) {
  return std::isfinite(f.latitude) && std::isfinite(f.longitude) && std::abs(f.latitude) <= 90.0 && std::abs(f.longitude) <= 180.0 &&
         f.time.tv_sec > 0 && f.time.tv_nsec >= 0 && f.time.tv_nsec < kNsPerS;
}

}  // namespace

Parsed<std::unique_ptr<GpsdSource>> GpsdSource::open(const std::string& host, const std::string& port) {
  std::unique_ptr<GpsdSource> source(new GpsdSource(host, port));
  // gpsd may come up after the daemon (boot order, a restart): down and retrying, not an error.
  if (const char* why = source->connect()) {
    source->go_down(why);
  } else {
    source->refresh_detail();
  }
  return source;
}

GpsdSource::GpsdSource(std::string host, std::string port)
    : host_(std::move(host)), port_(std::move(port)), data_(std::make_unique<gps_data_t>()), realtime_(kRealtimeConfig) {
  std::snprintf(name_, sizeof name_, "gpsd %s:%s", host_.c_str(), port_.c_str());
  status_.stamps = StampSource::userspace;
}

GpsdSource::~GpsdSource() {
  if (connected_) gps_close(data_.get());
}

const char* GpsdSource::connect() {
  if (gps_open(host_.c_str(), port_.c_str(), data_.get()) != 0) return gps_errstr(errno);
  if (gps_stream(data_.get(), WATCH_ENABLE | WATCH_JSON | WATCH_PPS, nullptr) != 0) {
    gps_close(data_.get());
    return "could not send the WATCH request";
  }
  connected_ = true;
  status_.state = io::SourceState::waiting;
  mode_ = GnssFixMode::none;
  hdop_ = std::numeric_limits<double>::quiet_NaN();
  return nullptr;
}

void GpsdSource::go_down(const char* why) {
  if (connected_) gps_close(data_.get());
  connected_ = false;
  status_.state = io::SourceState::down;
  shown_ = {};  // the detail now says down; the next connection rewrites it
  backoff_ = kFirstBackoff;
  next_attempt_ = clock_.now() + backoff_;
  std::snprintf(status_.detail, sizeof status_.detail, "%s down: %s", name_, why);
}

bool GpsdSource::try_reconnect(CaptureTime deadline) {
  if (clock_.now() < next_attempt_) clock_.sleep_until(std::min(next_attempt_, deadline), kMaxBackoff);
  if (clock_.now() < next_attempt_) return false;
  if (const char* why = connect()) {
    backoff_ = std::min(backoff_ * 2, kMaxBackoff);
    next_attempt_ = clock_.now() + backoff_;
    std::snprintf(status_.detail, sizeof status_.detail, "%s down: %s; retry in %.2g s", name_, why, to_seconds(backoff_));
    return false;
  }
  ++status_.restarts;
  return true;
}

std::size_t GpsdSource::read(std::span<GnssFix> out, Nanoseconds timeout) {
  const CaptureTime deadline = clock_.now() + timeout;
  if (!connected_ && !try_reconnect(deadline)) return 0;
  std::size_t n = 0;
  while (n < out.size()) {
    // Once a fix is out, only what gpsd has already sent: the caller is waiting for it.
    const std::int64_t wait_us = n > 0 ? 0 : std::clamp<std::int64_t>((deadline - clock_.now()).count() / 1000, 0, INT_MAX);
    if (!gps_waiting(data_.get(), static_cast<int>(wait_us))) break;
    data_->set = 0;  // libgps only adds bits; cleared, they name what this one report carried
    const int got = gps_read(data_.get(), nullptr, 0);
    const CaptureTime read = clock_.now();
    if (got < 0) {
      go_down(errno != 0 ? std::strerror(errno) : "gpsd closed the connection");
      break;
    }
    if (got > 0 && take_report(read, out[n])) ++n;
    // Half a line buffered: libgps says "waiting" until the rest comes, which gpsd sends at once.
    if (got == 0 && (n > 0 || read >= deadline)) break;
  }
  if (connected_) refresh_detail();
  return n;
}

bool GpsdSource::take_report(CaptureTime read, GnssFix& fix) {
  const gps_mask_t set = data_->set;
  if ((set & (PPS_SET | TOFF_SET)) != 0) take_time_offset((set & PPS_SET) != 0);
  if ((set & SATELLITE_SET) != 0 && std::isfinite(data_->dop.hdop)) hdop_ = data_->dop.hdop;
  // Only a TPV sets MODE_SET.
  return (set & MODE_SET) != 0 && take_tpv(read, fix);
}

bool GpsdSource::take_tpv(CaptureTime read, GnssFix& fix) {
  const gps_fix_t& f = data_->fix;
  const GnssFixMode mode = fix_mode(f);
  // gpsd reports a mode from GSA before the receiver has sent a timed sentence: no fix yet.
  if (mode == GnssFixMode::none || (data_->set & TIME_SET) == 0) {
    ++counters_.no_fix;
    mode_ = GnssFixMode::none;
    status_.state = io::SourceState::waiting;
    return false;
  }
  if (!usable(f)) {
    ++status_.errors;
    return false;
  }
  const std::int64_t utc_ns = ns(f.time);
  // Until gpsd has learnt which sentence ends a cycle it reports the cycle after each sentence.
  if (utc_ns == last_fix_utc_ns_) {
    ++counters_.repeats;
    return false;
  }
  last_fix_utc_ns_ = utc_ns;
  fix = GnssFix{read, utc_ns, f.latitude, f.longitude, f.altHAE, f.speed, f.track, mode, hdop_};
  utc_.observe_fix(utc_ns, read);
  ++status_.items;
  mode_ = mode;
  status_.state = io::SourceState::up;
  return true;
}

// libgps 3.22 unpacks both PPS and TOFF into gps_data_t.pps (toff stays zero): `real` is the UTC
// of the PPS edge or of the fix, `clock` gpsd's CLOCK_REALTIME at the edge or at the start of the
// fix's cycle. A TOFF is a fix read earlier than its TPV, so it tightens the fix-time bound.
void GpsdSource::take_time_offset(bool pps) {
  const clock::ClockReading now = read_clocks();
  realtime_.observe(now);
  const auto at = realtime_.map(ns(data_->pps.clock), now.mono_after_ns);
  if (!at) {
    ++counters_.unplaced;
  } else if (!pps) {
    utc_.observe_fix(ns(data_->pps.real), *at);
    ++counters_.toff;
  } else if (utc_.observe_pps(ns(data_->pps.real), *at)) {
    ++counters_.pps;
  } else {
    ++counters_.pps_refused;
  }
}

// Rewritten only when what it shows changes: the status thread copies it out between reads.
void GpsdSource::refresh_detail() {
  const Shown now{mode_, std::isfinite(hdop_) ? static_cast<int>(std::lround(hdop_ * 10)) : -1,
                  utc_.offset().source == UtcSource::pps};
  if (now == shown_) return;
  shown_ = now;
  char hdop[16] = "";
  if (now.hdop_tenths >= 0 && mode_ != GnssFixMode::none) std::snprintf(hdop, sizeof hdop, " hdop %.1f", hdop_);
  std::snprintf(status_.detail, sizeof status_.detail, "gpsd %s%s%s", mode_text(mode_), hdop, now.pps ? " pps" : "");
}

}  // namespace roadload::gnss
