// The LaTeX layout of the reports (common/latex_layout): what the width estimate counts, wide
// groups and fractions made breakable, a matrix too wide for the page listed entry by entry. The
// reports that `pogear` writes, compiled with pdflatex: tests/commands/latex_test.cpp.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/latex_layout.hpp"

namespace pogear::test {
namespace {

// The width estimate counts what prints: a fraction its wider part, a matrix its widest entries.
TEST(LatexLayout, WidthCountsWhatPrints) {
  EXPECT_EQ(latex_width("J_{c} + \\frac{J_{p} r_{c}^{2}}{r_{p}^{2}}"), 10u);  // J c, +, J p r c 2
  EXPECT_EQ(latex_width("\\mathbf{R} = \\begin{bmatrix}\n  r_{s} & -r_{p} \\\\\n  0 & r_{r} \\\\\n\\end{bmatrix}"), 13u);
  EXPECT_EQ(latex_width("\\left(\\omega_{c}\\right)"), 4u);
  EXPECT_EQ(latex_width("\\text{(mesh ps)}"), 9u);  // a space in text counts
}

// What fits is left alone; a group or fraction wider than the width opens up for TeX to break.
TEST(LatexLayout, WideGroupsAndFractionsBecomeBreakable) {
  const std::string narrow = "\\frac{J_{p}}{r_{p}^{2}} \\left(a + b\\right)";
  EXPECT_EQ(latex_breakable(narrow, 20), narrow);
  EXPECT_EQ(latex_breakable("c \\left(a_{1} + a_{2} + a_{3} + a_{4}\\right)^{2}", 10),
            "c \\bigl(a_{1} + a_{2} + a_{3} + a_{4}\\bigr)^{2}");
  EXPECT_EQ(latex_breakable("\\frac{\\left(a_{1} + a_{2} + a_{3} + a_{4}\\right)}{r_{p}}", 10),
            "\\frac{1}{r_{p}} \\bigl(a_{1} + a_{2} + a_{3} + a_{4}\\bigr)");
  EXPECT_EQ(latex_breakable("\\frac{a_{1} + a_{2} + a_{3}}{b_{1} + b_{2} + b_{3}}", 10),
            "\\bigl(a_{1} + a_{2} + a_{3}\\bigr) \\big/ \\bigl(b_{1} + b_{2} + b_{3}\\bigr)");
  // A product wider than the width may break between its factors.
  EXPECT_EQ(latex_breakable("x + J_{a} J_{b} J_{c} J_{d} J_{e} J_{f}", 10),
            "x + J_{a}\\allowbreak J_{b}\\allowbreak J_{c}\\allowbreak J_{d}\\allowbreak J_{e}\\allowbreak J_{f}");
}

TEST(LatexLayout, ASymmetricMatrixListsItsEntriesOnAndAboveTheDiagonal) {
  const MatrixEntries s = latex_matrix_entries("\\mathbf{L}_1", {{"a", "b"}, {"b", "0"}});
  EXPECT_TRUE(s.symmetric);
  EXPECT_EQ(s.formulas, (std::vector<std::string>{"(\\mathbf{L}_1)_{1,1} = a", "(\\mathbf{L}_1)_{1,2} = b"}));
  const MatrixEntries r = latex_matrix_entries("\\mathbf{R}", {{"a", "0", "c"}});
  EXPECT_FALSE(r.symmetric);
  EXPECT_EQ(r.formulas, (std::vector<std::string>{"(\\mathbf{R})_{1,1} = a", "(\\mathbf{R})_{1,3} = c"}));
}

}  // namespace
}  // namespace pogear::test
