// What the model and scene readers share: parsing a TOML file with located syntax errors, and the
// checks every table needs (known keys, strings), each complaint placed at the value it concerns.
#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include <toml++/toml.h>

#include "common/input_error.hpp"

namespace pogear {

SourceLocation toml_location(const std::string& file, const toml::source_region& region);

// Names become C++ identifiers and column headers; 64 characters is generous for `J_planet_3`.
inline constexpr std::size_t max_name_length = 64;

// Dotted keys (`a.b.c = 1`, `[a.b.c]`) of more parts than this are refused before parsing.
inline constexpr std::size_t max_key_parts = 64;

// Parses `text` (read from `path`); a file larger than `max_bytes` is refused with `too_large`, one
// with a dotted key of max_key_parts parts or more before the parser sees it.
toml::table parse_toml_document(const std::string& text, const std::string& path, std::size_t max_bytes,
                                const std::string& too_large);

// A short fingerprint of a file's text (64-bit FNV-1a, 16 hex digits): it names, in generated code,
// which model and scene text it came from. It tells versions apart; it is no defence against forgery.
std::string text_digest(std::string_view text);

// The contents of an input file, read at most `limit` bytes far (a FIFO or /dev/zero must not
// fill the memory). Throws InputError naming the file when it cannot be read, is a directory or
// is larger; `what` names it in messages: "file" (a model), "scene file".
std::string read_input_file(const std::string& path, std::size_t limit, const std::string& what);

struct TomlReader {
  std::string file;

  SourceLocation loc(const toml::node& n) const { return toml_location(file, n.source()); }
  [[noreturn]] void fail(const toml::node& n, const std::string& message) const;
  // Refuses keys of `t` outside `allowed`, listing the allowed ones; `what` names the table.
  void only_keys(const toml::table& t, std::initializer_list<std::string_view> allowed, std::string_view what) const;
  std::string string(const toml::node& n, std::string_view what) const;
  const toml::table& table(const toml::node& n, std::string_view what) const;
  std::optional<std::string> optional_string(const toml::table& t, std::string_view key, std::string_view what) const;
  // A name that becomes an identifier in generated code: letters, digits and '_', from a letter,
  // at most max_name_length characters.
  std::string identifier(const toml::node& n, std::string_view what) const;
};

// Whether `s` is such a name's form: letters, digits and '_', from a letter (its length unchecked).
bool is_name(std::string_view s);

}  // namespace pogear
