// candump -L lines: every frame kind real logs contain, and the exact text canplayer replays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "roadload/recording/candump.hpp"

namespace roadload::recording {
namespace {

struct ParsedLine {
  std::optional<LineError> error;
  LineResult result;
  CanFrame frame;
};

ParsedLine parse(std::string_view line) {
  static InterfaceTable ifaces;
  ParsedLine p;
  p.error = parse_candump_line(line, ifaces, p.frame, p.result);
  return p;
}

std::string format(const CanFrame& f) {
  char buf[kMaxLineChars];
  const std::size_t n = format_candump_line(f, "can0", buf);
  return std::string(buf, n);
}

TEST(CandumpLine, ExtendedFrameWithMicroseconds) {
  const ParsedLine p = parse("(1635188455.029900) can0 0CF00400#607D844A1400F084");
  ASSERT_FALSE(p.error);
  EXPECT_EQ(p.result, LineResult::frame);
  EXPECT_EQ(p.frame.kind, CanFrameKind::extended);
  EXPECT_EQ(p.frame.id, 0x0CF00400u);
  EXPECT_EQ(p.frame.len, 8);
  EXPECT_EQ(p.frame.data[3], 0x4A);
  EXPECT_EQ(to_ns(p.frame.t), 1635188455029900000);
}

TEST(CandumpLine, NanosecondStamps) {
  const ParsedLine p = parse("(12.000000001) vcan0 123#");
  ASSERT_FALSE(p.error);
  EXPECT_EQ(to_ns(p.frame.t), 12000000001);
  EXPECT_EQ(p.frame.kind, CanFrameKind::standard);
  EXPECT_EQ(p.frame.len, 0);
}

TEST(CandumpLine, RemoteErrorAndFdFramesAreTold) {
  EXPECT_EQ(parse("(1.000000) can0 123#R").frame.kind, CanFrameKind::remote);
  const ParsedLine err = parse("(1.000000) can0 20000080#0000000000000000");
  EXPECT_EQ(err.frame.kind, CanFrameKind::error);
  EXPECT_EQ(err.frame.id, 0x80u);
  const ParsedLine fd = parse("(1.000000) can0 18FEF100##1112233445566778899AABBCC");
  ASSERT_FALSE(fd.error);
  EXPECT_EQ(fd.frame.kind, CanFrameKind::fd);
  EXPECT_EQ(fd.frame.fd_flags, 1);
  EXPECT_EQ(fd.frame.len, 12);
  EXPECT_TRUE(fd.frame.id29);
}

TEST(CandumpLine, InterfaceNameWithControlBytesIsRejected) {
  constexpr std::string_view line("(1.000000) can\0\0 123#", 23);
  const ParsedLine p = parse(line);
  ASSERT_TRUE(p.error);
  EXPECT_STREQ(p.error->field, "interface");
}

TEST(CandumpLine, BlankLinesAndCommentsAreIgnoredAnythingElseIsMalformed) {
  EXPECT_EQ(parse("").result, LineResult::ignored);
  EXPECT_EQ(parse("  \r").result, LineResult::ignored);
  EXPECT_EQ(parse("# comment").result, LineResult::ignored);
  EXPECT_FALSE(parse("# comment").error);
  const ParsedLine garbage = parse("garbage");
  ASSERT_TRUE(garbage.error);
  EXPECT_STREQ(garbage.error->field, "timestamp");
}

TEST(CandumpLine, FormatRoundTripsEveryKind) {
  for (const char* line :
       {"(1635188455.029900) can0 0CF00400#607D844A1400F084", "(0000000001.000000) can0 123#R", "(0000000001.000000) can0 123#R2",
        "(0000000001.000000) can0 1CECFF00#R", "(0000000001.000000) can0 20000080#0000000000000000",
        "(0000000001.000000) can0 18FEF100##1112233445566778899AABBCC", "(0000000001.000000) can0 7FF#"}) {
    const ParsedLine p = parse(line);
    ASSERT_FALSE(p.error) << line;
    EXPECT_EQ(format(p.frame), line);
  }
}

// The stamp is written by hand; printf's "(%010lld.%06lld)" is the reference, edges included.
TEST(CandumpLine, StampsAreWrittenAsPrintfWritesThem) {
  std::mt19937_64 rng(7);
  std::vector<std::int64_t> stamps = {
      0, 999, 1'000, 999'999'999, 1'000'000'000, 9'999'999'999'999'999, std::numeric_limits<std::int64_t>::max()};
  for (int k = 0; k < 2000; ++k) stamps.push_back(static_cast<std::int64_t>(rng() >> (1 + k % 40)));
  for (const std::int64_t ns : stamps) {
    CanFrame f;
    f.kind = CanFrameKind::standard;
    f.id = 0x123;
    f.t = capture_time_from_ns(ns);
    char want[kMaxLineChars];
    std::snprintf(want, sizeof want, "(%010lld.%06lld) can0 123#", static_cast<long long>(ns / 1'000'000'000),
                  static_cast<long long>(ns % 1'000'000'000 / 1000));
    EXPECT_EQ(format(f), want) << ns;
  }
}

// The daemon judges live what a decode of its recording must find, on candump_stamp's stamps.
TEST(CandumpLine, AWrittenStampReadsBackAsCandumpStampSaysItWill) {
  std::mt19937_64 rng(11);
  for (int k = 0; k < 2000; ++k) {
    CanFrame f;
    f.kind = CanFrameKind::standard;
    f.id = 0x123;
    f.t = capture_time_from_ns(static_cast<std::int64_t>(rng() >> (2 + k % 30)));
    const ParsedLine p = parse(format(f));
    ASSERT_FALSE(p.error) << format(f);
    EXPECT_EQ(p.frame.t, candump_stamp(f.t)) << to_ns(f.t);
  }
  EXPECT_EQ(to_ns(candump_stamp(capture_time_from_ns(1'000'000'999))), 1'000'000'000);
}

// Lines shaped as candump -L writes them take a short path; a nanosecond stamp sends the same
// frame through the general one. Both must read every frame alike.
TEST(CandumpLine, TheShortAndTheGeneralPathReadTheSameFrames) {
  std::mt19937_64 rng(2026);
  for (int k = 0; k < 2000; ++k) {
    CanFrame f;
    f.kind = CanFrameKind::extended;
    f.id = static_cast<std::uint32_t>(rng()) & 0x1FFFFFFFu;
    f.len = static_cast<std::uint8_t>(rng() % 9);
    for (std::size_t i = 0; i < f.len; ++i) f.data[i] = static_cast<std::uint8_t>(rng());
    f.t = capture_time_from_ns(static_cast<std::int64_t>(rng() % 9'000'000'000'000'000u) / 1000 * 1000);
    std::string line = format(f);
    if (k % 2 == 1) std::transform(line.begin(), line.end(), line.begin(), [](char c) { return static_cast<char>(std::tolower(c)); });
    std::string nanos = line;
    nanos.insert(nanos.find(')'), "000");
    const ParsedLine a = parse(line), b = parse(nanos);
    ASSERT_FALSE(a.error) << line;
    ASSERT_FALSE(b.error) << nanos;
    EXPECT_EQ(to_ns(a.frame.t), to_ns(f.t)) << line;
    EXPECT_EQ(to_ns(a.frame.t), to_ns(b.frame.t)) << line;
    EXPECT_EQ(a.frame.id, b.frame.id) << line;
    EXPECT_EQ(a.frame.kind, b.frame.kind) << line;
    EXPECT_EQ(a.frame.iface, b.frame.iface) << line;
    EXPECT_EQ(a.frame.id29, b.frame.id29) << line;
    EXPECT_EQ(a.frame.fd_flags, b.frame.fd_flags) << line;
    ASSERT_EQ(a.frame.len, f.len) << line;
    ASSERT_EQ(b.frame.len, f.len) << line;
    for (std::size_t i = 0; i < f.len; ++i) EXPECT_EQ(a.frame.data[i], b.frame.data[i]) << line;
  }
}

// The short path compares the line's interface with the last one's name in one load: names of
// every length, and names that begin another, are each read as themselves.
TEST(CandumpLine, InterfaceNamesOfEveryLengthAreToldApart) {
  const std::vector<std::string> names = {"c", "can1", "can10", "vcan0123", "vcan01234", "abcdefghijklmno"};
  InterfaceTable ifaces;
  std::mt19937 rng(7);
  for (int k = 0; k < 1000; ++k) {
    const std::string& name = names[rng() % names.size()];
    CanFrame f;
    f.id = 0x18FEF100u | (static_cast<std::uint32_t>(k) & 0xFF);
    f.len = 8;
    char buf[kMaxLineChars];
    const std::size_t n = format_candump_line(f, name, buf);
    CanFrame g;
    LineResult result;
    ASSERT_FALSE(parse_candump_line(std::string_view(buf, n), ifaces, g, result)) << buf;
    EXPECT_EQ(ifaces.name(g.iface), name) << buf;
    EXPECT_EQ(g.id, f.id) << buf;
  }
  EXPECT_EQ(ifaces.size(), names.size());
}

// Every byte value at every place of a frame line: what is read as a frame must be that frame
// (it formats back to the line, letters' case aside); anything else is an error or ignored.
TEST(CandumpLine, NoAlteredLineIsReadAsAnotherFrame) {
  const std::string good = "(1635188455.029900) can0 0CF00400#607D844A1400F084";
  auto upper = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](char c) { return static_cast<char>(std::toupper(c)); });
    return s;
  };
  std::size_t frames = 0;
  for (std::size_t at = 0; at < good.size(); ++at) {
    for (int c = 0; c < 256; ++c) {
      std::string line = good;
      line[at] = static_cast<char>(c);
      InterfaceTable ifaces;
      ifaces.intern("can0");
      CanFrame f;
      LineResult result;
      if (parse_candump_line(line, ifaces, f, result) || result != LineResult::frame) continue;
      ++frames;
      char buf[kMaxLineChars];
      const std::size_t n = format_candump_line(f, ifaces.name(f.iface), buf);
      EXPECT_EQ(upper(std::string(buf, n)), upper(line)) << "byte " << c << " at " << at;
    }
  }
  EXPECT_GT(frames, good.size() * 10);  // the digits, hex letters and the interface's letters
}

struct BadLine {
  const char* line;
  const char* field;
};

class CandumpLineRejects : public testing::TestWithParam<BadLine> {};

TEST_P(CandumpLineRejects, NamingTheField) {
  const ParsedLine p = parse(GetParam().line);
  ASSERT_TRUE(p.error) << GetParam().line;
  EXPECT_STREQ(p.error->field, GetParam().field);
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, CandumpLineRejects,
    testing::Values(BadLine{"(1.00) can0 123#", "timestamp"}, BadLine{"(1.000000 can0 123#", "timestamp"},
                    BadLine{"(16351888455.031950) can0 123#", "timestamp"}, BadLine{"(1.000000)can0 123#", "interface"},
                    BadLine{"(1.000000) can0", "interface"}, BadLine{"(1.000000) a_name_longer_than_15 123#", "interface"},
                    BadLine{"(1.000000) can0 12#00", "identifier"}, BadLine{"(1.000000) can0 800#00", "identifier"},
                    BadLine{"(1.000000) can0 1G3#00", "identifier"}, BadLine{"(1.000000) can0 123#0", "data"},
                    BadLine{"(1.000000) can0 123#001122334455667788", "data"}, BadLine{"(1.000000) can0 123#zz", "data"},
                    BadLine{"(1.000000) can0 123##", "flags"}, BadLine{"(1.000000) can0 123#R9", "data"}));

}  // namespace
}  // namespace roadload::recording
