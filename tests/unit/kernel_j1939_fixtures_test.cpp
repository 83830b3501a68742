// Multi-packet messages sent by the Linux kernel's own J1939 stack (captured in UML with
// tests/uml/capture-j1939-fixtures.sh) reassemble byte-exactly from the raw frames.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <vector>

#include "roadload/j1939/assembler.hpp"
#include "roadload/recording/reader.hpp"

namespace roadload {
namespace {

struct KernelCase {
  const char* name;
  j1939::Pgn pgn;
  std::uint8_t sa;
  std::uint8_t da;
};

class KernelJ1939Capture : public testing::TestWithParam<KernelCase> {};

TEST_P(KernelJ1939Capture, ReassemblesByteExact) {
  const KernelCase& c = GetParam();
  const std::string base = std::string(ROADLOAD_TEST_DATA "/j1939-kernel/") + c.name;
  std::ifstream bin(base + ".bin", std::ios::binary);
  const std::vector<std::uint8_t> expected((std::istreambuf_iterator<char>(bin)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(expected.empty()) << base << ".bin";

  auto stream = recording::CandumpStream::open(base + ".log");
  ASSERT_TRUE(stream) << stream.error().to_string();
  recording::ErrorLog errors;
  j1939::MessageAssembler assembler;
  CanFrame f;
  std::vector<std::vector<std::uint8_t>> messages;
  while (stream.value()->next_frame(f, errors)) {
    const auto m = assembler.push(f);
    if (!m || !m->reassembled) continue;
    EXPECT_EQ(m->pgn, c.pgn);
    EXPECT_EQ(m->sa, c.sa);
    EXPECT_EQ(m->da, c.da);
    messages.emplace_back(m->data.begin(), m->data.end());
  }
  EXPECT_EQ(errors.count(), 0u);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0], expected);
  const j1939::TpCounters& tp = assembler.transport().counters();
  EXPECT_EQ(tp.duplicate_packets + tp.orphan_packets + tp.malformed + tp.timed_out, 0u);
}

INSTANTIATE_TEST_SUITE_P(Linux61, KernelJ1939Capture,
                         testing::Values(KernelCase{"bam-9", 65251, 0x80, 0xFF}, KernelCase{"bam-100", 65280, 0x81, 0xFF},
                                         KernelCase{"bam-1785", 65281, 0x82, 0xFF}, KernelCase{"rts-9", 61184, 0x40, 0x90},
                                         KernelCase{"rts-100", 61184, 0x41, 0x91}, KernelCase{"rts-1785", 61184, 0x42, 0x92}),
                         [](const testing::TestParamInfo<KernelCase>& param_info) {
                           std::string n = param_info.param.name;
                           for (char& ch : n) ch = ch == '-' ? '_' : ch;
                           return n;
                         });

}  // namespace
}  // namespace roadload
