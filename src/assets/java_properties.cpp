#include "assets/java_properties.h"

#include <fmt/format.h>

#include "core/error.h"

namespace inet {
namespace {

void appendUtf8(std::string& out, uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\f';
}

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/// Reads one logical line starting at `pos`: continuation backslashes and the next line's
/// leading blanks removed, escapes still in place. Advances `pos` and `line`.
std::string logicalLine(std::string_view text, size_t& pos, int& line) {
  std::string out;
  while (pos < text.size()) {
    const size_t end = text.find_first_of("\r\n", pos);
    std::string_view natural =
        text.substr(pos, end == std::string_view::npos ? text.npos : end - pos);
    pos = end == std::string_view::npos ? text.size() : end;
    if (pos < text.size() && text[pos] == '\r') {
      ++pos;
      if (pos < text.size() && text[pos] == '\n') ++pos;  // \r\n is one line break
    } else if (pos < text.size()) {
      ++pos;  // \n
    }
    ++line;
    size_t backslashes = 0;
    while (backslashes < natural.size() && natural[natural.size() - 1 - backslashes] == '\\')
      ++backslashes;
    const bool continues = backslashes % 2 == 1;
    out += continues ? natural.substr(0, natural.size() - 1) : natural;
    if (!continues) break;
    while (pos < text.size() && isBlank(text[pos])) ++pos;  // the next line's indentation
  }
  return out;
}

/// Unescapes s[begin, end) into UTF-8 (each other byte is an ISO-8859-1 code point).
std::string unescape(const std::string& s, size_t begin, size_t end, const std::string& where,
                     int line) {
  std::string out;
  for (size_t i = begin; i < end; ++i) {
    const char c = s[i];
    if (c != '\\') {
      appendUtf8(out, static_cast<unsigned char>(c));
      continue;
    }
    if (++i >= end) break;  // a lone trailing backslash (an even run already consumed) is lost
    const char e = s[i];
    if (e == 'u') {
      uint32_t cp = 0;
      for (int k = 0; k < 4; ++k) {
        const int h = i + 1 + k < end ? hexValue(s[i + 1 + k]) : -1;
        if (h < 0)
          throw InputError(where, fmt::format("line {}", line), "malformed \\uxxxx escape");
        cp = cp * 16 + static_cast<uint32_t>(h);
      }
      i += 4;
      appendUtf8(out, cp);
    } else {
      appendUtf8(out, e == 't'   ? '\t'
                      : e == 'n' ? '\n'
                      : e == 'r' ? '\r'
                      : e == 'f' ? '\f'
                                 : static_cast<unsigned char>(e));
    }
  }
  return out;
}

}  // namespace

JavaProperties parseJavaProperties(std::string_view text, const std::string& where) {
  JavaProperties props;
  size_t pos = 0;
  int line = 0;
  while (pos < text.size()) {
    const int first_line = line + 1;
    const std::string l = logicalLine(text, pos, line);
    size_t i = 0;
    while (i < l.size() && isBlank(l[i])) ++i;
    if (i == l.size() || l[i] == '#' || l[i] == '!') continue;
    const size_t key_begin = i;
    while (i < l.size() && l[i] != '=' && l[i] != ':' && !isBlank(l[i])) i += l[i] == '\\' ? 2 : 1;
    const size_t key_end = std::min(i, l.size());
    while (i < l.size() && isBlank(l[i])) ++i;
    if (i < l.size() && (l[i] == '=' || l[i] == ':')) ++i;
    while (i < l.size() && isBlank(l[i])) ++i;
    props[unescape(l, key_begin, key_end, where, first_line)] =
        unescape(l, std::min(i, l.size()), l.size(), where, first_line);
  }
  return props;
}

}  // namespace inet
