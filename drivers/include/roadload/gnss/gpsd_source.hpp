#pragma once
// GNSS fixes from gpsd through its client library (libgps 3.22). gpsd owns the receiver, its
// protocol (NMEA, u-blox, SiRF, ...) and its PPS device; the logger only reads its reports: TPV for
// fixes, SKY for the HDOP, PPS and TOFF for time (docs/gnss.md).
//
// A fix is stamped with CLOCK_MONOTONIC when the daemon reads it (StampSource::userspace), so `t`
// lags the fix's epoch by the receiver's output delay, the serial line and gpsd; utc_ns is when the
// fix was taken, and utc_map() relates the two.
//
// gpsd going away is a state, not an error: the source goes down and later reads reconnect, 0.25 s
// after the loss, then twice as long after each failure up to 8 s. Reconnecting allocates inside
// libgps (its buffer, the address lookup); reading does not.
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>

#include "roadload/clock/realtime_map.hpp"
#include "roadload/gnss/utc_map.hpp"
#include "roadload/io/replay_clock.hpp"
#include "roadload/io/source.hpp"
#include "roadload/parse_error.hpp"
#include "roadload/samples.hpp"

struct gps_data_t;

namespace roadload::gnss {

struct GpsdCounters {
  std::uint64_t no_fix = 0;       // TPV reports without a 2D or 3D fix (cold start, tunnel)
  std::uint64_t repeats = 0;      // TPVs with the time of the fix delivered last (gpsd's first cycles)
  std::uint64_t toff = 0;         // TOFF reports (gpsd's own receipt stamp of a fix) taken as fix times
  std::uint64_t pps = 0;          // PPS edges the UTC map took
  std::uint64_t pps_refused = 0;  // PPS edges the UTC map refused: labelled with the wrong second
  std::uint64_t unplaced = 0;     // PPS or TOFF stamps not placeable on the capture clock (wall clock stepped)
};

class GpsdSource final : public io::Source<GnssFix> {
 public:
  // Connects to gpsd (host "localhost", port "2947" on a gateway) and asks for JSON reports and PPS.
  // A gpsd that cannot be reached leaves the source down and retrying; it is not an error here.
  static Parsed<std::unique_ptr<GpsdSource>> open(const std::string& host, const std::string& port);
  ~GpsdSource() override;
  GpsdSource(const GpsdSource&) = delete;
  GpsdSource& operator=(const GpsdSource&) = delete;

  // Delivers one fix per new TPV time with mode 2D or better; once one is delivered, drains only
  // what gpsd has already sent. While down, waits for the next reconnection attempt within `timeout`.
  std::size_t read(std::span<GnssFix> out, Nanoseconds timeout) override;
  const io::SourceStatus& status() const override { return status_; }
  const char* name() const override { return name_; }
  const UtcMap& utc_map() const { return utc_; }
  const GpsdCounters& counters() const { return counters_; }

 private:
  GpsdSource(std::string host, std::string port);
  // Opens the connection and starts the watch; a libgps error text, or nullptr.
  const char* connect();
  void go_down(const char* why);
  bool try_reconnect(CaptureTime deadline);
  // Takes the report gps_read just unpacked; true when it filled `fix`.
  bool take_report(CaptureTime read, GnssFix& fix);
  bool take_tpv(CaptureTime read, GnssFix& fix);
  void take_time_offset(bool pps);
  void refresh_detail();

  std::string host_, port_;
  char name_[64] = {};
  std::unique_ptr<gps_data_t> data_;
  bool connected_ = false;
  Nanoseconds backoff_{};
  CaptureTime next_attempt_{};
  std::int64_t last_fix_utc_ns_ = 0;  // time of the fix delivered last
  GnssFixMode mode_ = GnssFixMode::none;
  double hdop_ = std::numeric_limits<double>::quiet_NaN();  // the last SKY's (gpsd 3.22 has no HDOP in TPV)
  struct Shown {
    GnssFixMode mode = GnssFixMode::none;
    int hdop_tenths = -2;  // -1: unknown; -2: nothing shown yet
    bool pps = false;
    bool operator==(const Shown&) const = default;
  } shown_;
  io::MonotonicClock clock_;
  clock::RealtimeMap realtime_;  // gpsd stamps PPS and TOFF with CLOCK_REALTIME
  UtcMap utc_;
  GpsdCounters counters_;
  io::SourceStatus status_;
};

}  // namespace roadload::gnss
