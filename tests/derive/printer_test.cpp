// The printer: the paper's term order, stable signs whatever form GiNaC returns, and notations.
#include "printer.hpp"

#include <gtest/gtest.h>

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
