// Text for messages: UTF-8 and escaping, shared by every command.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace minksum::cli {

// The length of the valid UTF-8 sequence starting at s[i] (1 for ASCII), or 0
// when s[i] does not start one (a stray continuation byte, an overlong form,
// a surrogate, a code point beyond U+10FFFF, a truncated sequence); the code
// point in *code when given.
std::size_t utf8_length(std::string_view s, std::size_t i, char32_t* code = nullptr);

// Text safe to print on one line of a terminal: valid UTF-8 is kept, a
// newline, tab or carriage return becomes \n, \t, \r, any other control
// character (C0, DEL, C1) and every byte that is not part of valid UTF-8
// becomes \xNN.  Every message and every echoed name goes through it, so one
// error is one line and no terminal escape sequence reaches the terminal.
std::string printable(std::string_view s);

}  // namespace minksum::cli
