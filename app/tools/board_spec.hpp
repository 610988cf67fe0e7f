// The calibration board as `rovctl calibrate --board` names it: chessboard:COLSxROWS:SQUARE_MM.
#pragma once

#include <string>

namespace rovctl::app {

struct BoardSpec {
  int inner_cols = 0;  // inner corners along a row
  int inner_rows = 0;  // inner corners along a column
  double square_m = 0.0;
};

// Throws std::invalid_argument naming the text and what does not parse.
BoardSpec parse_board_spec(const std::string& text);

}  // namespace rovctl::app
