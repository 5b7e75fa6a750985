// SPDX-License-Identifier: MIT
// one_line: the text of an error message with its control characters escaped, so that a user
// string inside it (a file or body name, a key, a command-line word) can neither break the
// message's single line nor reach the terminal as an escape sequence.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace elan {

/// `text` with every control character escaped JSON-style: \n, \r, \t, \b, \f, and \u00XX for
/// the other C0 codes (NUL and ESC included), DEL (\u007f) and the C1 codes U+0080..U+009F
/// (UTF-8 C2 80..C2 9F), which some terminals obey as escapes (U+009B is CSI). Backslashes are
/// left alone, so applying it twice changes nothing: every exception type whose message may
/// carry a user string applies it, and the command-line tool applies it again when printing.
inline std::string one_line(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  const auto code = [&out](unsigned c) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "\\u%04x", c);
    out += buf;
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == 0xc2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
        static_cast<unsigned char>(text[i + 1]) <= 0x9f) {
      code(static_cast<unsigned char>(text[++i]));
      continue;
    }
    switch (c) {
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      default:
        if (c < 0x20 || c == 0x7f) {
          code(c);
        } else {
          out.push_back(char(c));
        }
    }
  }
  return out;
}

}  // namespace elan
