// Shared TOML reading for models and scenes; see toml_reader.hpp.
#include "read/toml_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>

#include <fmt/format.h>

#include "pogear/input_file.hpp"

namespace pogear {

SourceLocation toml_location(const std::string& file, const toml::source_region& region) {
  return SourceLocation{file, static_cast<int>(region.begin.line), static_cast<int>(region.begin.column)};
}

namespace {

// toml++ parses a dotted key recursively, one call per part, and overflows the stack from about
// 30,500 parts (`a.a.a...= 1`, or a `[a.a...]` header). No model or scene needs more than a few, so
// the text is scanned before parsing: outside strings and comments, a run of key characters,
// quoted parts and blanks joined by more than max_key_parts - 1 dots is refused. Numbers (one dot),
// dates and values in lists (separated by commas) never come near the bound.
void check_dotted_keys(const std::string& text, const std::string& path) {
  int line = 1, column = 0, run_line = 1, run_column = 1;
  std::size_t dots = 0;
  auto key_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == ' ' || c == '\t';
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    ++column;
    if (c == '\n') {
      ++line;
      column = 0;
      dots = 0;
      continue;
    }
    if (c == '#') {  // a comment runs to the end of the line
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
      continue;
    }
    if (c == '"' || c == '\'') {  // a string is one part of a key, or a value; skip it whole
      const bool triple = text.compare(i, 3, std::string(3, c)) == 0;
      const std::string close = triple ? std::string(3, c) : std::string(1, c);
      std::size_t j = i + close.size();
      while (j < text.size() && text.compare(j, close.size(), close) != 0 && (triple || text[j] != '\n')) {
        if (c == '"' && text[j] == '\\') ++j;
        if (j < text.size() && text[j] == '\n') ++line, column = 0;
        ++j;
      }
      column += static_cast<int>(j + close.size() - 1 - i);
      i = std::min(j + close.size() - 1, text.size() - 1);
      continue;
    }
    if (c == '.') {
      if (dots == 0) run_line = line, run_column = column;
      if (++dots >= max_key_parts)
        throw InputError(SourceLocation{path, run_line, run_column},
                         fmt::format("a dotted key of more than {} parts; keys in pogear's files have at most a few "
                                     "parts: write the key as its table and name",
                                     max_key_parts));
      continue;
    }
    if (!key_char(c)) dots = 0;
  }
}

}  // namespace

toml::table parse_toml_document(const std::string& text, const std::string& path, std::size_t max_bytes,
                                const std::string& too_large) {
  if (text.size() > max_bytes) throw InputError(SourceLocation{path, 0, 0}, too_large);
  check_dotted_keys(text, path);
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(toml_location(path, e.source()), std::string(e.description()) + "; fix the TOML syntax");
  }
}

void TomlReader::fail(const toml::node& n, const std::string& message) const { throw InputError(loc(n), message); }

void TomlReader::only_keys(const toml::table& t, std::initializer_list<std::string_view> allowed,
                           std::string_view what) const {
  for (const auto& [key, value] : t) {
    if (std::find(allowed.begin(), allowed.end(), key.str()) != allowed.end()) continue;
    std::string list;
    for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    throw InputError(toml_location(file, key.source()),
                     fmt::format("unknown key '{}' in {}; the keys are {}", key.str(), what, list));
  }
}

std::string TomlReader::string(const toml::node& n, std::string_view what) const {
  if (!n.is_string()) fail(n, fmt::format("{} must be a string in quotes", what));
  return *n.value<std::string>();
}

const toml::table& TomlReader::table(const toml::node& n, std::string_view what) const {
  if (!n.is_table()) fail(n, fmt::format("{} must be a table {{ ... }}", what));
  return *n.as_table();
}

std::optional<std::string> TomlReader::optional_string(const toml::table& t, std::string_view key,
                                                       std::string_view what) const {
  const toml::node* n = t.get(key);
  if (!n) return std::nullopt;
  return string(*n, what);
}

bool is_name(std::string_view s) {
  return !s.empty() && std::isalpha(static_cast<unsigned char>(s[0])) &&
         std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

std::string TomlReader::identifier(const toml::node& n, std::string_view what) const {
  std::string s = string(n, what);
  if (!is_name(s)) fail(n, fmt::format("{} '{}' is not a name; use letters, digits and '_', starting with a letter", what, s));
  if (s.size() > max_name_length)
    fail(n, fmt::format("{} is {} characters long; names have at most {}", what, s.size(), max_name_length));
  return s;
}

std::string text_digest(std::string_view text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return fmt::format("{:016x}", h);
}

std::string read_input_file(const std::string& path, std::size_t limit, const std::string& what) {
  const SourceLocation where{path, 0, 0};
  rt::InputFile in = rt::read_regular_file(path, limit);
  switch (in.status) {
    case rt::InputFileStatus::ok: return std::move(in.text);
    case rt::InputFileStatus::cannot_open:
      throw InputError(where, fmt::format("cannot read the {} ({}); check the path", what, in.reason));
    case rt::InputFileStatus::directory:
      throw InputError(where, fmt::format("this is a directory; give the {} itself", what));
    case rt::InputFileStatus::not_regular:
      // A FIFO or a device would hang or never end; a model is a file on disk.
      throw InputError(where, fmt::format("this is {}, not a regular file; give the path of the {} itself", in.reason,
                                          what));
    case rt::InputFileStatus::too_large:
      throw InputError(where, fmt::format("the {} is larger than {} bytes; a model or scene file is a few kilobytes",
                                          what, limit));
    case rt::InputFileStatus::read_error: break;
  }
  throw InputError(where, fmt::format("cannot read the {}: a read error; check the file", what));
}

}  // namespace pogear
