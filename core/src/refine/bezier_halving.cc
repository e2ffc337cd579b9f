#include "refine/bezier_halving.h"

#include <array>
#include <cstddef>
#include <vector>

#include "freeform/core/triangular.h"

namespace freeform::internal {
namespace {

// HalveLine halves the Bezier line of m + 1 points `line` (point a at
// line + a * step, `width` values each) at 1/2 into `left` and `right`
// (same layout). The in-place de Casteljau levels run in `right`: after
// level r, right[a] is P^r_a for a <= m - r, and the last point of each
// level, P^r_{m-r}, is the right half's point m - r; left[r] is P^r_0.
// The midpoint is taken as 0.5 a + 0.5 b, which cannot overflow where the
// points are finite.
void HalveLine(const double* line, size_t step, int m, int width, double* left,
               double* right) {
  const size_t w = static_cast<size_t>(width);
  for (int a = 0; a <= m; ++a) {
    const double* from = line + static_cast<size_t>(a) * step;
    double* to = right + static_cast<size_t>(a) * step;
    for (size_t c = 0; c < w; ++c) to[c] = from[c];
  }
  for (size_t c = 0; c < w; ++c) left[c] = line[c];
  for (int r = 1; r <= m; ++r) {
    for (int a = 0; a <= m - r; ++a) {
      double* point = right + static_cast<size_t>(a) * step;
      const double* next = point + step;
      for (size_t c = 0; c < w; ++c) {
        point[c] = 0.5 * point[c] + 0.5 * next[c];
      }
    }
    double* to = left + static_cast<size_t>(r) * step;
    for (size_t c = 0; c < w; ++c) to[c] = right[c];
  }
}

}  // namespace

void HalveNet(const double* values, int count_u, int count_v, int width,
              bool in_u, double* first, double* second) {
  const size_t w = static_cast<size_t>(width);
  const size_t row = static_cast<size_t>(count_v) * w;
  if (in_u) {
    for (int b = 0; b < count_v; ++b) {
      const size_t offset = static_cast<size_t>(b) * w;
      HalveLine(values + offset, row, count_u - 1, width, first + offset,
                second + offset);
    }
    return;
  }
  for (int a = 0; a < count_u; ++a) {
    const size_t offset = static_cast<size_t>(a) * row;
    HalveLine(values + offset, w, count_v - 1, width, first + offset,
              second + offset);
  }
}

void BisectTriangle(const double* values, int n, int width, int edge,
                    double* first, double* second, std::vector<double>& row) {
  const size_t w = static_cast<size_t>(width);
  const size_t line = (static_cast<size_t>(n) + 1) * w;
  row.resize(3 * line);
  double* gathered = row.data();
  double* left = gathered + line;
  double* right = left + line;
  // The other two vertices, a < b.
  const int a = edge == 0 ? 1 : 0;
  const int b = edge == 2 ? 1 : 2;
  // Point with exponents e[0], e[1], e[2] of the three vertices.
  auto index = [n](const std::array<int, 3>& e) {
    return TriangularIndex(n, e[0], e[1]);
  };
  for (int i = 0; i <= n; ++i) {  // the exponent of vertex `edge`
    const int m = n - i;
    std::array<int, 3> e{};
    e[static_cast<size_t>(edge)] = i;
    // Row point x has exponent x of vertex a and m - x of b: the Bezier
    // curve from b (x = 0) to a (x = m).
    for (int x = 0; x <= m; ++x) {
      e[static_cast<size_t>(a)] = x;
      e[static_cast<size_t>(b)] = m - x;
      const double* from = values + index(e) * w;
      for (size_t c = 0; c < w; ++c)
        gathered[static_cast<size_t>(x) * w + c] = from[c];
    }
    HalveLine(gathered, w, m, width, left, right);
    // The half near b (left) is the piece with M in place of a, whose
    // exponent of M is x: the same storage position; likewise the half
    // near a (right) with M in place of b, whose exponent of M is m - x.
    for (int x = 0; x <= m; ++x) {
      e[static_cast<size_t>(a)] = x;
      e[static_cast<size_t>(b)] = m - x;
      const size_t k = index(e) * w;
      for (size_t c = 0; c < w; ++c) {
        first[k + c] = left[static_cast<size_t>(x) * w + c];
        second[k + c] = right[static_cast<size_t>(x) * w + c];
      }
    }
  }
}

}  // namespace freeform::internal
