#pragma once
// One CAN bus through a CAN_RAW socket. The daemon only listens: it never writes to the socket
// (the controller's listen-only mode is the interface's setting, `ip link set can0 type can
// listen-only on`, made by the system's network configuration, not by a process that reads).
//
// Frames are stamped by the kernel at receive (SO_TIMESTAMPING: hardware when the controller
// gives it, else software, CLOCK_REALTIME) and mapped into the capture clock through a
// RealtimeMap, so a wall-clock step neither shifts nor reorders them. The kernel's count of
// frames dropped for want of queue space (SO_RXQ_OVFL) is reported as drops. Error frames are
// delivered (they are recorded as candump records them) and counted; bus-off is shown in the
// status. An interface that disappears or goes down leaves the source `down`; it reopens the
// socket by name once a second until the interface is back.
#include <linux/can.h>
#include <sys/socket.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "roadload/can_frame.hpp"
#include "roadload/clock/realtime_map.hpp"
#include "roadload/io/source.hpp"
#include "roadload/parse_error.hpp"

namespace roadload::can {

struct SocketCanConfig {
  std::string interface = "can0";
  std::uint8_t iface_index = 0;          // CanFrame::iface of this bus's frames
  bool j1939_only = true;                // 29-bit data frames (and error frames) only
  int receive_buffer_bytes = 1 << 21;    // room for a second of a full bus at 10x its rate
  std::int64_t coalesce_ns = 1'000'000;  // wait after a drained queue: at most 64 frames per read anyway
};

struct SocketCanCounters {
  std::uint64_t error_frames = 0;
  std::uint64_t bus_off = 0;
  std::uint64_t controller_problems = 0;  // error passive, warning, overflow in the controller
  std::uint64_t reopen_attempts = 0;
};

class SocketCanSource final : public io::Source<CanFrame> {
 public:
  // Frames per recvmmsg. Under User-Mode Linux a system call and a switch between processes cost
  // tens of microseconds: a replay into roadloadd ran at 845 times real time with 256 and at 1,070
  // with 1,024 (tests/bench/replay_rtf.sh). A busy real bus fills a few hundred a read.
  static constexpr std::size_t kBatch = 1024;

  // Fails only on a configuration that can never work (a name too long for an interface).
  // A missing interface is not an error here: the source starts `down` and waits for it.
  static Parsed<std::unique_ptr<SocketCanSource>> open(SocketCanConfig config);
  ~SocketCanSource() override;
  SocketCanSource(const SocketCanSource&) = delete;
  SocketCanSource& operator=(const SocketCanSource&) = delete;

  std::size_t read(std::span<CanFrame> out, Nanoseconds timeout) override;
  const io::SourceStatus& status() const override { return status_; }
  const char* name() const override { return config_.interface.c_str(); }
  const SocketCanCounters& counters() const { return counters_; }
  const clock::RealtimeMap& clock_map() const { return map_; }

 private:
  explicit SocketCanSource(SocketCanConfig config);
  bool try_open();  // sets status_.detail with the reason when it cannot
  void go_down(int err);
  void back_on_bus(const char* how);
  std::int64_t observe_clocks();  // the monotonic clock after the reading
  std::size_t receive(std::span<CanFrame> out);
  bool convert(const ::mmsghdr& m, const ::canfd_frame& f, std::int64_t read_mono_ns, CanFrame& out);

  SocketCanConfig config_;
  int fd_ = -1;
  std::int64_t next_open_mono_ns_ = 0;
  std::uint32_t kernel_drops_ = 0;  // SO_RXQ_OVFL's running count on this socket
  bool last_full_ = false;          // the last receive filled what it was given: more may wait
  std::size_t touched_ = 0;         // headers the last recvmmsg filled, to reset before the next
  clock::RealtimeMap map_;
  io::SourceStatus status_;
  SocketCanCounters counters_;
  bool bus_off_ = false;  // the controller reported bus-off and has not been heard since

  struct Buffers;
  std::unique_ptr<Buffers> buf_;  // recvmmsg's, allocated once at open
};

}  // namespace roadload::can
