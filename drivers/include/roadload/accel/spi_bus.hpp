#pragma once
// The SPI link to one accelerometer. The driver speaks registers through this interface, so the
// same driver runs against spidev on a gateway and against a register-level model in tests.
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "roadload/parse_error.hpp"

namespace roadload::accel {

class SpiBus {
 public:
  virtual ~SpiBus() = default;
  // Full duplex under one chip-select assertion: rx[i] is clocked in while tx[i] goes out
  // (tx.size() == rx.size()). False when the transfer did not happen; nothing is thrown.
  virtual bool transfer(std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) = 0;
};

// /dev/spidevB.C through the spidev ioctls.
class SpidevBus final : public SpiBus {
 public:
  // `mode` is SPI_MODE_0..3 (CPOL, CPHA); words are 8 bits. Errors name the ioctl that failed.
  static Parsed<std::unique_ptr<SpidevBus>> open(const std::string& path, std::uint32_t speed_hz, std::uint8_t mode);
  ~SpidevBus() override;
  SpidevBus(const SpidevBus&) = delete;
  SpidevBus& operator=(const SpidevBus&) = delete;

  bool transfer(std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) override;

 private:
  SpidevBus(int fd, std::uint32_t speed_hz) : fd_(fd), speed_hz_(speed_hz) {}
  int fd_;
  std::uint32_t speed_hz_;
};

}  // namespace roadload::accel
