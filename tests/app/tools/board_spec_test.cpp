// The --board spec: what parses, and each way it does not, named.
#include "app/tools/board_spec.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace rovctl::app {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_board_spec(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(BoardSpec, ParsesInnerCornersAndSquareInMillimetres) {
  const BoardSpec b = parse_board_spec("chessboard:9x6:25.5");
  EXPECT_EQ(b.inner_cols, 9);
  EXPECT_EQ(b.inner_rows, 6);
  EXPECT_DOUBLE_EQ(b.square_m, 0.0255);
}

TEST(BoardSpec, EachMistakeIsNamed) {
  EXPECT_NE(error_of("charuco:9x6:25").find("unknown board kind 'charuco'"), std::string::npos);
  EXPECT_NE(error_of("chessboard:9x6").find("three fields"), std::string::npos);
  EXPECT_NE(error_of("chessboard:9by6:25").find("not COLSxROWS"), std::string::npos);
  EXPECT_NE(error_of("chessboard:9x2:25").find("3..100"), std::string::npos);
  EXPECT_NE(error_of("chessboard:9x6:25mm").find("square size '25mm'"), std::string::npos);
  EXPECT_NE(error_of("chessboard:9x6:0").find("square size"), std::string::npos);
  EXPECT_NE(error_of("chessboard:9x6:25:1").find("three fields"), std::string::npos);
  EXPECT_NE(error_of("chessboard:-9x6:25").find("whole numbers"), std::string::npos);
}

}  // namespace
}  // namespace rovctl::app
