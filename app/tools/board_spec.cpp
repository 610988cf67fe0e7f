// Parses the board spec strictly: a typo in the square size scales the baseline, so nothing is
// guessed.
#include "app/tools/board_spec.hpp"

#include <cstdlib>
#include <stdexcept>

namespace rovctl::app {
namespace {

[[noreturn]] void fail(const std::string& text, const std::string& what) {
  throw std::invalid_argument("--board '" + text + "': " + what +
                              " (expected chessboard:COLSxROWS:SQUARE_MM, e.g. "
                              "chessboard:9x6:25, counting inner corners)");
}

// A whole decimal number in [min, max], or -1.
int whole(const std::string& s, int min, int max) {
  if (s.empty() || s.size() > 4 || s.find_first_not_of("0123456789") != std::string::npos)
    return -1;
  const int v = std::atoi(s.c_str());
  return v >= min && v <= max ? v : -1;
}

}  // namespace

BoardSpec parse_board_spec(const std::string& text) {
  const std::size_t c1 = text.find(':');
  const std::size_t c2 = c1 == std::string::npos ? c1 : text.find(':', c1 + 1);
  if (c2 == std::string::npos || text.find(':', c2 + 1) != std::string::npos)
    fail(text, "not three fields separated by ':'");
  if (text.substr(0, c1) != "chessboard")
    fail(text, "unknown board kind '" + text.substr(0, c1) + "' (supported: chessboard)");
  const std::string size = text.substr(c1 + 1, c2 - c1 - 1);
  const std::size_t x = size.find('x');
  if (x == std::string::npos) fail(text, "size '" + size + "' is not COLSxROWS");
  BoardSpec spec;
  spec.inner_cols = whole(size.substr(0, x), 3, 100);
  spec.inner_rows = whole(size.substr(x + 1), 3, 100);
  if (spec.inner_cols < 0 || spec.inner_rows < 0)
    fail(text, "size '" + size + "': COLS and ROWS must be whole numbers of inner corners, 3..100");
  const std::string square = text.substr(c2 + 1);
  char* end = nullptr;
  const double square_mm = std::strtod(square.c_str(), &end);
  if (square.empty() || end != square.c_str() + square.size() || !(square_mm >= 1.0) ||
      !(square_mm <= 1000.0))
    fail(text, "square size '" + square + "' is not a number of millimetres in [1, 1000]");
  spec.square_m = square_mm / 1000.0;
  return spec;
}

}  // namespace rovctl::app
