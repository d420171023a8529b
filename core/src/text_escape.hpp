// Character escapes as tables: a text format lists once which characters it spells differently
// (JSON's \n, XML's &lt;, ...), and both its writer and its reader use that list.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>

namespace tristim {

/// One character and how a format spells it. `written`: the writer uses the spelling (false: the
/// reader accepts it, the writer leaves the character as it is or spells it another way).
struct CharEscape {
  char raw;
  std::string_view text;
  bool written = true;
};

/// The row the writer uses for `raw`, or nullptr.
template <std::size_t N>
const CharEscape* escape_of(char raw, const CharEscape (&table)[N]) {
  for (const CharEscape& e : table)
    if (e.written && e.raw == raw) return &e;
  return nullptr;
}

/// The row spelled `text` (the reader's lookup), or nullptr.
template <std::size_t N>
const CharEscape* escape_named(std::string_view text, const CharEscape (&table)[N]) {
  for (const CharEscape& e : table)
    if (e.text == text) return &e;
  return nullptr;
}

/// Appends `s` to `out` with each character the table writes spelled as its text; every other
/// character goes through other(out, c).
template <std::size_t N, class Other>
void append_escaped(std::string& out, std::string_view s, const CharEscape (&table)[N], Other other) {
  for (char c : s) {
    if (const CharEscape* e = escape_of(c, table)) out += e->text;
    else other(out, c);
  }
}

}  // namespace tristim
