// pogear's own expression printer. GiNaC orders terms by hash, and its hashes change from run to
// run, so everything pogear writes goes through this walk that orders sums and products stably.
#pragma once

#include <string>
#include <vector>
#include <string_view>

#include <ginac/ginac.h>

namespace pogear {

enum class Notation {
  ginac,  // GiNaC's input syntax: `J_c+J_p*r_c^2/r_p^2`; parses back with GiNaC::parser
  text,   // the same with spaces, for terminals: `J_c + J_p*r_c^2/r_p^2`
  latex,  // amsmath: `J_{c} + \frac{J_{p} r_{c}^{2}}{r_{p}^{2}}`
  cpp,    // C++ with doubles: small integer powers as products, `1.0/(...)`
};

std::string print_expression(const GiNaC::ex& e, Notation notation);
// The same, with the symbols `printed_last` (the equations' variables) after every other factor of a
// product, as the paper writes J_p r_r1 domega_r; the two print alike where none of them occurs.
std::string print_expression(const GiNaC::ex& e, Notation notation, const GiNaC::exset& printed_last);

// `omega_c` -> `\omega_{c}`, `r_s1` -> `r_{s1}`, `domega_c` -> `\dot{\omega}_{c}`.
std::string latex_symbol(const std::string& name);

// Text for LaTeX's text mode (a title, a body's name in \text{}): every character LaTeX gives a
// meaning (\ { } $ & % # _ ^ ~) written so that it prints as itself.
std::string latex_text(std::string_view text);
// Text for Markdown (a title, a name): no HTML, math, emphasis or link it could start renders.
std::string markdown_text(std::string_view text);

// Shortest decimal that reads back as the same double, always with a '.' or an exponent.
std::string cpp_double(double v);

// The items with `separator` between them: "c, r".
std::string joined(const std::vector<std::string>& v, std::string_view separator = ", ");

// Matrices of printed entries: "label =" and bracketed rows for terminals; amsmath's bmatrix.
std::string text_matrix(const std::string& label, const std::vector<std::vector<std::string>>& m);
std::string latex_matrix(const std::vector<std::vector<std::string>>& m);
std::string latex_vector(const std::vector<std::string>& v);

// A table of plain text cells (names, values as written), each cell escaped for Markdown; LaTeX's
// is latex_table (latex_layout.hpp), which fits the page.
std::string markdown_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);

// A measured or computed number for a report line: 6 significant digits (the eigenproblems and
// ratios behind them hold ~8), and -0 written as 0.
std::string six_digits(double v);

}  // namespace pogear
