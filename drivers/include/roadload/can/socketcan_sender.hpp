#pragma once
// Puts recorded frames onto a CAN interface (a vcan on a bench, never a truck's bus): the write
// side of `roadload replay`. Frames go out in batches through sendmmsg, so a replay at full speed
// costs one system call per batch; a full transmit queue (ENOBUFS) is waited out, not dropped.
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "roadload/can_frame.hpp"
#include "roadload/parse_error.hpp"

namespace roadload::can {

class SocketCanSender {
 public:
  // Frames per sendmmsg: 1,024 rather than 256 took a replay into roadloadd under User-Mode Linux
  // from 1,070 to 1,230 times real time (tests/bench/replay_rtf.sh).
  static constexpr std::size_t kBatch = 1024;

  static Parsed<std::unique_ptr<SocketCanSender>> open(const std::string& interface);
  ~SocketCanSender();
  SocketCanSender(const SocketCanSender&) = delete;
  SocketCanSender& operator=(const SocketCanSender&) = delete;

  // Sends every frame, in order; false with error() set when the interface fails for good.
  bool send(std::span<const CanFrame> frames);
  const std::string& error() const { return error_; }
  std::uint64_t sent() const { return sent_; }
  std::uint64_t waits() const { return waits_; }  // times the transmit queue was full

 private:
  SocketCanSender(int fd, std::string interface) : fd_(fd), interface_(std::move(interface)) {}
  int fd_;
  std::string interface_;
  std::string error_;
  std::uint64_t sent_ = 0, waits_ = 0;
};

}  // namespace roadload::can
