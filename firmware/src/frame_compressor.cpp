#include "roadload/firmware/frame_compressor.hpp"

#define ZSTD_STATIC_LINKING_ONLY  // ZSTD_initStaticCCtx: a context in memory the caller owns
#include <zstd.h>

#include <algorithm>

namespace roadload::firmware {

namespace {
ZSTD_CCtx* context(void* p) { return static_cast<ZSTD_CCtx*>(p); }
}  // namespace

FrameCompressor::FrameCompressor(int level, std::size_t max_input)
    : level_(std::clamp(level, kMinLevel, kMaxLevel)), max_input_(max_input) {
  // Parameters for inputs of this size: a window no larger than a frame, so far less memory than
  // the level's defaults for unknown sizes.
  const ZSTD_compressionParameters params = ZSTD_getCParams(level_, max_input_, 0);
  const std::size_t workspace = ZSTD_estimateCCtxSize_usingCParams(params);
  workspace_ = std::make_unique<char[]>(workspace);
  context_ = ZSTD_initStaticCCtx(workspace_.get(), workspace);
  out_capacity_ = ZSTD_compressBound(max_input_);
  out_ = std::make_unique<char[]>(out_capacity_);
  if (context_ == nullptr) return;
  ZSTD_CCtx_setParameter(context(context_), ZSTD_c_compressionLevel, level_);
  ZSTD_CCtx_setParameter(context(context_), ZSTD_c_checksumFlag, 1);
  ZSTD_CCtx_setParameter(context(context_), ZSTD_c_windowLog, static_cast<int>(params.windowLog));
}

FrameCompressor::~FrameCompressor() = default;

std::span<const char> FrameCompressor::compress(std::span<const char> text) {
  if (context_ == nullptr || text.size() > max_input_) return {};
  const std::size_t n = ZSTD_compress2(context(context_), out_.get(), out_capacity_, text.data(), text.size());
  if (ZSTD_isError(n)) return {};
  return {out_.get(), n};
}

}  // namespace roadload::firmware
