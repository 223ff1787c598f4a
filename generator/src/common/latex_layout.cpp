// The width estimate walks the LaTeX that pogear's printer writes (amsmath, no user macros); the
// rewrites keep every symbol and only change what TeX may break, so a report reads the same.
#include "common/latex_layout.hpp"

#include <algorithm>
#include <cctype>
#include <numeric>

#include <fmt/format.h>

#include "common/printer.hpp"

namespace pogear {
namespace {

bool is_letter(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }

// The name of the command whose backslash is at s[i]: its letters, or the one other character.
std::string_view command_at(std::string_view s, std::size_t i) {
  std::size_t j = i + 1;
  while (j < s.size() && is_letter(s[j])) ++j;
  if (j == i + 1 && j < s.size()) ++j;
  return s.substr(i + 1, j - i - 1);
}

bool command_is(std::string_view s, std::size_t i, std::string_view name) {
  return i < s.size() && s[i] == '\\' && command_at(s, i) == name;
}

// One past the '}' that closes the group opening at s[i] == '{'.
std::size_t group_end(std::string_view s, std::size_t i) {
  int depth = 0;
  for (; i < s.size(); ++i) {
    if (s[i] == '\\') ++i;  // \{ and \} are characters, not braces
    else if (s[i] == '{') ++depth;
    else if (s[i] == '}' && --depth == 0) return i + 1;
  }
  return s.size();
}

std::size_t skip_spaces(std::string_view s, std::size_t i) {
  while (i < s.size() && s[i] == ' ') ++i;
  return i;
}

// Where the \right that closes the \left at s[i] starts.
std::size_t matching_right(std::string_view s, std::size_t i) {
  int depth = 0;
  for (; i < s.size(); ++i) {
    if (command_is(s, i, "left")) ++depth;
    else if (command_is(s, i, "right") && --depth == 0) return i;
    if (s[i] == '\\') i += command_at(s, i).size();
  }
  return s.size();
}

// Commands that print nothing of their own: sizes, styles, fonts (their argument counts), spaces
// too thin to matter, break points.
bool prints_nothing(std::string_view name) {
  static constexpr std::string_view none[] = {
      "left", "right", "bigl", "bigr", "big", "bigm", "Bigl", "Bigr", "displaystyle", "textstyle",
      "mathrm", "mathbf", "mathsf", "boldsymbol", "operatorname", "text", "dot", "hat", "allowbreak",
      "nolimits", "limits", ",", ";", "!", "\\", "raggedright", "arraybackslash", "hline", "relax"};
  return std::find(std::begin(none), std::end(none), name) != std::end(none);
}

std::size_t command_width(std::string_view name) {
  if (prints_nothing(name)) return 0;
  if (name == "quad") return 2;
  if (name == "qquad") return 4;
  static constexpr std::string_view words[] = {"cos", "sin", "tan", "arccos", "log", "exp", "det", "ln"};
  if (std::find(std::begin(words), std::end(words), name) != std::end(words)) return name.size();
  return 1;  // \omega, \cdot, \_, \textasciicircum, ...
}

// The scan of latex_width: `text` while in text mode (where a space is as wide as a character),
// toggled by $ and entered by \text{}.
struct Cursor {
  std::string_view s;
  std::size_t i = 0;
  bool text = false;
};

std::size_t environment_width(Cursor& c);
std::size_t argument_width(Cursor& c, bool text);

// The width of what follows up to the end, a '}' closing an enclosing group, or, in a matrix's
// cell, the cell's end (& or \\ or \end).
std::size_t scan_width(Cursor& c, bool cell) {
  std::size_t w = 0;
  while (c.i < c.s.size()) {
    const char ch = c.s[c.i];
    if (ch == '}' || (cell && ch == '&')) return w;
    if (ch == '{') {
      w += argument_width(c, c.text);
      continue;
    }
    if (ch == '\\') {
      const std::string_view name = command_at(c.s, c.i);
      if (cell && (name == "\\" || name == "end")) return w;
      c.i += 1 + name.size();
      if (name == "frac") {
        const std::size_t up = argument_width(c, false);
        w += 1 + std::max(up, argument_width(c, false));
      } else if (name == "begin") {
        w += environment_width(c);
      } else if (name == "text") {
        w += argument_width(c, true);
      } else {
        w += command_width(name);
      }
      continue;
    }
    ++c.i;
    if (ch == '$') c.text = !c.text;
    else if (ch == '^' || ch == '_' || ch == '&' || ch == '\n') continue;
    else if (ch == ' ') w += c.text ? 1 : 0;
    else if (!c.text && (ch == '+' || ch == '-' || ch == '=' || ch == '<' || ch == '>')) w += 2;
    else ++w;
  }
  return w;
}

// A {group} or a single character or command, as an argument of \frac or \text.
std::size_t argument_width(Cursor& c, bool text) {
  c.i = skip_spaces(c.s, c.i);
  if (c.i >= c.s.size()) return 0;
  if (c.s[c.i] != '{') {
    if (c.s[c.i] != '\\') return ++c.i, 1;
    const std::string_view name = command_at(c.s, c.i);
    c.i += 1 + name.size();
    return command_width(name);
  }
  ++c.i;
  const bool outer = c.text;
  c.text = text;
  const std::size_t w = scan_width(c, false);
  c.text = outer;
  if (c.i < c.s.size()) ++c.i;  // the '}'
  return w;
}

// After \begin: the environment's name, then rows of cells up to \end{...}. Its width is that of
// its widest cells, column by column, with the gaps and brackets between them.
std::size_t environment_width(Cursor& c) {
  c.i = c.i < c.s.size() && c.s[c.i] == '{' ? group_end(c.s, c.i) : c.i;
  std::vector<std::size_t> columns;
  std::size_t column = 0;
  while (c.i < c.s.size()) {
    const std::size_t w = scan_width(c, true);
    if (columns.size() <= column) columns.push_back(0);
    columns[column] = std::max(columns[column], w);
    if (c.i >= c.s.size()) break;
    if (c.s[c.i] == '&') {
      ++c.i, ++column;
    } else if (c.s[c.i] == '}') {
      ++c.i;  // a stray brace: counted as nothing
    } else if (command_is(c.s, c.i, "\\")) {
      c.i += 2, column = 0;
    } else {  // \end{...}
      c.i = group_end(c.s, c.i + 4);
      break;
    }
  }
  return std::accumulate(columns.begin(), columns.end(), std::size_t{0}) + 2 * columns.size();
}

std::size_t measure(std::string_view s, bool text) {
  Cursor c{s, 0, text};
  std::size_t w = 0;
  while (c.i < s.size()) {
    w += scan_width(c, false);
    if (c.i < s.size()) ++c.i;  // an unmatched '}'
  }
  return w;
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return s;
}

std::string rewrite_groups(std::string_view s, std::size_t width);

// X as one breakable parenthesized group: X's own \left( ... \right) when that is all of it.
std::string breakable_group(std::string_view x, std::size_t width) {
  x = trimmed(x);
  if (command_is(x, 0, "left") && x.size() > 6 && x[5] == '(' && matching_right(x, 0) + 7 == x.size())
    x = x.substr(6, x.size() - 13);
  return "\\bigl(" + rewrite_groups(x, width) + "\\bigr)";
}

// The first pass of latex_breakable: groups and fractions wider than `width` opened up.
std::string rewrite_groups(std::string_view s, std::size_t width) {
  std::string out;
  std::size_t i = 0;
  while (i < s.size()) {
    if (command_is(s, i, "left") && i + 5 < s.size() && s[i + 5] == '(') {
      const std::size_t close = matching_right(s, i);
      const std::size_t end = std::min(s.size(), close + 7);  // past "\right)"
      const std::string_view inner = s.substr(i + 6, close - std::min(close, i + 6));
      if (measure(inner, false) + 2 > width) out += "\\bigl(" + rewrite_groups(inner, width) + "\\bigr)";
      else out += s.substr(i, end - i);
      i = end;
    } else if (command_is(s, i, "frac") && skip_spaces(s, i + 5) < s.size() && s[skip_spaces(s, i + 5)] == '{') {
      const std::size_t up = skip_spaces(s, i + 5), up_end = group_end(s, up);
      const std::size_t down = skip_spaces(s, up_end);
      if (down >= s.size() || s[down] != '{') {
        out += s.substr(i, up_end - i);
        i = up_end;
        continue;
      }
      const std::size_t down_end = group_end(s, down);
      const std::string_view numerator = s.substr(up + 1, up_end - up - 2), denominator = s.substr(down + 1, down_end - down - 2);
      const std::size_t wn = measure(numerator, false), wd = measure(denominator, false);
      if (std::max(wn, wd) + 1 <= width) out += s.substr(i, down_end - i);
      else if (wd + 1 <= width) out += "\\frac{1}{" + std::string(denominator) + "} " + breakable_group(numerator, width);
      else out += breakable_group(numerator, width) + " \\big/ " + breakable_group(denominator, width);
      i = down_end;
    } else if (s[i] == '{') {
      const std::size_t end = group_end(s, i);
      out += s.substr(i, end - i);
      i = end;
    } else if (s[i] == '\\') {
      const std::size_t end = i + 1 + command_at(s, i).size();
      out += s.substr(i, end - i);
      i = end;
    } else {
      out += s[i++];
    }
  }
  return out;
}

// The second pass: in a run between two outer + - = wider than `width` (a long product), a break
// point between its factors. Braces and \left...\right hold what TeX cannot break anyway.
std::string break_products(const std::string& s, std::size_t width) {
  std::vector<std::size_t> spaces;  // outer spaces of the current run
  std::string out;
  std::size_t run_start = 0;
  auto close_run = [&](std::size_t end) {
    std::string run = s.substr(run_start, end - run_start);
    if (measure(run, false) > width)
      for (auto k = spaces.rbegin(); k != spaces.rend(); ++k) run.insert(*k - run_start, "\\allowbreak");
    out += run;
    spaces.clear();
    run_start = end;
  };
  int depth = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\\') {
      if (command_is(s, i, "left")) ++depth;
      else if (command_is(s, i, "right")) --depth;
      i += command_at(s, i).size();
    } else if (s[i] == '{') {
      ++depth;
    } else if (s[i] == '}') {
      --depth;
    } else if (depth == 0 && s[i] == ' ') {
      const bool operator_next = i + 2 < s.size() && std::string_view("+-=").find(s[i + 1]) != std::string_view::npos &&
                                 s[i + 2] == ' ';
      if (operator_next) {
        close_run(i);
        i += 2;  // the run restarts at the space after the operator
      } else if (i > 0 && s[i - 1] != ' ' && std::string_view("+-=(").find(s[i - 1]) == std::string_view::npos) {
        spaces.push_back(i);
      }
    }
  }
  close_run(s.size());
  return out;
}

// A text cell of a table: escaped, and breakable after the characters that join a long value or
// name, which has no spaces to break at.
std::string latex_cell(std::string_view text) {
  std::string out;
  for (char c : text) {
    out += latex_text(std::string_view(&c, 1));
    if (std::string_view("*/_,=+").find(c) != std::string_view::npos) out += "\\allowbreak{}";
  }
  return out;
}

// The longest stretch of a text cell between two spaces, which no p{} column can break.
std::size_t longest_word(std::string_view text) {
  std::size_t longest = 0;
  for (std::size_t from = 0; from <= text.size();) {
    std::size_t to = text.find(' ', from);
    if (to == std::string_view::npos) to = text.size();
    longest = std::max(longest, measure(text.substr(from, to - from), true));
    from = to + 1;
  }
  return longest;
}

}  // namespace

std::size_t latex_width(std::string_view formula) { return measure(formula, false); }

std::string latex_breakable(std::string_view formula, std::size_t width) {
  return break_products(rewrite_groups(formula, width), width);
}

std::string latex_fitted(const std::string& math) {
  return latex_width(math) <= latex_line_width ? math : latex_breakable(math);
}

std::string latex_display(const std::string& math) {
  if (latex_width(math) <= latex_line_width) return "\\[\n" + math + "\n\\]\n";
  return "\\begin{longformula}\n" + latex_breakable(math) + "\n\\end{longformula}\n";
}

bool latex_matrix_too_wide(const std::string& label, const std::vector<std::vector<std::string>>& m) {
  return latex_width(label + " = " + latex_matrix(m)) > latex_line_width;
}

MatrixEntries latex_matrix_entries(const std::string& label, const std::vector<std::vector<std::string>>& m) {
  bool symmetric = !m.empty();
  for (std::size_t i = 0; i < m.size(); ++i)
    for (std::size_t j = 0; j < m[i].size(); ++j)
      symmetric = symmetric && j < m.size() && i < m[j].size() && m[i][j] == m[j][i];
  MatrixEntries entries{symmetric, {}};
  for (std::size_t i = 0; i < m.size(); ++i)
    for (std::size_t j = symmetric ? i : 0; j < m[i].size(); ++j)
      if (m[i][j] != "0") entries.formulas.push_back(fmt::format("({})_{{{},{}}} = {}", label, i + 1, j + 1, m[i][j]));
  return entries;
}

std::string latex_preamble() {
  return "\\documentclass{article}\n\\usepackage{amsmath,amssymb}\n\\usepackage[margin=2cm,landscape]{geometry}\n"
         "\\usepackage{longtable,array}\n\\setcounter{MaxMatrixCols}{64}\n\\allowdisplaybreaks\n\\sloppy\n"
         "% A formula too wide for one line: inline mathematics, which TeX breaks after an outer + - =,\n"
         "% in a ragged-right paragraph of its own with its continuation lines indented.\n"
         "\\newenvironment{longformula}{\\par\\smallskip\\noindent\\hangindent=2em\\hangafter=1"
         "\\rightskip=0pt plus 1fil$\\displaystyle}{$\\par\\smallskip}\n"
         "\\begin{document}\n";
}

std::string latex_longtable(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                            const std::vector<std::size_t>& widths) {
  std::string columns;
  for (std::size_t w : widths)
    columns += fmt::format(">{{\\raggedright\\arraybackslash}}p{{\\dimexpr {:.3f}\\linewidth-2\\tabcolsep\\relax}}",
                           static_cast<double>(w) / latex_line_width);
  std::string s = "\\begin{longtable}{" + columns + "}\n" + joined(header, " & ") + " \\\\\n\\hline\n\\endhead\n";
  for (const auto& r : rows) s += joined(r, " & ") + " \\\\\n";
  return s + "\\end{longtable}\n";
}

std::vector<std::size_t> latex_column_widths(const std::vector<std::string>& header,
                                             const std::vector<std::vector<std::string>>& rows) {
  // Each column's cells sit between two \tabcolsep (2 x 6 pt, about 2 units). A word of capitals
  // runs to 8.5 pt a character, a third above the unit: a column's natural width allows for that.
  auto roomy = [](std::size_t w) { return w + w / 3 + 2; };
  std::vector<std::size_t> natural, least;
  for (std::size_t k = 0; k < header.size(); ++k) {
    std::size_t widest = measure(header[k], true);
    for (const auto& r : rows)
      if (k < r.size()) widest = std::max(widest, measure(r[k], true));
    natural.push_back(roomy(widest));
    least.push_back(roomy(longest_word(header[k])));
  }
  if (std::accumulate(natural.begin(), natural.end(), std::size_t{0}) <= latex_line_width) return natural;
  // Narrowest first: a column that needs less than an equal share of what is left keeps its width.
  std::vector<std::size_t> order(header.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return natural[a] < natural[b]; });
  std::vector<std::size_t> widths(header.size());
  std::size_t left = latex_line_width;
  for (std::size_t n = 0; n < order.size(); ++n) {
    const std::size_t k = order[n], share = left / (order.size() - n);
    widths[k] = std::max(least[k], std::min(natural[k], share));
    left -= std::min(left, widths[k]);
  }
  return widths;
}

std::string latex_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::string> head;
  for (const auto& h : header) head.push_back(latex_text(h));
  std::vector<std::vector<std::string>> cells;
  for (const auto& r : rows) {
    cells.emplace_back();
    for (const auto& c : r) cells.back().push_back(latex_cell(c));
  }
  return latex_longtable(head, cells, latex_column_widths(head, cells)) + "\n";
}

}  // namespace pogear
