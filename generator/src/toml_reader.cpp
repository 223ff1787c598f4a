// Shared TOML reading for models and scenes; see toml_reader.hpp.
#include "toml_reader.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace pogear {

SourceLocation toml_location(const std::string& file, const toml::source_region& region) {
  return SourceLocation{file, static_cast<int>(region.begin.line), static_cast<int>(region.begin.column)};
}

toml::table parse_toml_document(const std::string& text, const std::string& path, std::size_t max_bytes,
                                const std::string& too_large) {
  if (text.size() > max_bytes) throw InputError(SourceLocation{path, 0, 0}, too_large);
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

}  // namespace pogear
