#pragma once
// A FLAC encoder (RFC 9639) for a handful of 32-bit integer channels, with no heap and no library:
// the recorder's own, so that roadloadd can run it in the data path. It writes what `flac -d`,
// libFLAC and ffmpeg read: a variable-blocksize stream (each frame numbered by its first sample), so
// that a frame can be closed at any moment, as the zstd streams close one at every fsync. Subframes
// are CONSTANT, VERBATIM or FIXED (orders 0-4) with partitioned Rice coding; no LPC, no stereo
// decorrelation: sensor counts are noise-limited, and the fixed predictors are within a few percent
// of LPC on them.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace roadload::recording {

inline constexpr std::size_t kFlacMaxChannels = 5;
inline constexpr std::size_t kFlacMaxBlock = 2048;
// A frame's worst case: every channel verbatim, plus headers.
inline constexpr std::size_t kFlacMaxFrameBytes = kFlacMaxChannels * kFlacMaxBlock * 4 + 64;

// What encoding needs only while it runs, and the bytes an encoder returns until its next call:
// the encoders of one thread share one (a recorder of eight sensors keeps a block each, and one
// of these).
struct FlacScratch {
  std::array<std::int64_t, kFlacMaxBlock> residual{};  // the chosen predictor's, channel by channel
  std::array<std::uint8_t, kFlacMaxFrameBytes> out{};
};

class FlacEncoder {
 public:
  static constexpr std::size_t kMaxChannels = kFlacMaxChannels;
  static constexpr std::size_t kMaxBlock = kFlacMaxBlock;
  static constexpr std::size_t kMaxFrameBytes = kFlacMaxFrameBytes;
  // The smallest frame but the last, as STREAMINFO declares it.
  static constexpr std::size_t kMinBlock = 16;

  explicit FlacEncoder(FlacScratch& scratch) : scratch_(&scratch) {}

  // `channels` of 32-bit samples at a nominal `sample_rate_hz` (1 .. 655350); `comments` are
  // VORBIS_COMMENT entries ("KEY=value"). Returns the stream's header bytes.
  std::span<const std::uint8_t> start(std::size_t channels, std::uint32_t sample_rate_hz, std::span<const std::string_view> comments);
  // Adds one sample of every channel. Returns a frame's bytes when the block is full, else empty;
  // like every span returned, valid until the next call on an encoder sharing the scratch.
  std::span<const std::uint8_t> push(std::span<const std::int32_t> sample);
  // Closes the open block as a frame (nothing when it holds fewer than kMinBlock samples and
  // `last` is false: they stay for the next frame).
  std::span<const std::uint8_t> close_frame(bool last = false);
  std::size_t pending() const { return fill_; }
  std::uint64_t samples_written() const { return first_sample_; }

 private:
  class Bits;
  void encode_subframe(Bits& out, std::span<const std::int32_t> x);

  std::size_t channels_ = 0;
  std::size_t fill_ = 0;
  std::uint64_t first_sample_ = 0;  // of the open block
  FlacScratch* scratch_;
  std::array<std::array<std::int32_t, kMaxBlock>, kMaxChannels> block_{};
};

}  // namespace roadload::recording
