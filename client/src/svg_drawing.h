// SvgDrawing: curves and control polygons as an SVG picture (for the CLI's
// --svg output). Points of any dimension are drawn by their first two
// coordinates, fitted into the picture with y pointing up. Not thread-safe.
#ifndef FREEFORM_CLIENT_SVG_DRAWING_H_
#define FREEFORM_CLIENT_SVG_DRAWING_H_

#include <ostream>
#include <string>
#include <vector>

#include "absl/types/span.h"

namespace freeform::cli {

class SvgDrawing {
 public:
  struct Style {
    std::string color = "black";
    double width = 1.5;
    bool dashed = false;
    bool dots = false;  // mark every point
    bool closed = false;
  };

  // AddPolyline draws the points (dimension coordinates each) in order.
  void AddPolyline(absl::Span<const double> points, int dimension,
                   const Style& style);

  // Write prints the picture, `size` pixels wide.
  void Write(std::ostream& out, double size = 800) const;

 private:
  struct Polyline {
    std::vector<double> xy;
    Style style;
  };
  std::vector<Polyline> polylines_;
};

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_SVG_DRAWING_H_
