#pragma once
// The ADXL355 3-axis accelerometer on SPI: identity check, reset, range and output rate, and FIFO
// bursts converted to m/s². Register facts from the ADXL354/ADXL355 data sheet;
// see docs/accelerometer.md.
//
// The FIFO holds 96 entries, one axis each (32 x/y/z sets). An entry is a 20-bit two's complement
// value left-justified in 3 bytes; bit 0 of the last byte marks an x-axis entry, bit 1 an empty
// FIFO. Sets are rebuilt from the x marker, so an entry lost or read out of turn costs one sample
// (delivered as a hole, never as data) instead of shifting every later axis.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "roadload/accel/spi_bus.hpp"
#include "roadload/parse_error.hpp"

namespace roadload::accel {

namespace adxl355 {
inline constexpr std::uint8_t kDevIdAd = 0x00, kDevIdMst = 0x01, kPartId = 0x02, kRevId = 0x03;
inline constexpr std::uint8_t kStatus = 0x04, kFifoEntries = 0x05, kTemp2 = 0x06, kTemp1 = 0x07;
inline constexpr std::uint8_t kXData3 = 0x08, kFifoData = 0x11;
inline constexpr std::uint8_t kFilter = 0x28, kFifoSamples = 0x29, kIntMap = 0x2A, kSync = 0x2B;
inline constexpr std::uint8_t kRange = 0x2C, kPowerCtl = 0x2D, kReset = 0x2F;

inline constexpr std::uint8_t kDevIdAdValue = 0xAD, kDevIdMstValue = 0x1D, kPartIdValue = 0xED;
inline constexpr std::uint8_t kResetCode = 0x52;

inline constexpr std::uint8_t kStatusDataRdy = 1 << 0, kStatusFifoFull = 1 << 1, kStatusFifoOvr = 1 << 2;
inline constexpr std::uint8_t kStatusNvmBusy = 1 << 4;
inline constexpr std::uint8_t kPowerStandby = 1 << 0, kPowerDrdyOff = 1 << 2;
inline constexpr std::uint8_t kRangeMask = 0x03;      // 1: ±2 g, 2: ±4 g, 3: ±8 g
inline constexpr std::uint8_t kFilterOdrMask = 0x0F;  // 0: 4000 Hz ... 10: 3.906 Hz, halving
inline constexpr std::uint8_t kFifoEntriesMask = 0x7F;
inline constexpr std::uint8_t kEntryX = 1 << 0, kEntryEmpty = 1 << 1;

inline constexpr std::size_t kFifoEntriesMax = 96;
inline constexpr double kLsbPerG2g = 256000;  // typical sensitivity at ±2 g; halves per range step
inline constexpr double kStandardGravity = 9.80665;
// m/s^2 per count at RANGE code 1, 2 or 3 (±2, ±4, ±8 g): every sample is a whole number of it,
// which is what lets a recording store the counts (recording/flac_accel.hpp).
constexpr double mps2_per_lsb(int range_code) { return kStandardGravity / (kLsbPerG2g / static_cast<double>(1 << (range_code - 1))); }

constexpr std::uint8_t read_command(std::uint8_t reg) { return static_cast<std::uint8_t>(reg << 1 | 1); }
constexpr std::uint8_t write_command(std::uint8_t reg) { return static_cast<std::uint8_t>(reg << 1); }
const char* register_name(std::uint8_t reg);
}  // namespace adxl355

struct Adxl355Settings {
  int range_g = 2;       // full scale, g: 2, 4 or 8
  double odr_hz = 4000;  // nominal output data rate, Hz: 4000 / 2^k for k = 0..10
};

// One x/y/z set out of the FIFO. `valid` false: a hole where a set came out broken.
struct FifoSample {
  double x_mps2 = 0.0;
  double y_mps2 = 0.0;
  double z_mps2 = 0.0;
  bool valid = false;
};

struct FifoRead {
  bool ok = false;             // every transfer went through
  bool overflow = false;       // STATUS.FIFO_OVR: the part dropped its oldest samples
  bool drained = false;        // every entry was read and no set is left half-read
  std::uint8_t entries = 0;    // FIFO_ENTRIES before the burst, axis entries (3 per sample)
  std::size_t samples = 0;     // sets written to the output, holes included
  std::size_t misaligned = 0;  // holes among them
};

class Adxl355 {
 public:
  enum class Fault : std::uint8_t { none, spi, identity, not_ready, readback };

  // `device` names the part in errors (the spidev path).
  Adxl355(SpiBus& bus, std::string device) : bus_(bus), device_(std::move(device)) {}

  // The FILTER code of a nominal rate, or nullopt when the part has no such rate.
  static std::optional<std::uint8_t> odr_code(double odr_hz);
  static std::optional<std::uint8_t> range_code(int range_g);

  // Checks the settings and the three ID registers, resets the part and sets range and rate,
  // leaving it in standby for measure(). The error names the register and the value read.
  std::optional<ParseError> configure(const Adxl355Settings& settings);
  // configure()'s steps with the settings it took, without building an error (recovery).
  Fault prepare();
  // Out of standby: sampling starts, the data-ready pin on; then the settings are read back.
  Fault measure();
  // Whether the part still answers with its IDs and the settings measure() left: a power cycle or
  // a reset in between shows as a readback fault.
  Fault check();
  // The error for a fault, naming the register and what was read.
  ParseError error(Fault f) const;

  // Reads STATUS and FIFO_ENTRIES, then bursts FIFO_DATA into `out`. Reads at most out.size()
  // entries (each entry ends at most one set), the rest stays in the FIFO.
  FifoRead read_fifo(std::span<FifoSample> out);

 private:
  bool read(std::uint8_t reg, std::size_t n);  // into rx_[1..n]
  bool write(std::uint8_t reg, std::uint8_t value);
  Fault check_identity();
  Fault fail(Fault f, std::uint8_t reg, std::uint8_t value = 0, std::uint8_t expected = 0);
  void take_entry(const std::uint8_t* entry, std::span<FifoSample> out, FifoRead& r);

  SpiBus& bus_;
  std::string device_;
  std::uint8_t odr_code_ = 0, range_code_ = 1;
  double mps2_per_lsb_ = adxl355::kStandardGravity / adxl355::kLsbPerG2g;
  std::array<std::uint8_t, 1 + 3 * adxl355::kFifoEntriesMax> tx_{}, rx_{};
  // The set being rebuilt across bursts: its entries so far and non-x entries waiting for an x.
  std::array<std::int32_t, 3> set_{};
  int set_entries_ = 0;
  int stray_entries_ = 0;
  // What the last fault saw, for error()'s message.
  std::uint8_t fault_reg_ = 0, fault_value_ = 0, fault_expected_ = 0;
};

}  // namespace roadload::accel
