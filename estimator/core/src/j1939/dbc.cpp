#include "roadload/j1939/dbc.hpp"

#include <charconv>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "roadload/text_scan.hpp"

namespace roadload::j1939 {
namespace {

constexpr std::uint32_t kDbcExtendedFlag = 0x80000000u;
constexpr std::uint32_t kMaxMessageBytes = 0xFFFFFFu;  // ETP; the transport reassembler bounds it further

struct Failure {
  ParseError error;
};

// A character cursor that knows its line, so every error can name file, line and field.
class Cursor {
 public:
  Cursor(std::string_view text, std::string_view source) : text_(text), source_(source) {}

  bool at_end() {
    skip_space();
    return pos_ >= text_.size();
  }

  [[noreturn]] void fail(std::string_view field, std::string message) const {
    throw Failure{ParseError{std::string(source_), line_, std::string(field), std::move(message)}};
  }

  // White space and // comments.
  void skip_space() {
    for (;;) {
      pos_ = skip_whitespace(text_, pos_, line_);
      if (pos_ + 1 >= text_.size() || text_[pos_] != '/' || text_[pos_ + 1] != '/') return;
      skip_line();
    }
  }

  // Spaces only: for statements whose fields must stay on one line.
  void skip_blanks() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\r')) ++pos_;
  }

  // A comma between receivers; never looks past the end of the line.
  bool accept_on_line(char c) {
    skip_blanks();
    if (pos_ >= text_.size() || text_[pos_] != c) return false;
    ++pos_;
    return true;
  }

  bool at_line_end() {
    skip_blanks();
    return pos_ >= text_.size() || text_[pos_] == '\n';
  }

  void skip_line() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  }

  char peek() {
    skip_space();
    return pos_ < text_.size() ? text_[pos_] : '\0';
  }

  bool accept(char c) {
    if (peek() != c) return false;
    ++pos_;
    return true;
  }

  void expect(char c, std::string_view field) {
    if (!accept(c)) fail(field, std::string("expected '") + c + "'" + found());
  }

  std::string_view identifier(std::string_view field) {
    skip_space();
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && is_ident_char(text_[pos_])) ++pos_;
    if (pos_ == begin) fail(field, "expected a name" + found());
    return text_.substr(begin, pos_ - begin);
  }

  double number(std::string_view field) {
    skip_space();
    const std::size_t begin = pos_;
    if (pos_ < text_.size() && (text_[pos_] == '+' || text_[pos_] == '-')) ++pos_;
    while (pos_ < text_.size() && (is_number_char(text_[pos_]))) ++pos_;
    double v = 0;
    const char* first = text_.data() + begin;
    const char* last = text_.data() + pos_;
    if (first != last && *first == '+') ++first;
    const auto [end, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || end != last || first == last) {
      pos_ = begin;
      fail(field, "expected a number" + found());
    }
    return v;
  }

  std::uint64_t unsigned_integer(std::string_view field, std::uint64_t max) {
    skip_space();
    const std::size_t begin = pos_;
    std::uint64_t v = 0;
    const auto [end, ec] = std::from_chars(text_.data() + pos_, text_.data() + text_.size(), v);
    if (ec != std::errc() || end == text_.data() + begin) fail(field, "expected an unsigned integer" + found());
    pos_ = static_cast<std::size_t>(end - text_.data());
    if (v > max) fail(field, "value " + std::to_string(v) + " exceeds " + std::to_string(max));
    return v;
  }

  std::string string(std::string_view field) {
    expect('"', field);
    const long start_line = line_;
    std::string s;
    while (pos_ < text_.size() && text_[pos_] != '"') {
      if (text_[pos_] == '\\' && pos_ + 1 < text_.size()) ++pos_;
      if (text_[pos_] == '\n') ++line_;
      s.push_back(text_[pos_++]);
    }
    if (pos_ >= text_.size()) {
      line_ = start_line;
      fail(field, "unterminated string");
    }
    ++pos_;
    return s;
  }

  // Skips a statement this reader does not need, honouring strings that may span lines.
  void skip_statement(std::string_view keyword) {
    const long start_line = line_;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '"') {
        string(keyword);
        continue;
      }
      ++pos_;
      if (c == '\n') ++line_;
      if (c == ';') return;
    }
    line_ = start_line;
    fail(keyword, "statement has no terminating ';'");
  }

  // NS_ lists symbol names on indented lines; the block ends at the first unindented line.
  void skip_indented_block() {
    skip_line();
    while (pos_ < text_.size()) {
      ++pos_;  // the newline
      ++line_;
      if (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\r' || text_[pos_] == '\n')) {
        if (text_[pos_] != '\n') skip_line();
        continue;
      }
      return;
    }
  }

 private:
  static bool is_ident_char(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; }
  static bool is_number_char(char c) { return (c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-'; }
  std::string found() const {
    if (pos_ >= text_.size()) return ", found end of file";
    const std::size_t end = text_.find_first_of(" \t\r\n", pos_);
    return ", found '" + std::string(text_.substr(pos_, std::min<std::size_t>(end - pos_, 24))) + "'";
  }

  std::string_view text_;
  std::string_view source_;
  std::size_t pos_ = 0;
  long line_ = 1;
};

struct PendingMessage {
  MessageDef def;
  std::uint32_t dbc_id = 0;
  bool extended = false;
};

class DbcReader {
 public:
  DbcReader(std::string_view text, std::string_view source) : in_(text, source) {}

  std::vector<MessageDef> read() {
    while (!in_.at_end()) statement();
    std::vector<MessageDef> out;
    for (PendingMessage& m : messages_) {
      // 11-bit messages cannot carry J1939 parameters; the database is keyed by PGN.
      if (m.extended) out.push_back(std::move(m.def));
    }
    return out;
  }

 private:
  void statement() {
    const std::string_view kw = in_.identifier("keyword");
    if (kw == "VERSION") {
      in_.string("VERSION");
    } else if (kw == "NS_") {
      in_.expect(':', "NS_");
      in_.skip_indented_block();
    } else if (kw == "BS_" || kw == "BU_") {
      in_.expect(':', kw);
      in_.skip_line();
    } else if (kw == "BO_") {
      message();
    } else if (kw == "SG_") {
      signal();
    } else if (kw == "BA_") {
      attribute();
    } else if (kw == "CM_" || kw == "BA_DEF_" || kw == "BA_DEF_DEF_" || kw == "BA_DEF_REL_" || kw == "BA_DEF_DEF_REL_" ||
               kw == "BA_REL_" || kw == "VAL_" || kw == "VAL_TABLE_" || kw == "SIG_VALTYPE_" || kw == "BO_TX_BU_" || kw == "EV_" ||
               kw == "ENVVAR_DATA_" || kw == "SIG_GROUP_" || kw == "SGTYPE_" || kw == "SIG_TYPE_REF_" || kw == "CAT_DEF_" ||
               kw == "CAT_" || kw == "FILTER" || kw == "SG_MUL_VAL_") {
      in_.skip_statement(kw);
    } else {
      in_.fail("keyword", "unknown DBC keyword '" + std::string(kw) + "'");
    }
  }

  void message() {
    PendingMessage m;
    const auto id = static_cast<std::uint32_t>(in_.unsigned_integer("BO_ id", 0xFFFFFFFFu));
    m.dbc_id = id;
    m.extended = (id & kDbcExtendedFlag) != 0;
    m.def.pgn = pgn_of(id & 0x1FFFFFFFu);
    m.def.name = std::string(in_.identifier("BO_ name"));
    in_.expect(':', "BO_");
    m.def.length = static_cast<std::uint32_t>(in_.unsigned_integer("BO_ dlc", kMaxMessageBytes));
    in_.identifier("BO_ transmitter");
    messages_.push_back(std::move(m));
  }

  void signal() {
    if (messages_.empty()) in_.fail("SG_", "signal outside a BO_ message");
    SignalDef s;
    s.name = std::string(in_.identifier("SG_ name"));
    bool multiplexed = false;
    if (in_.peek() != ':') {
      const std::string_view mux = in_.identifier("SG_ multiplexer");
      if (mux.empty() || (mux[0] != 'M' && mux[0] != 'm')) in_.fail("SG_ multiplexer", "expected M or mN");
      multiplexed = mux[0] == 'm';
    }
    in_.expect(':', "SG_");
    const auto start = in_.unsigned_integer("SG_ start bit", 0xFFFFFFFFu);
    in_.expect('|', "SG_ start bit");
    const auto length = in_.unsigned_integer("SG_ length", 64);
    if (length == 0) in_.fail("SG_ length", "length must be 1 to 64 bits");
    in_.expect('@', "SG_ byte order");
    const auto order = in_.unsigned_integer("SG_ byte order", 1);
    const char sign = in_.peek();
    if (sign != '+' && sign != '-') in_.fail("SG_ sign", "expected '+' or '-'");
    in_.accept(sign);
    in_.expect('(', "SG_ factor");
    s.factor = in_.number("SG_ factor");
    in_.expect(',', "SG_ offset");
    s.offset = in_.number("SG_ offset");
    in_.expect(')', "SG_ offset");
    if (s.factor == 0.0) in_.fail("SG_ factor", "factor must not be 0");
    in_.expect('[', "SG_ minimum");
    s.minimum = in_.number("SG_ minimum");
    in_.expect('|', "SG_ maximum");
    s.maximum = in_.number("SG_ maximum");
    in_.expect(']', "SG_ maximum");
    s.unit = in_.string("SG_ unit");
    while (!in_.at_line_end()) {
      in_.identifier("SG_ receiver");
      in_.accept_on_line(',');
    }
    s.start_bit = static_cast<std::uint16_t>(start);
    s.length = static_cast<std::uint8_t>(length);
    s.order = order == 1 ? ByteOrder::little_endian : ByteOrder::big_endian;
    s.is_signed = sign == '-';
    if (start > 0xFFFFu) in_.fail("SG_ start bit", "start bit beyond 65535 is not supported");
    // Values of a multiplexed signal depend on the multiplexer; decoding them as plain signals
    // would print wrong numbers, so they are not loaded.
    if (!multiplexed) messages_.back().def.signals.push_back(std::move(s));
  }

  void attribute() {
    const std::string name = in_.string("BA_ name");
    const char c = in_.peek();
    if (c != 'B' && c != 'S') {
      in_.skip_statement("BA_");
      return;
    }
    const std::string_view object = in_.identifier("BA_ object");
    if (object == "BO_" && name == "GenMsgCycleTime") {
      PendingMessage* m = find(in_.unsigned_integer("BA_ message id", 0xFFFFFFFFu));
      const double ms = in_.number("BA_ GenMsgCycleTime");
      if (ms < 0) in_.fail("BA_ GenMsgCycleTime", "negative cycle time");
      m->def.cycle_time_ms = static_cast<std::uint32_t>(ms);
      in_.expect(';', "BA_");
    } else if (object == "SG_" && name == "SPN") {
      signal_attribute("BA_ SPN", 524287, [](SignalDef& s, std::uint64_t v) { s.spn = static_cast<std::uint32_t>(v); });
    } else if (object == "SG_" && name == "J1939Ranges") {
      // 0 marks a field with no reserved ranges (a raw bit pattern such as a DTC's SPN bits).
      signal_attribute("BA_ J1939Ranges", 1, [](SignalDef& s, std::uint64_t v) { s.j1939_ranges = v != 0; });
    } else {
      in_.skip_statement("BA_");
    }
  }

  // `BA_ "Name" SG_ <message id> <signal> <value>;` applied to the named signal.
  template <typename Apply>
  void signal_attribute(std::string_view field, std::uint64_t max, Apply apply) {
    PendingMessage* m = find(in_.unsigned_integer("BA_ message id", 0xFFFFFFFFu));
    const std::string_view sig = in_.identifier("BA_ signal name");
    const std::uint64_t value = in_.unsigned_integer(field, max);
    for (SignalDef& s : m->def.signals) {
      if (s.name == sig) apply(s, value);
    }
    in_.expect(';', "BA_");
  }

  PendingMessage* find(std::uint64_t dbc_id) {
    for (PendingMessage& m : messages_) {
      if (m.dbc_id == dbc_id) return &m;
    }
    in_.fail("BA_ message id", "no BO_ with id " + std::to_string(dbc_id));
  }

  Cursor in_;
  std::vector<PendingMessage> messages_;
};

}  // namespace

std::optional<ParseError> load_dbc(Database& db, std::string_view text, std::string_view source) {
  std::vector<MessageDef> messages;
  try {
    messages = DbcReader(text, source).read();
  } catch (const Failure& f) {
    return f.error;
  }
  for (MessageDef& m : messages) db.add(std::move(m));
  return std::nullopt;
}

}  // namespace roadload::j1939
