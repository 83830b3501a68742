#include "roadload/recording/candump.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>

namespace roadload::recording {
namespace {

constexpr std::uint32_t kErrFlag = 0x20000000u;
constexpr std::uint32_t kEffMask = 0x1FFFFFFFu;

// A table beats three range compares per digit in the 110-million-frame decode loop.
constexpr auto kHexTable = [] {
  std::array<std::int8_t, 256> t{};
  t.fill(-1);
  for (int i = 0; i < 10; ++i) t['0' + i] = static_cast<std::int8_t>(i);
  for (int i = 0; i < 6; ++i) {
    t['A' + i] = static_cast<std::int8_t>(10 + i);
    t['a' + i] = static_cast<std::int8_t>(10 + i);
  }
  return t;
}();

int hex_value(char c) { return kHexTable[static_cast<unsigned char>(c)]; }

// Linux interface names: at most 15 bytes (IFNAMSIZ - 1), printable, no '/' or blanks.
bool valid_interface_name(std::string_view name) {
  if (name.size() > 15) return false;
  for (const char c : name) {
    if (c <= ' ' || c > '~' || c == '/') return false;
  }
  return true;
}

// "(1635188455.020850)" with 6 or 9 fractional digits.
std::optional<LineError> parse_stamp(std::string_view& s, CaptureTime& t) {
  std::size_t i = 1;
  std::int64_t sec = 0;
  const std::size_t sec_begin = i;
  // Nanoseconds in an int64 reach year 2262; 9e9 s keeps every stamp representable.
  constexpr std::int64_t kMaxSeconds = 9'000'000'000;
  while (i < s.size() && s[i] >= '0' && s[i] <= '9') {
    sec = sec * 10 + (s[i++] - '0');
    if (sec > kMaxSeconds) return LineError{"timestamp", "seconds beyond 9000000000"};
  }
  if (i == sec_begin || i >= s.size() || s[i] != '.') return LineError{"timestamp", "expected (seconds.fraction)"};
  ++i;
  const std::size_t frac_begin = i;
  std::int64_t frac = 0;
  while (i < s.size() && s[i] >= '0' && s[i] <= '9' && i - frac_begin < 9) frac = frac * 10 + (s[i++] - '0');
  const std::size_t digits = i - frac_begin;
  if (digits != 6 && digits != 9) return LineError{"timestamp", "fraction must have 6 or 9 digits"};
  if (i >= s.size() || s[i] != ')') return LineError{"timestamp", "expected ')'"};
  if (digits == 6) frac *= 1000;
  t = capture_time_from_ns(sec * 1'000'000'000 + frac);
  s.remove_prefix(i + 1);
  return std::nullopt;
}

std::optional<LineError> parse_bytes(std::string_view s, std::size_t max, CanFrame& out) {
  std::size_t n = 0;
  std::size_t i = 0;
  while (i < s.size()) {
    if (s[i] == '.') {  // can-utils accepts byte separators
      ++i;
      continue;
    }
    if (i + 1 >= s.size()) return LineError{"data", "odd number of hex digits"};
    const int hi = hex_value(s[i]);
    const int lo = hex_value(s[i + 1]);
    if (hi < 0 || lo < 0) return LineError{"data", "not a hex digit"};
    if (n >= max) return LineError{"data", "too many data bytes"};
    out.data[n++] = static_cast<std::uint8_t>(hi << 4 | lo);
    i += 2;
  }
  out.len = static_cast<std::uint8_t>(n);
  return std::nullopt;
}

// Two characters, the first in the low byte, whatever the machine's byte order.
std::uint16_t load2(const char* p) {
  std::uint16_t v;
  std::memcpy(&v, p, sizeof v);
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap16(v);
  return v;
}

// Eight characters, the first in the lowest byte.
std::uint64_t load8(const char* p) {
  std::uint64_t v;
  std::memcpy(&v, p, sizeof v);
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap64(v);
  return v;
}

// Two characters (load2) to the byte they spell in hex, either case, or -1: one load a byte.
// Filled at start-up: as a constant expression its 65,536 entries pass clang's evaluation step
// limit.
const auto kHexPairs = [] {
  std::array<std::int16_t, 65536> t{};
  for (std::size_t i = 0; i < t.size(); ++i) {
    const int hi = kHexTable[i & 0xFF], lo = kHexTable[i >> 8];
    t[i] = hi < 0 || lo < 0 ? std::int16_t{-1} : static_cast<std::int16_t>(hi << 4 | lo);
  }
  return t;
}();

// Two characters (load2) to the number 0-99 their decimal digits make, or -1.
const auto kDecimalPairs = [] {
  std::array<std::int8_t, 65536> t{};
  for (std::size_t i = 0; i < t.size(); ++i) {
    const std::size_t hi = i & 0xFF, lo = i >> 8;
    const bool digits = hi >= '0' && hi <= '9' && lo >= '0' && lo <= '9';
    t[i] = digits ? static_cast<std::int8_t>((hi - '0') * 10 + (lo - '0')) : std::int8_t{-1};
  }
  return t;
}();

// kPairs pairs of decimal digits at p as one number; `bad` turns negative if any is not a digit.
// The count is a constant so that the loop unrolls.
template <int kPairs>
std::uint64_t decimal_pairs(const char* p, int& bad) {
  std::uint64_t v = 0;
#pragma GCC unroll 8
  for (int i = 0; i < kPairs; ++i) {
    const int d = kDecimalPairs[load2(p + 2 * i)];
    bad |= d;
    v = v * 100 + static_cast<std::uint64_t>(d);
  }
  return v;
}

// kBytes (at most 8) bytes in hex at p, the first in the lowest byte of `bytes`; negative `bad`
// if any digit is not hex. Gathered in a register for the caller to store in one move: a byte
// store into the frame may alias anything, and inside the loop it would keep `bad` in memory,
// each pair waiting on the last one's store.
struct HexBytes {
  std::uint64_t bytes;
  int bad;
};
template <std::size_t kBytes>
HexBytes hex_bytes(const char* p) {
  static_assert(kBytes <= 8);
  HexBytes h{0, 0};
  // Unrolled, the pairs are independent loads with nothing spilled between them.
#pragma GCC unroll 8
  for (std::size_t i = 0; i < kBytes; ++i) {
    const int v = kHexPairs[load2(p + 2 * i)];
    h.bad |= v;
    h.bytes |= std::uint64_t{static_cast<std::uint8_t>(v)} << (8 * i);
  }
  return h;
}

// `bytes` (the first in the lowest byte) to memory in that order.
void store8(std::uint8_t* p, std::uint64_t bytes) {
  if constexpr (std::endian::native == std::endian::big) bytes = __builtin_bswap64(bytes);
  std::memcpy(p, &bytes, sizeof bytes);
}

// Whether `name` starts at p, where p has at least eight readable bytes. A memcmp call per line
// showed in a decode's profile.
bool same_name(const char* p, std::string_view name, std::uint64_t word) {
  if (name.size() > 8) return std::memcmp(p, name.data(), name.size()) == 0;
  const std::uint64_t mask = name.size() == 8 ? ~std::uint64_t{0} : (std::uint64_t{1} << (8 * name.size())) - 1;
  return ((load8(p) ^ word) & mask) == 0;
}

// The line as candump -L and roadloadd write nearly every line of a J1939 log:
// "(SSSSSSSSSS.UUUUUU) <the interface of the line before> IIIIIIII#<0-8 bytes>". Returns false
// for anything else, which the general parser then reads or refuses with its reason, so both give
// the same frame or the same error. The line comes as pointer and size: as a string_view it was
// spilled and reloaded whole, a store-forwarding stall that took a quarter of a decode's time.
bool parse_common(const char* s, std::size_t size, const InterfaceTable& ifaces, CanFrame& out) {
  constexpr std::size_t kStamp = 20;  // "(SSSSSSSSSS.UUUUUU) "
  const std::string_view iface = ifaces.last();
  const std::size_t id_at = kStamp + iface.size() + 1;
  if (iface.empty() || size < id_at + 9 || s[0] != '(' || s[11] != '.' || s[18] != ')' || s[19] != ' ') return false;
  int bad = 0;
  const std::uint64_t sec = decimal_pairs<5>(s + 1, bad);
  const std::uint64_t usec = decimal_pairs<3>(s + 12, bad);
  if (bad < 0 || sec > 9'000'000'000u) return false;
  if (!same_name(s + kStamp, iface, ifaces.last_word()) || s[id_at - 1] != ' ' || s[id_at + 8] != '#') return false;
  const HexBytes id_hex = hex_bytes<4>(s + id_at);
  // Written most significant byte first.
  const std::uint32_t id = __builtin_bswap32(static_cast<std::uint32_t>(id_hex.bytes));
  const std::size_t data_at = id_at + 9, digits = size - data_at;
  if ((bad | id_hex.bad) < 0 || (id & ~kEffMask) != 0 || digits > 16 || digits % 2 != 0) return false;
  if (digits == 16) {  // J1939 sends eight bytes in nearly every frame
    const HexBytes data = hex_bytes<8>(s + data_at);
    if (data.bad < 0) return false;
    store8(out.data.data(), data.bytes);
  } else {
    for (std::size_t i = 0; i < digits / 2; ++i) {
      const HexBytes one = hex_bytes<1>(s + data_at + 2 * i);
      if (one.bad < 0) return false;
      out.data[i] = static_cast<std::uint8_t>(one.bytes);
    }
  }
  out.t = capture_time_from_ns(static_cast<std::int64_t>(sec * 1'000'000'000 + usec * 1000));
  out.iface = ifaces.last_index();
  out.kind = CanFrameKind::extended;
  out.id = id;
  out.id29 = false;
  out.fd_flags = 0;
  out.len = static_cast<std::uint8_t>(digits / 2);
  return true;
}

}  // namespace

std::optional<std::uint8_t> InterfaceTable::find(std::string_view name) {
  if (last_ < count_ && names_[last_] == name) return last_;
  for (std::size_t i = 0; i < count_; ++i) {
    if (names_[i] == name) {
      last_ = static_cast<std::uint8_t>(i);
      return last_;
    }
  }
  return std::nullopt;
}

std::optional<std::uint8_t> InterfaceTable::intern(std::string_view name) {
  if (const auto i = find(name)) return i;
  if (count_ == kMax) return std::nullopt;
  names_[count_] = std::string(name);
  char padded[8] = {};
  std::memcpy(padded, name.data(), std::min(name.size(), sizeof padded));
  words_[count_] = load8(padded);
  last_ = static_cast<std::uint8_t>(count_);
  return static_cast<std::uint8_t>(count_++);
}

std::string_view InterfaceTable::name(std::uint8_t index) const {
  return index < count_ ? std::string_view(names_[index]) : std::string_view("?");
}

std::optional<LineError> parse_candump_line(std::string_view line, InterfaceTable& ifaces, CanFrame& out, LineResult& result) {
  if (parse_common(line.data(), line.size(), ifaces, out)) {
    result = LineResult::frame;
    return std::nullopt;
  }
  result = LineResult::ignored;
  // Blank lines and comments are passed over; any other line is a frame or an error, so that a
  // file of something else is refused rather than read as a drive without frames.
  if (line.empty() || line[0] != '(') {
    if (line.find_first_not_of(" \t\r") == std::string_view::npos || line[0] == '#') return std::nullopt;
    return LineError{"timestamp", "expected a candump -L line: (seconds.fraction) iface ID#DATA"};
  }
  if (auto e = parse_stamp(line, out.t)) return e;
  if (line.empty() || line[0] != ' ') return LineError{"interface", "expected ' ' after timestamp"};
  line.remove_prefix(1);
  const std::size_t sp = line.find(' ');
  if (sp == 0 || sp == std::string_view::npos) return LineError{"interface", "missing interface name"};
  const std::string_view name = line.substr(0, sp);
  // A name already in the table was valid when it went in.
  auto idx = ifaces.find(name);
  if (!idx) {
    if (!valid_interface_name(name)) return LineError{"interface", "not a network interface name"};
    idx = ifaces.intern(name);
    if (!idx) return LineError{"interface", "more than 16 interfaces"};
  }
  out.iface = *idx;
  line.remove_prefix(sp + 1);

  const std::size_t hash = line.find('#');
  if (hash == std::string_view::npos) return LineError{"identifier", "missing '#'"};
  if (hash != 3 && hash != 8) return LineError{"identifier", "identifier must have 3 or 8 hex digits"};
  std::uint32_t id = 0;
  for (std::size_t i = 0; i < hash; ++i) {
    const int v = hex_value(line[i]);
    if (v < 0) return LineError{"identifier", "not a hex digit"};
    id = id << 4 | static_cast<std::uint32_t>(v);
  }
  if (hash == 3 && id > 0x7FF) return LineError{"identifier", "11-bit identifier above 0x7FF"};
  if (hash == 8 && id > (kEffMask | kErrFlag)) return LineError{"identifier", "identifier above 29 bits"};
  std::string_view rest = line.substr(hash + 1);
  out.id29 = false;
  out.fd_flags = 0;

  if (!rest.empty() && rest[0] == '#') {  // CAN FD: ID##<flags nibble><data>
    if (rest.size() < 2 || hex_value(rest[1]) < 0) return LineError{"flags", "expected FD flags nibble"};
    out.kind = CanFrameKind::fd;
    out.id29 = hash == 8;
    out.fd_flags = static_cast<std::uint8_t>(hex_value(rest[1]));
    out.id = id & kEffMask;
    if (auto e = parse_bytes(rest.substr(2), 64, out)) return e;
  } else if (!rest.empty() && (rest[0] == 'R' || rest[0] == 'r')) {
    out.kind = CanFrameKind::remote;
    out.id29 = hash == 8;
    out.id = id & kEffMask;
    out.len = 0;
    if (rest.size() == 2 && rest[1] >= '0' && rest[1] <= '8') {
      out.len = static_cast<std::uint8_t>(rest[1] - '0');
    } else if (rest.size() != 1) {
      return LineError{"data", "malformed remote frame length"};
    }
  } else {
    if (hash == 8 && (id & kErrFlag) != 0) {
      out.kind = CanFrameKind::error;
      out.id = id & kEffMask;
    } else {
      out.kind = hash == 8 ? CanFrameKind::extended : CanFrameKind::standard;
      out.id = id;
    }
    if (auto e = parse_bytes(rest, 8, out)) return e;
  }
  result = LineResult::frame;
  return std::nullopt;
}

namespace {

// `digits` decimal digits of v, zero-padded (v < 10^digits).
char* put_decimal(char* p, std::uint64_t v, int digits) {
  for (int i = digits - 1; i >= 0; --i) {
    p[i] = static_cast<char>('0' + v % 10);
    v /= 10;
  }
  return p + digits;
}

// "(SSSSSSSSSS.UUUUUU) IFACE ". By hand: snprintf was a sixth of roadloadd's time recording a bus.
// A stamp before the epoch keeps printf's rendering of it.
std::size_t put_stamp_and_iface(std::int64_t ns, std::string_view iface, char* buf) {
  const std::int64_t sec = ns / 1'000'000'000;
  const std::int64_t usec = (ns % 1'000'000'000) / 1000;
  if (ns < 0 || iface.size() > kMaxLineChars / 2) {
    const int n = std::snprintf(buf, kMaxLineChars, "(%010lld.%06lld) %.*s ", static_cast<long long>(sec),
                                static_cast<long long>(usec), static_cast<int>(iface.size()), iface.data());
    return static_cast<std::size_t>(n);
  }
  char* p = buf;
  *p++ = '(';
  p = put_decimal(p, static_cast<std::uint64_t>(sec), 10);  // an int64 of ns is under 10^10 s
  *p++ = '.';
  p = put_decimal(p, static_cast<std::uint64_t>(usec), 6);
  *p++ = ')';
  *p++ = ' ';
  std::memcpy(p, iface.data(), iface.size());
  p += iface.size();
  *p++ = ' ';
  return static_cast<std::size_t>(p - buf);
}

}  // namespace

std::size_t format_candump_line(const CanFrame& f, std::string_view iface, char* buf) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::size_t pos = put_stamp_and_iface(to_ns(f.t), iface, buf);
  auto put_id = [&](std::uint32_t id, int digits) {
    for (int d = digits - 1; d >= 0; --d) buf[pos++] = kHex[(id >> (4 * d)) & 0xF];
  };
  switch (f.kind) {
    case CanFrameKind::standard: put_id(f.id, 3); break;
    case CanFrameKind::extended: put_id(f.id, 8); break;
    case CanFrameKind::error: put_id(f.id | kErrFlag, 8); break;
    case CanFrameKind::remote:
    case CanFrameKind::fd: put_id(f.id, f.id29 ? 8 : 3); break;
  }
  buf[pos++] = '#';
  if (f.kind == CanFrameKind::remote) {
    buf[pos++] = 'R';
    // A requested length is part of the frame; can-utils writes it as one digit after R.
    if (f.len > 0) buf[pos++] = static_cast<char>('0' + f.len);
    buf[pos] = '\0';
    return pos;
  }
  if (f.kind == CanFrameKind::fd) {
    buf[pos++] = '#';
    buf[pos++] = kHex[f.fd_flags & 0xF];
  }
  for (std::size_t i = 0; i < f.len; ++i) {
    buf[pos++] = kHex[f.data[i] >> 4];
    buf[pos++] = kHex[f.data[i] & 0xF];
  }
  buf[pos] = '\0';
  return pos;
}

}  // namespace roadload::recording
