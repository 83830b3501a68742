#include "roadload/accel/adxl355.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace roadload::accel {

namespace adxl355 {

const char* register_name(std::uint8_t reg) {
  switch (reg) {
    case kDevIdAd: return "DEVID_AD";
    case kDevIdMst: return "DEVID_MST";
    case kPartId: return "PARTID";
    case kRevId: return "REVID";
    case kStatus: return "STATUS";
    case kFifoEntries: return "FIFO_ENTRIES";
    case kFifoData: return "FIFO_DATA";
    case kFilter: return "FILTER";
    case kFifoSamples: return "FIFO_SAMPLES";
    case kIntMap: return "INT_MAP";
    case kSync: return "SYNC";
    case kRange: return "RANGE";
    case kPowerCtl: return "POWER_CTL";
    case kReset: return "RESET";
    default: return "register";
  }
}

}  // namespace adxl355

namespace {

using namespace adxl355;

// STATUS reads while NVM_BUSY shows the part busy after RESET. Each read takes tens of
// microseconds through spidev, so this allows well over the 5 ms Linux's adxl355 driver waits.
constexpr int kResetPolls = 2000;

// 20 bits left-justified in 3 bytes, two's complement.
std::int32_t entry_value(const std::uint8_t* e) {
  const std::uint32_t raw = (std::uint32_t{e[0]} << 12) | (std::uint32_t{e[1]} << 4) | (std::uint32_t{e[2]} >> 4);
  return static_cast<std::int32_t>(raw ^ 0x80000u) - 0x80000;
}

}  // namespace

std::optional<std::uint8_t> Adxl355::odr_code(double odr_hz) {
  for (std::uint8_t k = 0; k <= 10; ++k) {
    const double nominal = 4000.0 / static_cast<double>(1 << k);
    if (std::abs(odr_hz / nominal - 1.0) < 1e-3) return k;
  }
  return std::nullopt;
}

std::optional<std::uint8_t> Adxl355::range_code(int range_g) {
  switch (range_g) {
    case 2: return 1;
    case 4: return 2;
    case 8: return 3;
    default: return std::nullopt;
  }
}

std::optional<ParseError> Adxl355::configure(const Adxl355Settings& settings) {
  const auto range = range_code(settings.range_g);
  if (!range) return ParseError{device_, 0, "range_g", std::to_string(settings.range_g) + " g: the part has 2, 4 and 8 g"};
  const auto odr = odr_code(settings.odr_hz);
  if (!odr) {
    char msg[96];
    std::snprintf(msg, sizeof msg, "%g Hz: the part has 4000 Hz halved 0 to 10 times (down to 3.906 Hz)", settings.odr_hz);
    return ParseError{device_, 0, "odr_hz", msg};
  }
  odr_code_ = *odr;
  range_code_ = *range;
  if (const Fault f = prepare(); f != Fault::none) return error(f);
  return std::nullopt;
}

ParseError Adxl355::error(Fault f) const {
  char msg[96] = "";
  switch (f) {
    case Fault::none: break;
    case Fault::spi: std::snprintf(msg, sizeof msg, "SPI transfer failed"); break;
    case Fault::identity:
      std::snprintf(msg, sizeof msg, "read 0x%02X, expected 0x%02X: not an ADXL355", fault_value_, fault_expected_);
      break;
    case Fault::not_ready: std::snprintf(msg, sizeof msg, "NVM_BUSY still set %d reads after RESET", kResetPolls); break;
    case Fault::readback: std::snprintf(msg, sizeof msg, "wrote 0x%02X, read back 0x%02X", fault_expected_, fault_value_); break;
  }
  char field[32];
  std::snprintf(field, sizeof field, "%s (0x%02X)", register_name(fault_reg_), fault_reg_);
  return ParseError{device_, 0, field, msg};
}

Adxl355::Fault Adxl355::prepare() {
  if (const Fault f = check_identity(); f != Fault::none) return f;
  if (!write(kReset, kResetCode)) return fail(Fault::spi, kReset);
  for (int polls = 0;; ++polls) {
    if (!read(kDevIdAd, 5)) return fail(Fault::spi, kStatus);
    if (rx_[1] == kDevIdAdValue && (rx_[5] & kStatusNvmBusy) == 0) break;
    if (polls == kResetPolls) return fail(Fault::not_ready, kStatus, rx_[5]);
  }
  if (!write(kFilter, odr_code_)) return fail(Fault::spi, kFilter);
  if (!read(kRange, 1)) return fail(Fault::spi, kRange);
  // RANGE also holds the interrupt polarity and I2C speed: keep them.
  if (!write(kRange, static_cast<std::uint8_t>((rx_[1] & ~kRangeMask) | range_code_))) return fail(Fault::spi, kRange);
  set_entries_ = 0;
  stray_entries_ = 0;
  mps2_per_lsb_ = mps2_per_lsb(range_code_);
  return Fault::none;
}

Adxl355::Fault Adxl355::measure() {
  if (!write(kPowerCtl, 0)) return fail(Fault::spi, kPowerCtl);
  return check();
}

Adxl355::Fault Adxl355::check() {
  if (const Fault f = check_identity(); f != Fault::none) return f;
  if (!read(kFilter, 6)) return fail(Fault::spi, kFilter);  // FILTER .. POWER_CTL
  if ((rx_[1] & 0x7F) != odr_code_) return fail(Fault::readback, kFilter, rx_[1], odr_code_);
  if ((rx_[5] & kRangeMask) != range_code_) return fail(Fault::readback, kRange, rx_[5], range_code_);
  if (rx_[6] != 0) return fail(Fault::readback, kPowerCtl, rx_[6], 0);
  return Fault::none;
}

Adxl355::Fault Adxl355::check_identity() {
  if (!read(kDevIdAd, 3)) return fail(Fault::spi, kDevIdAd);
  constexpr std::uint8_t expected[3] = {kDevIdAdValue, kDevIdMstValue, kPartIdValue};
  for (std::uint8_t i = 0; i < 3; ++i) {
    if (rx_[1u + i] != expected[i]) return fail(Fault::identity, i, rx_[1u + i], expected[i]);
  }
  return Fault::none;
}

FifoRead Adxl355::read_fifo(std::span<FifoSample> out) {
  FifoRead r;
  if (!read(kStatus, 2)) return r;
  r.overflow = (rx_[1] & kStatusFifoOvr) != 0;
  r.entries = rx_[2] & kFifoEntriesMask;
  const std::size_t n = std::min({std::size_t{r.entries}, out.size(), kFifoEntriesMax});
  // FIFO_DATA does not auto-increment: every 3 bytes read from it pop the next entry.
  if (n > 0 && !read(kFifoData, 3 * n)) return r;
  r.ok = true;
  for (std::size_t i = 0; i < n; ++i) take_entry(&rx_[1 + 3 * i], out, r);
  r.drained = n == r.entries && set_entries_ == 0 && stray_entries_ == 0;
  return r;
}

void Adxl355::take_entry(const std::uint8_t* entry, std::span<FifoSample> out, FifoRead& r) {
  if ((entry[2] & kEntryEmpty) != 0) return;
  const auto hole = [&] {
    out[r.samples++] = FifoSample{};
    ++r.misaligned;
  };
  const std::int32_t v = entry_value(entry);
  if ((entry[2] & kEntryX) != 0) {
    if (set_entries_ > 0 || stray_entries_ > 0) hole();  // a set cut short, or axes without their x
    stray_entries_ = 0;
    set_[0] = v;
    set_entries_ = 1;
  } else if (set_entries_ == 0) {
    if (++stray_entries_ == 3) {
      hole();
      stray_entries_ = 0;
    }
  } else {
    set_[static_cast<std::size_t>(set_entries_++)] = v;
    if (set_entries_ == 3) {
      out[r.samples++] = {set_[0] * mps2_per_lsb_, set_[1] * mps2_per_lsb_, set_[2] * mps2_per_lsb_, true};
      set_entries_ = 0;
    }
  }
}

bool Adxl355::read(std::uint8_t reg, std::size_t n) {
  tx_[0] = read_command(reg);
  std::fill_n(tx_.begin() + 1, n, std::uint8_t{0});
  return bus_.transfer(std::span(tx_.data(), n + 1), std::span(rx_.data(), n + 1));
}

bool Adxl355::write(std::uint8_t reg, std::uint8_t value) {
  tx_[0] = write_command(reg);
  tx_[1] = value;
  return bus_.transfer(std::span(tx_.data(), 2), std::span(rx_.data(), 2));
}

Adxl355::Fault Adxl355::fail(Fault f, std::uint8_t reg, std::uint8_t value, std::uint8_t expected) {
  fault_reg_ = reg;
  fault_value_ = value;
  fault_expected_ = expected;
  return f;
}

}  // namespace roadload::accel
