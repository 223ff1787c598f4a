// The printer: the paper's term order, stable signs whatever form GiNaC returns, and notations.
#include "common/printer.hpp"

#include <gtest/gtest.h>

#include "../support/files.hpp"
#include "derive/derivation.hpp"
#include "report/report.hpp"

namespace pogear::test {
namespace {

using GiNaC::ex;
using GiNaC::realsymbol;

TEST(Printer, SumsReadLikeThePaper) {
  realsymbol Jc("J_c"), Jp("J_p"), rc("r_c"), rp("r_p");
  const ex e = Jp * pow(rc, 2) / pow(rp, 2) + Jc;
  EXPECT_EQ(print_expression(e, Notation::ginac), "J_c+J_p*r_c^2/r_p^2");
  EXPECT_EQ(print_expression(e, Notation::text), "J_c + J_p*r_c^2/r_p^2");
  EXPECT_EQ(print_expression(e, Notation::latex), "J_{c} + \\frac{J_{p} r_{c}^{2}}{r_{p}^{2}}");
  EXPECT_EQ(print_expression(e, Notation::cpp), "J_c + J_p*r_c*r_c/(r_p*r_p)");
}

// The variables print after the parameters because the caller says which symbols they are, not
// because of their names: a parameter named omega_0 is a parameter, ordered by its name.
TEST(Printer, VariablesPrintLastBecauseTheCallerSaysSo) {
  realsymbol Jp("J_p"), omega0("omega_0"), z("z_a"), domega("domega_r");
  EXPECT_EQ(print_expression(Jp * omega0 * z, Notation::ginac), "J_p*omega_0*z_a");
  EXPECT_EQ(print_expression(Jp * omega0 * z, Notation::ginac, {Jp}), "omega_0*z_a*J_p");
  EXPECT_EQ(print_expression(Jp * domega * z, Notation::ginac, {domega}), "J_p*z_a*domega_r");
  EXPECT_EQ(print_expression(Jp * domega * z, Notation::ginac), "J_p*domega_r*z_a");
}

TEST(Printer, SignOfASumFactorIsCanonical) {
  realsymbol a("a"), b("b"), c("c");
  // The same value written two ways, as GiNaC's normal() may return either.
  const ex one = (a - 2 * b) / c;
  const ex other = -(2 * b - a) / c;
  EXPECT_EQ(print_expression(one, Notation::ginac), print_expression(other, Notation::ginac));
  EXPECT_EQ(print_expression(pow(2 * b - a, 2), Notation::ginac), print_expression(pow(a - 2 * b, 2), Notation::ginac));
}

TEST(Printer, NumbersAndRationals) {
  realsymbol x("x");
  EXPECT_EQ(print_expression(x / 2, Notation::ginac), "x/2");
  EXPECT_EQ(print_expression(x / 2, Notation::latex), "\\frac{x}{2}");
  // C++ gets one correctly rounded coefficient, never a quotient of two long integers.
  EXPECT_EQ(print_expression(x / 2, Notation::cpp), "0.5*x");
  EXPECT_EQ(print_expression(x / 3, Notation::cpp), "0.3333333333333333*x");
  EXPECT_EQ(print_expression(ex(-3), Notation::ginac), "-3");
  EXPECT_EQ(print_expression(1 / x, Notation::ginac), "1/x");
}

TEST(Printer, LatexSymbols) {
  EXPECT_EQ(latex_symbol("omega_c"), "\\omega_{c}");
  EXPECT_EQ(latex_symbol("domega_r"), "\\dot{\\omega}_{r}");
  EXPECT_EQ(latex_symbol("r_s1"), "r_{s1}");
  EXPECT_EQ(latex_symbol("F_ps"), "F_{ps}");
  EXPECT_EQ(latex_symbol("tau_c"), "\\tau_{c}");
}

TEST(Printer, CppDoublesReadBackExactly) {
  for (double v : {0.1, 1.0 / 3.0, 1e-300, 123456789.0, 2.0}) {
    const std::string s = cpp_double(v);
    EXPECT_EQ(std::stod(s), v) << s;
    EXPECT_NE(s.find_first_of(".e"), std::string::npos) << s;
  }
}

}  // namespace
}  // namespace pogear::test

namespace pogear::test {
namespace {

TEST(LatexText, EverySpecialCharacterPrintsAsItself) {
  EXPECT_EQ(latex_text("inertias in kg*m^2"), "inertias in kg*m\\textasciicircum{}2");
  EXPECT_EQ(latex_text("mg_2 & 100% #1 {x} $5 ~a \\b"),
            "mg\\_2 \\& 100\\% \\#1 \\{x\\} \\$5 \\textasciitilde{}a \\textbackslash{}b");
  EXPECT_EQ(latex_text("plain text, 1.5 (ok)"), "plain text, 1.5 (ok)");
}

TEST(LatexText, TitleAndNamesOfALatexReportAreEscaped) {
  // The title a user wrote and a mesh named with '_' (which reaches \text{} in the geometry lines).
  std::string model = read_text(source_path("tests/errors/gear.toml"));
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto pos = model.find(from);
    ASSERT_NE(pos, std::string::npos) << from;
    model.replace(pos, from.size(), to);
  };
  replace("name = \"gear\"", "name = \"gear\"\ntitle = \"inertias in kg*m^2, 50% & more\"");
  replace("first = \"p\"\nsecond = \"s1\"\n", "first = \"p\"\nsecond = \"s1\"\nname = \"p_s\"\n");
  replace("K_ps = \"1000*Newton/mm\"", "K_p_s = \"1000*Newton/mm\"\nK_ps = \"K_p_s\"");
  replace("b_ps = \"0.4*Newton*s/cm\"", "b_p_s = \"0.4*Newton*s/cm\"\nb_ps = \"b_p_s\"");
  const Derivation d = derive_topology(parse_topology_text(model, "gear.toml"), std::nullopt, SourceLocation{"gear.toml", 0, 0});
  const std::string tex = report_latex(d, derivation_diagnostics(d));
  EXPECT_NE(tex.find("\\section*{gear: inertias in kg*m\\textasciicircum{}2, 50\\% \\& more}"), std::string::npos) << tex;
  EXPECT_NE(tex.find("\\text{(mesh p\\_s)}"), std::string::npos) << tex;
}

// A Markdown viewer renders raw HTML, $ math, emphasis and links: a title shows as written.
TEST(MarkdownText, EverySpecialCharacterShowsAsItself) {
  EXPECT_EQ(markdown_text("<img src=x onerror=alert(1)> $\\int$ *a* _b_ [l](u) `c` a|b ~~s~~ #1 \\ & x"),
            "&lt;img src=x onerror=alert(1)&gt; \\$\\\\int\\$ \\*a\\* \\_b\\_ \\[l\\](u) \\`c\\` a\\|b "
            "\\~\\~s\\~\\~ \\#1 \\\\ &amp; x");
  EXPECT_EQ(markdown_text("plain text, 1.5 (ok) - yes!"), "plain text, 1.5 (ok) - yes!");
  EXPECT_EQ(markdown_text("two\nlines"), "two lines");
}

TEST(MarkdownText, TitleOfAMarkdownReportIsEscaped) {
  std::string model = read_text(source_path("tests/errors/gear.toml"));
  const auto pos = model.find("name = \"gear\"");
  ASSERT_NE(pos, std::string::npos);
  model.insert(pos + std::string("name = \"gear\"").size(), "\ntitle = \"<b>bold</b> $x^2$ *em*\"");
  const Derivation d = derive_topology(parse_topology_text(model, "gear.toml"), std::nullopt, SourceLocation{"gear.toml", 0, 0});
  const std::string md = report_markdown(d, derivation_diagnostics(d));
  EXPECT_EQ(md.substr(0, md.find('\n')), "# gear: &lt;b&gt;bold&lt;/b&gt; \\$x^2\\$ \\*em\\*") << md;
}

}  // namespace
}  // namespace pogear::test
