// Number parsing and fixed-width formatting of deck text (src/io/text_scan.h).
#include "io/text_scan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace voxremesh::io;

TEST(ParseReal, AcceptsTheFormsSolversWrite) {
  double v = 0;
  ASSERT_TRUE(parseReal("  1.5  ", v));
  EXPECT_EQ(v, 1.5);
  ASSERT_TRUE(parseReal("1.-3", v));
  EXPECT_DOUBLE_EQ(v, 1e-3);
  ASSERT_TRUE(parseReal("-2.5+2", v));
  EXPECT_DOUBLE_EQ(v, -250.0);
  ASSERT_TRUE(parseReal("1.5D+3", v));
  EXPECT_DOUBLE_EQ(v, 1500.0);
  ASSERT_TRUE(parseReal("+.5", v));
  EXPECT_DOUBLE_EQ(v, 0.5);
  ASSERT_TRUE(parseReal("7.", v));
  EXPECT_DOUBLE_EQ(v, 7.0);
  ASSERT_TRUE(parseReal("1.e+06", v));
  EXPECT_DOUBLE_EQ(v, 1e6);
  ASSERT_TRUE(parseReal("", v, 3.0));
  EXPECT_EQ(v, 3.0);
}

TEST(ParseReal, RejectsWhatIsNotANumber) {
  double v = 0;
  EXPECT_FALSE(parseReal("abc", v));
  EXPECT_FALSE(parseReal("1.5x", v));
  EXPECT_FALSE(parseReal("1.5 2.5", v));
  EXPECT_FALSE(parseReal("--1", v));
  EXPECT_FALSE(parseReal("1e", v));
  EXPECT_FALSE(parseReal("e5", v));
}

TEST(ParseInt, AcceptsBlanksAndSignsRejectsReals) {
  std::int64_t v = 0;
  ASSERT_TRUE(parseInt("   434225", v));
  EXPECT_EQ(v, 434225);
  ASSERT_TRUE(parseInt("+12 ", v));
  EXPECT_EQ(v, 12);
  ASSERT_TRUE(parseInt("9000000000000", v));
  EXPECT_EQ(v, 9000000000000);
  EXPECT_FALSE(parseInt("1.5", v));
  EXPECT_FALSE(parseInt("12a", v));
  ASSERT_TRUE(parseInt("", v, -1));
  EXPECT_EQ(v, -1);
}

TEST(AppendRealFixedWidth, FitsTheFieldAndKeepsTheMostDigits) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-12, 12);
  for (int i = 0; i < 20000; ++i) {
    const double value = mantissa(random) * std::pow(10.0, exponent(random));
    for (int width : {16, 20}) {
      std::string out;
      appendRealFixedWidth(out, value, width);
      ASSERT_EQ(out.size(), static_cast<std::size_t>(width)) << out;
      double back = 0;
      ASSERT_TRUE(parseReal(out, back)) << out;
      // 16 columns keep at least 10 significant digits in any of these magnitudes.
      EXPECT_LE(std::fabs(back - value), 1e-9 * std::fabs(value) + 1e-300) << out;
    }
  }
}

TEST(AppendRealFixedWidth, ExtremesAndNarrowFieldsFit) {
  for (double value : {0.0, -0.0, 1e-300, -1e-300, 1e300, -1.2e300, 4.9e-324, 123456789012345.0,
                       -99999999.5, 0.009999999999999, 1.0 / 3.0}) {
    for (int width : {8, 10, 16, 20}) {
      std::string out;
      appendRealFixedWidth(out, value, width);
      ASSERT_EQ(out.size(), static_cast<std::size_t>(width)) << value << " -> '" << out << "'";
      double back = 0;
      ASSERT_TRUE(parseReal(out, back)) << out;
      EXPECT_LE(std::fabs(back - value), std::fabs(value) * (width <= 8 ? 0.2 : 1e-3)) << out;
    }
  }
}

TEST(LineCursor, NumbersLinesAndKeepsRawTerminators) {
  LineCursor cursor("a\r\nb\n\nc");
  ASSERT_TRUE(cursor.next());
  EXPECT_EQ(cursor.line(), "a");
  EXPECT_EQ(cursor.rawLine(), "a\r\n");
  ASSERT_TRUE(cursor.next());
  EXPECT_EQ(cursor.line(), "b");
  EXPECT_EQ(cursor.lineNumber(), 2u);
  cursor.pushBack();
  ASSERT_TRUE(cursor.next());
  EXPECT_EQ(cursor.line(), "b");
  ASSERT_TRUE(cursor.next());
  EXPECT_EQ(cursor.line(), "");
  ASSERT_TRUE(cursor.next());
  EXPECT_EQ(cursor.line(), "c");
  EXPECT_EQ(cursor.lineNumber(), 4u);
  EXPECT_FALSE(cursor.next());
}
