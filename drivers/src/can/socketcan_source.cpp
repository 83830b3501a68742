#include "roadload/can/socketcan_source.hpp"

#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <linux/errqueue.h>
#include <linux/net_tstamp.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "roadload/io/posix_time.hpp"

namespace roadload::can {

namespace {

constexpr std::int64_t kReopenPeriodNs = kNsPerS;

std::int64_t clock_ns(clockid_t id) { return io::read_clock(id).count(); }

std::int64_t to_ns(const timespec& ts) { return io::from_timespec(ts).count(); }

}  // namespace

// recvmmsg takes its headers as one contiguous array; the buffers they point to sit beside it.
static_assert(SocketCanSource::kBatch <= 1024, "recvmmsg takes at most UIO_MAXIOV (1,024) messages a call");

struct SocketCanSource::Buffers {
  std::array<mmsghdr, kBatch> msgs;
  std::array<canfd_frame, kBatch> frames;
  std::array<iovec, kBatch> iov;
  // SCM_TIMESTAMPING and SO_RXQ_OVFL, with room to spare.
  struct alignas(cmsghdr) Control {
    char bytes[CMSG_SPACE(sizeof(scm_timestamping)) + CMSG_SPACE(sizeof(std::uint32_t)) + 64];
  };
  std::array<Control, kBatch> control;
};

Parsed<std::unique_ptr<SocketCanSource>> SocketCanSource::open(SocketCanConfig config) {
  if (config.interface.empty() || config.interface.size() >= IFNAMSIZ) {
    return ParseError{"can", 0, "interface",
                      "'" + config.interface + "' is not an interface name (1 to " + std::to_string(IFNAMSIZ - 1) + " characters)"};
  }
  std::unique_ptr<SocketCanSource> s(new SocketCanSource(std::move(config)));
  s->try_open();
  return s;
}

SocketCanSource::SocketCanSource(SocketCanConfig config) : config_(std::move(config)), buf_(std::make_unique<Buffers>()) {
  for (std::size_t i = 0; i < kBatch; ++i) {
    buf_->iov[i] = {&buf_->frames[i], sizeof(canfd_frame)};
    std::memset(&buf_->msgs[i], 0, sizeof(mmsghdr));
    buf_->msgs[i].msg_hdr.msg_iov = &buf_->iov[i];
    buf_->msgs[i].msg_hdr.msg_iovlen = 1;
    buf_->msgs[i].msg_hdr.msg_control = buf_->control[i].bytes;
    buf_->msgs[i].msg_hdr.msg_controllen = sizeof buf_->control[i].bytes;
  }
  status_.stamps = StampSource::kernel;
}

SocketCanSource::~SocketCanSource() {
  if (fd_ >= 0) ::close(fd_);
}

bool SocketCanSource::try_open() {
  ++counters_.reopen_attempts;
  // Until the socket is bound the bus is not heard: down, with the reason in detail.
  status_.state = io::SourceState::down;
  next_open_mono_ns_ = clock_ns(CLOCK_MONOTONIC) + kReopenPeriodNs;
  const char* iface = config_.interface.c_str();
  const unsigned index = if_nametoindex(iface);
  if (index == 0) {
    std::snprintf(status_.detail, sizeof status_.detail, "no interface %s", iface);
    return false;
  }
  const int fd = socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC | SOCK_NONBLOCK, CAN_RAW);
  if (fd < 0) {
    std::snprintf(status_.detail, sizeof status_.detail, "socket: %s", std::strerror(errno));
    return false;
  }
  ifreq ifr{};
  std::memcpy(ifr.ifr_name, iface, config_.interface.size() + 1);
  if (ioctl(fd, SIOCGIFFLAGS, &ifr) == 0 && (ifr.ifr_flags & IFF_UP) == 0) {
    std::snprintf(status_.detail, sizeof status_.detail, "%s is down", iface);
    ::close(fd);
    return false;
  }
  const int on = 1;
  const can_err_mask_t errors = CAN_ERR_MASK;
  const int stamping = SOF_TIMESTAMPING_RX_SOFTWARE | SOF_TIMESTAMPING_SOFTWARE;
  bool ok = setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof on) == 0 &&
            setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errors, sizeof errors) == 0 &&
            setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on) == 0 &&
            setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPING, &stamping, sizeof stamping) == 0;
  if (ok && config_.j1939_only) {
    const can_filter j1939{CAN_EFF_FLAG, CAN_EFF_FLAG | CAN_RTR_FLAG};
    ok = setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, &j1939, sizeof j1939) == 0;
  }
  // FORCE exceeds rmem_max when the daemon has CAP_NET_ADMIN; without it the plain option applies.
  if (ok && setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &config_.receive_buffer_bytes, sizeof(int)) != 0) {
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &config_.receive_buffer_bytes, sizeof(int));
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(index);
  // Read before the socket receives: every frame it will hold is stamped after this reading, and
  // the map places them all with its offset, however late the first read comes (a slow start).
  observe_clocks();
  if (!ok || bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    std::snprintf(status_.detail, sizeof status_.detail, "%s: %s", iface, std::strerror(errno));
    ::close(fd);
    return false;
  }
  if (fd_ >= 0) ::close(fd_);
  fd_ = fd;
  kernel_drops_ = 0;
  if (status_.items > 0) ++status_.restarts;
  status_.state = io::SourceState::waiting;
  std::snprintf(status_.detail, sizeof status_.detail, "listening");
  return true;
}

void SocketCanSource::go_down(int err) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  status_.state = io::SourceState::down;
  std::snprintf(status_.detail, sizeof status_.detail, "%s: %s", config_.interface.c_str(), std::strerror(err));
  next_open_mono_ns_ = clock_ns(CLOCK_MONOTONIC) + kReopenPeriodNs;
}

void SocketCanSource::back_on_bus(const char* how) {
  if (!bus_off_) return;
  bus_off_ = false;
  ++status_.restarts;
  status_.state = io::SourceState::up;
  std::snprintf(status_.detail, sizeof status_.detail, "%s", how);
}

std::int64_t SocketCanSource::observe_clocks() {
  clock::ClockReading r;
  r.mono_before_ns = clock_ns(CLOCK_MONOTONIC);
  r.realtime_ns = clock_ns(CLOCK_REALTIME);
  r.mono_after_ns = clock_ns(CLOCK_MONOTONIC);
  map_.observe(r);
  return r.mono_after_ns;
}

std::size_t SocketCanSource::read(std::span<CanFrame> out, Nanoseconds timeout) {
  if (fd_ < 0) {
    const std::int64_t now = clock_ns(CLOCK_MONOTONIC);
    const std::int64_t wait = std::min(timeout.count(), std::max<std::int64_t>(0, next_open_mono_ns_ - now));
    if (wait > 0) {
      const timespec ts = io::to_timespec(Nanoseconds{wait});
      nanosleep(&ts, nullptr);
    }
    if (clock_ns(CLOCK_MONOTONIC) < next_open_mono_ns_ || !try_open()) return 0;
  }
  // After a full batch the queue most likely holds more: read it before asking poll, one system
  // call a batch instead of two while a bus (or a replay) outruns the reads.
  if (last_full_) {
    const std::size_t n = receive(out);
    if (n > 0 || fd_ < 0) return n;
  }
  pollfd p{fd_, POLLIN, 0};
  const int ms = static_cast<int>(std::clamp<std::int64_t>(timeout.count() / 1'000'000, 0, 60'000));
  const int ready = poll(&p, 1, ms);
  if (ready < 0) return 0;  // EINTR: the caller loops
  if (ready == 0) return 0;
  // Once the queue has been drained, let a batch gather before reading again: one wake-up per
  // batch instead of one per frame. The kernel stamps the frames; the wait only delays reading.
  if (!last_full_ && config_.coalesce_ns > 0) {
    const timespec pause{0, static_cast<long>(config_.coalesce_ns)};
    nanosleep(&pause, nullptr);
  }
  return receive(out);
}

std::size_t SocketCanSource::receive(std::span<CanFrame> out) {
  const std::size_t want = std::min(out.size(), kBatch);
  // Only the headers the last call filled were changed by the kernel: a truck's bus brings a few
  // frames a read, and resetting all 1,024 each time cost more than reading them.
  for (std::size_t i = 0; i < touched_; ++i) {
    msghdr& h = buf_->msgs[i].msg_hdr;
    h.msg_controllen = sizeof buf_->control[i].bytes;
    h.msg_flags = 0;
  }
  touched_ = 0;
  const int got = recvmmsg(fd_, buf_->msgs.data(), static_cast<unsigned>(want), MSG_DONTWAIT, nullptr);
  if (got < 0) {
    last_full_ = false;
    if (errno == EAGAIN || errno == EINTR) return 0;
    go_down(errno);
    return 0;
  }
  // One reading of both clocks per batch, which ends after every frame of it was received.
  const std::int64_t read_mono = observe_clocks();
  status_.clock_steps = map_.counters().steps;
  std::size_t n = 0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(got); ++i) {
    if (convert(buf_->msgs[i], buf_->frames[i], read_mono, out[n])) ++n;
  }
  status_.items += n;
  touched_ = static_cast<std::size_t>(got);
  last_full_ = want > 0 && static_cast<std::size_t>(got) == want;
  if (n > 0 && status_.state == io::SourceState::waiting) {
    status_.state = io::SourceState::up;
    std::snprintf(status_.detail, sizeof status_.detail, "receiving");
  }
  return n;
}

bool SocketCanSource::convert(const mmsghdr& m, const canfd_frame& f, std::int64_t read_mono_ns, CanFrame& out) {
  std::int64_t realtime_ns = -1;
  for (cmsghdr* c = CMSG_FIRSTHDR(&m.msg_hdr); c != nullptr; c = CMSG_NXTHDR(const_cast<msghdr*>(&m.msg_hdr), c)) {
    if (c->cmsg_level != SOL_SOCKET) continue;
    if (c->cmsg_type == SO_TIMESTAMPING) {
      scm_timestamping ts;
      std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
      realtime_ns = to_ns(ts.ts[0]);
    } else if (c->cmsg_type == SO_RXQ_OVFL) {
      std::uint32_t dropped;
      std::memcpy(&dropped, CMSG_DATA(c), sizeof dropped);
      // The kernel's count is cumulative per socket and wraps at 2^32.
      status_.dropped += static_cast<std::uint32_t>(dropped - kernel_drops_);
      kernel_drops_ = dropped;
    }
  }
  const bool fd_frame = m.msg_len == CANFD_MTU;
  if (!fd_frame && m.msg_len != CAN_MTU) {
    ++status_.errors;
    return false;
  }
  std::optional<CaptureTime> t;
  if (realtime_ns >= 0) t = map_.map(realtime_ns, read_mono_ns);
  if (!t) {
    ++status_.userspace_stamps;
    t = capture_time_from_ns(read_mono_ns);
  }
  out.t = *t;
  out.iface = config_.iface_index;
  out.fd_flags = 0;
  out.id29 = (f.can_id & CAN_EFF_FLAG) != 0;
  out.len = std::min<std::uint8_t>(f.len, fd_frame ? 64 : 8);
  std::memcpy(out.data.data(), f.data, out.len);
  if ((f.can_id & CAN_ERR_FLAG) != 0) {
    out.kind = CanFrameKind::error;
    out.id = f.can_id & CAN_ERR_MASK;
    ++counters_.error_frames;
    ++status_.errors;
    if ((f.can_id & CAN_ERR_BUSOFF) != 0) {
      ++counters_.bus_off;
      bus_off_ = true;
      status_.state = io::SourceState::down;
      std::snprintf(status_.detail, sizeof status_.detail, "bus-off");
    } else if ((f.can_id & CAN_ERR_RESTARTED) != 0) {
      back_on_bus("restarted after bus-off");
    } else if ((f.can_id & CAN_ERR_PROT) != 0) {
      std::snprintf(status_.detail, sizeof status_.detail, "protocol violation");
    } else if ((f.can_id & CAN_ERR_CRTL) != 0) {
      ++counters_.controller_problems;
    }
  } else if (fd_frame) {
    out.kind = CanFrameKind::fd;
    out.id = f.can_id & (out.id29 ? CAN_EFF_MASK : CAN_SFF_MASK);
    out.fd_flags = f.flags & 0xF;
  } else if ((f.can_id & CAN_RTR_FLAG) != 0) {
    out.kind = CanFrameKind::remote;
    out.id = f.can_id & (out.id29 ? CAN_EFF_MASK : CAN_SFF_MASK);
  } else {
    if (bus_off_) back_on_bus("receiving after bus-off");
    out.kind = out.id29 ? CanFrameKind::extended : CanFrameKind::standard;
    out.id = f.can_id & (out.id29 ? CAN_EFF_MASK : CAN_SFF_MASK);
  }
  return true;
}

}  // namespace roadload::can
