#include "roadload/accel/spi_bus.hpp"

#include <fcntl.h>
#include <linux/spi/spidev.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace roadload::accel {

Parsed<std::unique_ptr<SpidevBus>> SpidevBus::open(const std::string& path, std::uint32_t speed_hz, std::uint8_t mode) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return ParseError{path, 0, "open", std::strerror(errno)};
  const std::uint8_t bits = 8;
  const char* failed = ioctl(fd, SPI_IOC_WR_MODE, &mode) != 0               ? "SPI_IOC_WR_MODE"
                       : ioctl(fd, SPI_IOC_WR_BITS_PER_WORD, &bits) != 0    ? "SPI_IOC_WR_BITS_PER_WORD"
                       : ioctl(fd, SPI_IOC_WR_MAX_SPEED_HZ, &speed_hz) != 0 ? "SPI_IOC_WR_MAX_SPEED_HZ"
                                                                            : nullptr;
  if (failed != nullptr) {
    ParseError e{path, 0, failed, std::strerror(errno)};
    ::close(fd);
    return e;
  }
  return std::unique_ptr<SpidevBus>(new SpidevBus(fd, speed_hz));
}

SpidevBus::~SpidevBus() { ::close(fd_); }

bool SpidevBus::transfer(std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) {
  if (tx.size() != rx.size() || tx.empty()) return false;
  spi_ioc_transfer xfer{};
  xfer.tx_buf = reinterpret_cast<std::uintptr_t>(tx.data());
  xfer.rx_buf = reinterpret_cast<std::uintptr_t>(rx.data());
  xfer.len = static_cast<std::uint32_t>(tx.size());
  xfer.speed_hz = speed_hz_;
  xfer.bits_per_word = 8;
  return ioctl(fd_, SPI_IOC_MESSAGE(1), &xfer) >= 0;
}

}  // namespace roadload::accel
