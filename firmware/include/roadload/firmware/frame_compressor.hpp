#pragma once
// Turns a buffer of whole lines into one independent zstd frame (with its content size and checksum),
// through a workspace and an output buffer allocated once at construction: the running daemon
// compresses without touching the heap. One compressor serves every stream of a recorder, which
// writes them from one thread.
#include <cstddef>
#include <memory>
#include <span>

namespace roadload::firmware {

class FrameCompressor {
 public:
  static constexpr int kMinLevel = 1;
  static constexpr int kMaxLevel = 19;

  // Frames of at most `max_input` bytes at zstd level `level` (kMinLevel..kMaxLevel).
  FrameCompressor(int level, std::size_t max_input);
  FrameCompressor(const FrameCompressor&) = delete;
  FrameCompressor& operator=(const FrameCompressor&) = delete;
  ~FrameCompressor();

  // The frame of `text` (at most max_input bytes), valid until the next call; empty if zstd failed.
  std::span<const char> compress(std::span<const char> text);
  int level() const { return level_; }

 private:
  int level_;
  std::size_t max_input_;
  std::unique_ptr<char[]> workspace_;
  std::unique_ptr<char[]> out_;
  std::size_t out_capacity_ = 0;
  void* context_ = nullptr;  // a ZSTD_CCtx inside workspace_
};

}  // namespace roadload::firmware
