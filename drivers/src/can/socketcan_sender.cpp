#include "roadload/can/socketcan_sender.hpp"

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>

namespace roadload::can {

namespace {

// The frame as the kernel takes it: classic frames in can_frame's size, FD frames in canfd_frame's.
std::size_t to_kernel(const CanFrame& f, canfd_frame& k) {
  std::memset(&k, 0, sizeof k);
  k.can_id = f.id;
  switch (f.kind) {
    case CanFrameKind::standard: break;
    case CanFrameKind::extended: k.can_id |= CAN_EFF_FLAG; break;
    case CanFrameKind::error: k.can_id |= CAN_ERR_FLAG; break;
    case CanFrameKind::remote: k.can_id |= CAN_RTR_FLAG | (f.id29 ? CAN_EFF_FLAG : 0u); break;
    case CanFrameKind::fd: k.can_id |= f.id29 ? CAN_EFF_FLAG : 0u; break;
  }
  k.len = f.len;
  std::memcpy(k.data, f.data.data(), f.kind == CanFrameKind::fd ? f.len : std::min<std::size_t>(f.len, 8));
  if (f.kind == CanFrameKind::fd) {
    k.flags = f.fd_flags;
    return CANFD_MTU;
  }
  return CAN_MTU;
}

}  // namespace

Parsed<std::unique_ptr<SocketCanSender>> SocketCanSender::open(const std::string& interface) {
  const unsigned index = if_nametoindex(interface.c_str());
  if (index == 0) return ParseError{interface, 0, "interface", std::string("no such CAN interface: ") + std::strerror(errno)};
  const int fd = socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) return ParseError{interface, 0, "socket", std::strerror(errno)};
  const int on = 1;
  const can_err_mask_t none = 0;
  setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof on);
  setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &none, sizeof none);
  // This socket only writes: no receive filter matches anything.
  setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, nullptr, 0);
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(index);
  if (bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    const int err = errno;
    ::close(fd);
    return ParseError{interface, 0, "bind", std::strerror(err)};
  }
  return std::unique_ptr<SocketCanSender>(new SocketCanSender(fd, interface));
}

SocketCanSender::~SocketCanSender() { ::close(fd_); }

static_assert(SocketCanSender::kBatch <= 1024, "sendmmsg takes at most UIO_MAXIOV (1,024) messages a call");

bool SocketCanSender::send(std::span<const CanFrame> frames) {
  std::array<canfd_frame, kBatch> k;
  std::array<iovec, kBatch> iov;
  std::array<mmsghdr, kBatch> msgs;
  std::size_t done = 0;
  while (done < frames.size()) {
    const std::size_t n = std::min(kBatch, frames.size() - done);
    for (std::size_t i = 0; i < n; ++i) {
      iov[i] = {&k[i], to_kernel(frames[done + i], k[i])};
      std::memset(&msgs[i], 0, sizeof msgs[i]);
      msgs[i].msg_hdr.msg_iov = &iov[i];
      msgs[i].msg_hdr.msg_iovlen = 1;
    }
    const int sent = sendmmsg(fd_, msgs.data(), static_cast<unsigned>(n), 0);
    if (sent > 0) {
      done += static_cast<std::size_t>(sent);
      sent_ += static_cast<std::uint64_t>(sent);
      continue;
    }
    if (sent < 0 && (errno == ENOBUFS || errno == EAGAIN || errno == EINTR)) {
      // CAN_RAW reports writable while the queue is still full: back off briefly instead.
      ++waits_;
      const timespec pause{0, 200'000};
      nanosleep(&pause, nullptr);
      continue;
    }
    error_ = interface_ + ": " + std::strerror(errno);
    return false;
  }
  return true;
}

}  // namespace roadload::can
