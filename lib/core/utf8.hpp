#pragma once
// UTF-8 as RFC 3629 defines it, for text that reaches a report or a message from a user's file:
// what is well formed is kept, what is not is refused or replaced by the caller, never copied on.
#include <cstddef>
#include <string_view>

namespace wr {

// The length (1 to 4) of the well-formed UTF-8 sequence at s[i], or 0 where there is none (a
// stray continuation byte, a truncated sequence, an overlong form, a surrogate, a code point
// above U+10FFFF: latin-1 text such as "Stra\xDF" is one of these). Its code point in `cp`.
inline std::size_t utf8_length_at(std::string_view s, std::size_t i, char32_t* cp = nullptr) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[i + k]); };
  const unsigned char c = b(0);
  std::size_t n = 0;
  char32_t v = 0, min = 0;
  if (c < 0x80) n = 1, v = c;
  else if (c >= 0xC2 && c <= 0xDF) n = 2, v = c & 0x1F, min = 0x80;
  else if (c >= 0xE0 && c <= 0xEF) n = 3, v = c & 0x0F, min = 0x800;
  else if (c >= 0xF0 && c <= 0xF4) n = 4, v = c & 0x07, min = 0x10000;
  else return 0;
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((b(k) & 0xC0) != 0x80) return 0;
    v = (v << 6) | (b(k) & 0x3F);
  }
  if (v < min || v > 0x10FFFF || (v >= 0xD800 && v <= 0xDFFF)) return 0;
  if (cp) *cp = v;
  return n;
}

// A control character (C0, DEL, C1): not text to show.
inline bool is_control(char32_t cp) { return cp < 0x20 || (cp >= 0x7F && cp <= 0x9F); }

}  // namespace wr
