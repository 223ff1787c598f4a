// How pogear's LaTeX documents fit their landscape page: a width estimate of formulas, formulas
// rewritten so that TeX can break them, matrices entry by entry, tables that wrap and run over pages.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace pogear {

// The line of every report (landscape letter paper, 2 cm margins: 681 pt) in latex_width's unit,
// taken as 6.5 pt. On the shipped models' reports a unit of a displayed formula came to 3.8 pt
// (long sums) to 6.3 pt (short formulas of matrices), so a formula the estimate fits does fit.
inline constexpr std::size_t latex_line_width = 104;

// A deterministic estimate of the printed width of a formula (or of text), in characters:
// a letter, digit or a command such as \omega counts one, a binary operator or relation two (its
// spacing), \frac its wider part, a matrix the sum of its widest entries per column; braces, scripts'
// markers and sizing commands (\left, \bigl, \displaystyle) nothing. Subscripts count in full, so
// the estimate errs wide.
std::size_t latex_width(std::string_view formula);

// The formula so written that, as inline mathematics, TeX can break it into lines of `width`: a
// parenthesized group wider than that loses \left...\right (which TeX cannot break inside) for
// \bigl...\bigr, a fraction with a wider numerator or denominator is written as a factor 1/D or a
// quotient of breakable groups, and a product wider than that may break between its factors.
// Whatever fits is left as it is.
std::string latex_breakable(std::string_view formula, std::size_t width = latex_line_width * 3 / 4);

// The formula as LaTeX displays it: \[ ... \] when it fits the line, else the `longformula`
// environment of latex_preamble (inline mathematics in a paragraph of its own) with the formula
// made breakable. latex_fitted is the mathematics that display holds.
std::string latex_fitted(const std::string& math);
std::string latex_display(const std::string& math);

// Whether a matrix of printed entries, written `label = [...]`, is wider than the line: the
// reports then list its entries instead (latex_matrix_entries).
bool latex_matrix_too_wide(const std::string& label, const std::vector<std::vector<std::string>>& m);
// Its nonzero entries as formulas `(label)_{i,j} = entry`, row by row; of a symmetric matrix only
// those on and above the diagonal.
struct MatrixEntries {
  bool symmetric = false;
  std::vector<std::string> formulas;
};
MatrixEntries latex_matrix_entries(const std::string& label, const std::vector<std::vector<std::string>>& m);

// Everything from \documentclass to \begin{document} that every LaTeX document of pogear shares:
// amsmath, geometry, longtable and array (texlive-latex-base), \sloppy text, the longformula
// environment.
std::string latex_preamble();

// A longtable with a header row repeated on every page. Cells are LaTeX already; each column is a
// ragged-right p{} column, `widths` in latex_width's unit (latex_column_widths).
std::string latex_longtable(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                            const std::vector<std::size_t>& widths);
// Widths that fit the line: each column as wide as its widest cell while all fit, else the widest
// columns narrowed to an equal share of what the others leave, none below its header's longest word.
std::vector<std::size_t> latex_column_widths(const std::vector<std::string>& header,
                                             const std::vector<std::vector<std::string>>& rows);
// A table of plain text cells (names, values as written): escaped, with break points after the
// characters that join a long value (`*`, `/`, `_`, ...), in columns of latex_column_widths.
std::string latex_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);

}  // namespace pogear
