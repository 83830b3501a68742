#include "roadload/recording/flac_encoder.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>

namespace roadload::recording {
namespace {

constexpr unsigned kBitsPerSample = 32;
constexpr unsigned kRiceEscape = 31;  // RICE2: 5-bit parameters, all ones escapes to raw bits
constexpr unsigned kMaxRiceParam = 30;
constexpr unsigned kMaxFixedOrder = 4;
// A decoder keeps residuals in 32 bits, and an escaped partition holds at most 31 signed bits.
constexpr std::int64_t kMaxResidual = (std::int64_t{1} << 30) - 1;

constexpr std::array<std::uint8_t, 256> crc8_table() {
  std::array<std::uint8_t, 256> t{};
  for (unsigned i = 0; i < 256; ++i) {
    unsigned c = i;
    for (int b = 0; b < 8; ++b) c = (c & 0x80) != 0 ? ((c << 1) ^ 0x07) & 0xFF : (c << 1) & 0xFF;
    t[i] = static_cast<std::uint8_t>(c);
  }
  return t;
}
constexpr std::array<std::uint16_t, 256> crc16_table() {
  std::array<std::uint16_t, 256> t{};
  for (unsigned i = 0; i < 256; ++i) {
    unsigned c = i << 8;
    for (int b = 0; b < 8; ++b) c = (c & 0x8000) != 0 ? ((c << 1) ^ 0x8005) & 0xFFFF : (c << 1) & 0xFFFF;
    t[i] = static_cast<std::uint16_t>(c);
  }
  return t;
}
constexpr auto kCrc8 = crc8_table();
constexpr auto kCrc16 = crc16_table();

std::uint8_t crc8(std::span<const std::uint8_t> bytes) {
  std::uint8_t c = 0;
  for (const std::uint8_t b : bytes) c = kCrc8[c ^ b];
  return c;
}
std::uint16_t crc16(std::span<const std::uint8_t> bytes) {
  std::uint16_t c = 0;
  for (const std::uint8_t b : bytes) c = static_cast<std::uint16_t>((c << 8) ^ kCrc16[(c >> 8) ^ b]);
  return c;
}

std::uint64_t zigzag(std::int64_t r) { return (static_cast<std::uint64_t>(r) << 1) ^ static_cast<std::uint64_t>(r >> 63); }

// Bits a value needs as a signed integer.
unsigned signed_bits(std::int64_t v) {
  const std::uint64_t m = static_cast<std::uint64_t>(v < 0 ? ~v : v);
  return m == 0 ? (v == 0 ? 0U : 1U) : static_cast<unsigned>(std::bit_width(m)) + 1;
}

struct RiceChoice {
  std::uint64_t bits = std::numeric_limits<std::uint64_t>::max();
  unsigned param = 0;  // kRiceEscape: raw
  unsigned raw_bits = 0;
};

// What a partition's codings cost follows from these alone.
struct PartitionSums {
  std::uint64_t sum = 0;  // of its residuals zigzagged
  std::uint64_t n = 0;
  unsigned raw = 0;  // the signed bits its widest residual needs
  PartitionSums& operator+=(const PartitionSums& o) {
    sum += o.sum;
    n += o.n;
    raw = std::max(raw, o.raw);
    return *this;
  }
};

// The cheapest coding of a partition: a Rice parameter near its mean's log, or raw bits. A Rice
// code of parameter k takes n (k + 1) + sum of (u >> k) bits, which is the sum over 2^k less
// about n / 2 for the bits shifted out: estimated so from the sums rather than counted.
RiceChoice best_rice(const PartitionSums& p) {
  RiceChoice best{5 + 5 + std::uint64_t{p.raw} * p.n, kRiceEscape, p.raw};
  const unsigned guess = p.n == 0 || p.sum < p.n ? 0U : static_cast<unsigned>(std::bit_width(p.sum / p.n)) - 1;
  for (unsigned k = guess == 0 ? 0 : guess - 1; k <= std::min(guess + 1, kMaxRiceParam); ++k) {
    const std::uint64_t shifted_out = k == 0 ? 0 : p.n / 2;
    const std::uint64_t bits = 5 + p.n * (k + 1) + (p.sum >> k) - std::min(shifted_out, p.sum >> k);
    if (bits < best.bits) best = {bits, k, 0};
  }
  return best;
}

}  // namespace

class FlacEncoder::Bits {
 public:
  explicit Bits(std::span<std::uint8_t> buf) : buf_(buf) {}
  // n <= 32 bits of v, most significant first.
  void put(std::uint64_t v, unsigned n) {
    if (n == 0) return;
    acc_ = (acc_ << n) | (v & ((std::uint64_t{1} << n) - 1));
    count_ += n;
    while (count_ >= 8) {
      count_ -= 8;
      buf_[len_++] = static_cast<std::uint8_t>(acc_ >> count_);
    }
  }
  void put_signed(std::int64_t v, unsigned n) { put(static_cast<std::uint64_t>(v), n); }
  void unary(std::uint64_t zeros) {
    for (; zeros >= 32; zeros -= 32) put(0, 32);
    put(1, static_cast<unsigned>(zeros) + 1);
  }
  void align() {
    if (count_ != 0) put(0, 8 - count_);
  }
  std::size_t size() const { return len_; }
  std::uint8_t* data() { return buf_.data(); }

 private:
  std::span<std::uint8_t> buf_;
  std::uint64_t acc_ = 0;
  unsigned count_ = 0;
  std::size_t len_ = 0;
};

std::span<const std::uint8_t> FlacEncoder::start(std::size_t channels, std::uint32_t sample_rate_hz,
                                                 std::span<const std::string_view> comments) {
  assert(channels >= 1 && channels <= kMaxChannels && sample_rate_hz >= 1 && sample_rate_hz <= 655350);
  channels_ = channels;
  fill_ = 0;
  first_sample_ = 0;
  Bits b(scratch_->out);
  for (const char c : std::string_view("fLaC")) b.put(static_cast<unsigned char>(c), 8);
  // STREAMINFO: frame sizes, sample count and MD5 unknown, as a stream written live has them.
  b.put(0, 1);
  b.put(0, 7);
  b.put(34, 24);
  b.put(kMinBlock, 16);
  b.put(kMaxBlock, 16);
  b.put(0, 24);
  b.put(0, 24);
  b.put(sample_rate_hz, 20);
  b.put(channels - 1, 3);
  b.put(kBitsPerSample - 1, 5);
  b.put(0, 32);  // 36 bits of total samples
  b.put(0, 4);
  for (int i = 0; i < 4; ++i) b.put(0, 32);
  // VORBIS_COMMENT: its lengths little-endian, as Ogg Vorbis has them.
  std::size_t length = 4 + 4;
  for (const auto c : comments) length += 4 + c.size();
  auto le32 = [&](std::size_t v) {
    for (int i = 0; i < 4; ++i) b.put((v >> (8 * i)) & 0xFF, 8);
  };
  b.put(1, 1);
  b.put(4, 7);
  b.put(length, 24);
  le32(0);  // no vendor string
  le32(comments.size());
  for (const auto c : comments) {
    le32(c.size());
    for (const char ch : c) b.put(static_cast<unsigned char>(ch), 8);
  }
  return {scratch_->out.data(), b.size()};
}

std::span<const std::uint8_t> FlacEncoder::push(std::span<const std::int32_t> sample) {
  assert(sample.size() == channels_);
  for (std::size_t c = 0; c < channels_; ++c) block_[c][fill_] = sample[c];
  ++fill_;
  return fill_ == kMaxBlock ? close_frame() : std::span<const std::uint8_t>{};
}

std::span<const std::uint8_t> FlacEncoder::close_frame(bool last) {
  if (fill_ == 0 || (fill_ < kMinBlock && !last)) return {};
  Bits b(scratch_->out);
  b.put(0x3FFE, 14);  // sync
  b.put(0, 1);
  b.put(1, 1);       // variable blocksize: the coded number is the first sample's
  b.put(0b0111, 4);  // block size: 16 bits at the header's end
  b.put(0, 4);       // sample rate: STREAMINFO's
  b.put(channels_ - 1, 4);
  b.put(0, 3);  // sample size: STREAMINFO's
  b.put(0, 1);
  // The sample number coded as UTF-8 extended to 36 bits.
  const std::uint64_t n = first_sample_;
  if (n < 0x80) {
    b.put(n, 8);
  } else {
    int extra = 1;
    while (extra < 6 && n >= (std::uint64_t{1} << (6 + 5 * extra))) ++extra;
    const std::uint64_t lead_marker = (0xFF00U >> (extra + 1)) & 0xFF;
    b.put(lead_marker | (n >> (6 * extra)), 8);
    for (int i = extra - 1; i >= 0; --i) b.put(0x80 | ((n >> (6 * i)) & 0x3F), 8);
  }
  b.put(fill_ - 1, 16);
  b.put(crc8({b.data(), b.size()}), 8);
  for (std::size_t c = 0; c < channels_; ++c) encode_subframe(b, {block_[c].data(), fill_});
  b.align();
  const std::uint16_t crc = crc16({b.data(), b.size()});
  b.put(crc, 16);
  first_sample_ += fill_;
  fill_ = 0;
  return {scratch_->out.data(), b.size()};
}

namespace {

// The fixed polynomial predictors: order k's residual is the k-th difference. One pass finds each
// order's bits (the sum of its residuals' bit widths) and whether all of them fit; the fewest bits
// win; nullopt when no order fits.
std::optional<unsigned> fixed_order(std::span<const std::int32_t> x) {
  const std::size_t n = x.size();
  std::array<std::uint64_t, kMaxFixedOrder + 1> magnitude{};
  std::array<bool, kMaxFixedOrder + 1> usable{};
  for (unsigned k = 0; k <= kMaxFixedOrder; ++k) usable[k] = k < n;
  std::array<std::int64_t, kMaxFixedOrder + 1> prev{}, diff{};
  for (std::size_t i = 0; i < n; ++i) {
    diff[0] = x[i];
    for (unsigned k = 1; k <= kMaxFixedOrder; ++k) diff[k] = diff[k - 1] - prev[k - 1];
    for (unsigned k = 0; k <= kMaxFixedOrder && k <= i; ++k) {
      const auto m = static_cast<std::uint64_t>(std::llabs(diff[k]));
      // Bits, not size: a stamp's nanoseconds wrap once a second, and that one residual's size
      // would outweigh a block of small ones (order 1 then cost 21 raw bits a sample).
      magnitude[k] += static_cast<std::uint64_t>(std::bit_width(m));
      usable[k] = usable[k] && m <= kMaxResidual;
    }
    prev = diff;
  }
  std::optional<unsigned> best;
  for (unsigned k = 0; k <= kMaxFixedOrder; ++k) {
    if (usable[k] && (!best || magnitude[k] < magnitude[*best])) best = k;
  }
  return best;
}

// Order `order`'s residual from sample `order` on (the samples before it are the warm-up).
void fixed_residual(std::span<const std::int32_t> x, unsigned order, std::span<std::int64_t> res) {
  // The k-th difference, from the binomial coefficients of (1 - z^-1)^k.
  static constexpr std::array<std::array<std::int64_t, kMaxFixedOrder + 1>, kMaxFixedOrder + 1> kCoeff{
      {{1, 0, 0, 0, 0}, {1, -1, 0, 0, 0}, {1, -2, 1, 0, 0}, {1, -3, 3, -1, 0}, {1, -4, 6, -4, 1}}};
  for (std::size_t i = order; i < x.size(); ++i) {
    std::int64_t r = x[i];
    for (unsigned j = 1; j <= order; ++j) r += kCoeff[order][j] * x[i - j];
    res[i] = r;
  }
}

// A block's residual cut into 2^p partitions (the first shortened by the warm-up), for every p up
// to the finest that divides the block and leaves each partition samples (at most 2^8): the
// finest partitions' sums are taken in one pass, a coarser one's are theirs added.
class Partitions {
 public:
  static constexpr unsigned kMaxOrder = 8;

  Partitions(std::span<const std::int64_t> res, unsigned order) : res_(res), order_(order) {
    while (finest_ < kMaxOrder && ((res.size() >> (finest_ + 1)) << (finest_ + 1)) == res.size() &&
           (res.size() >> (finest_ + 1)) > order) {
      ++finest_;
    }
    for (std::size_t j = 0; j < (std::size_t{1} << finest_); ++j) {
      for (const std::int64_t v : samples(finest_, j)) {
        sums_[j].sum += zigzag(v);
        sums_[j].raw = std::max(sums_[j].raw, signed_bits(v));
      }
      sums_[j].n = samples(finest_, j).size();
    }
  }

  std::span<const std::int64_t> samples(unsigned p, std::size_t j) const {
    const std::size_t part = res_.size() >> p;
    const std::size_t from = j == 0 ? order_ : j * part;
    return res_.subspan(from, (j + 1) * part - from);
  }
  PartitionSums sums(unsigned p, std::size_t j) const {
    const std::size_t span = std::size_t{1} << (finest_ - p);
    PartitionSums s;
    for (std::size_t i = j * span; i < (j + 1) * span; ++i) s += sums_[i];
    return s;
  }
  // The partition order that codes the residual in the fewest bits, and those bits.
  std::pair<unsigned, std::uint64_t> cheapest() const {
    std::pair<unsigned, std::uint64_t> best{0, std::numeric_limits<std::uint64_t>::max()};
    for (unsigned p = 0; p <= finest_; ++p) {
      std::uint64_t bits = 0;
      for (std::size_t j = 0; j < (std::size_t{1} << p); ++j) bits += best_rice(sums(p, j)).bits;
      if (bits < best.second) best = {p, bits};
    }
    return best;
  }

 private:
  std::span<const std::int64_t> res_;
  unsigned order_;
  unsigned finest_ = 0;
  std::array<PartitionSums, std::size_t{1} << kMaxOrder> sums_{};
};

}  // namespace

void FlacEncoder::encode_subframe(Bits& out, std::span<const std::int32_t> x) {
  const std::size_t n = x.size();
  if (std::all_of(x.begin(), x.end(), [&](std::int32_t v) { return v == x[0]; })) {
    out.put(0, 8);
    out.put_signed(x[0], kBitsPerSample);
    return;
  }
  const std::optional<unsigned> fixed = fixed_order(x);
  const unsigned order = fixed.value_or(0);
  const std::span<std::int64_t> res{scratch_->residual.data(), n};
  if (fixed) fixed_residual(x, order, res);
  const Partitions parts(res, order);
  const auto [p, bits] = fixed ? parts.cheapest() : std::pair<unsigned, std::uint64_t>{0, 0};
  if (!fixed || 6 + bits + std::uint64_t{order} * kBitsPerSample >= std::uint64_t{n} * kBitsPerSample) {
    out.put(1 << 1, 8);  // VERBATIM
    for (const std::int32_t v : x) out.put_signed(v, kBitsPerSample);
    return;
  }
  out.put((0b001000U | order) << 1, 8);
  for (unsigned i = 0; i < order; ++i) out.put_signed(x[i], kBitsPerSample);
  out.put(1, 2);  // RICE2
  out.put(p, 4);
  for (std::size_t j = 0; j < (std::size_t{1} << p); ++j) {
    const RiceChoice c = best_rice(parts.sums(p, j));
    out.put(c.param, 5);
    if (c.param == kRiceEscape) {
      out.put(c.raw_bits, 5);
      for (const std::int64_t v : parts.samples(p, j)) out.put_signed(v, c.raw_bits);
      continue;
    }
    for (const std::int64_t v : parts.samples(p, j)) {
      const std::uint64_t u = zigzag(v);
      out.unary(u >> c.param);
      out.put(u, c.param);
    }
  }
}

}  // namespace roadload::recording
